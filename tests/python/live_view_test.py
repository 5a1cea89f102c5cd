"""comply run --foxglove and comply.Sim(foxglove=...): a viewer (tests/viewer/node_viewer.mjs, Foxglove's own client and ROS 2
deserializer run by Node) watching while Python steps the Sim receives its state, cycle records,
commands, outcomes and transforms; while it watches the episode keeps to real time (never ahead
of the wall clock); a bad address is refused naming what is wrong.

    live_view_test.py COMPLY SOURCE_DIR
"""

import json
import subprocess
import sys
import time

import numpy as np

import comply

comply_cli, source = sys.argv[1], sys.argv[2]
config = f"{source}/config/sim/cartesian_impedance.yaml"


def watch(url, duration_ms, *topics):
    """A viewer of its own process: what it decoded, per topic, when it is done."""
    return subprocess.Popen(
        ["node", "--experimental-websocket", "--no-warnings",
         f"{source}/tests/viewer/node_viewer.mjs", url, str(duration_ms), *topics],
        stdout=subprocess.PIPE, text=True)


# comply run: the live host serves its state and its diagnostics.
host = subprocess.Popen([comply_cli, "run", "--sim", "--config", config, "--duration", "4",
                         "--transport", "in_process", "--foxglove", "127.0.0.1:0"],
                        stdout=subprocess.PIPE, text=True)
line = host.stdout.readline()
while "Foxglove live view on" not in line:
    assert line, "comply run ended without serving a live view"
    line = host.stdout.readline()
run_viewer = watch(line.split()[-1], 2000, "/comply/state", "/comply/diagnostics", "/tf")
run_counts = json.loads(run_viewer.communicate()[0])
summary = host.communicate()[0]
assert host.returncode == 0, summary
print(f"comply run: the viewer decoded {run_counts}")
assert run_counts["/comply/state"] > 100 and run_counts["/comply/diagnostics"] >= 1, run_counts
assert run_counts["/tf"] > 10, run_counts
assert "live view: " in summary and " 0 dropped" in summary, summary

try:
    comply.Sim(config, robot="fr3", foxglove="127.0.0.1:x")
    raise AssertionError("a port that is not a number was accepted")
except ValueError as error:
    assert "port must be a number" in str(error), error
assert comply.Sim(config, robot="fr3").foxglove_url is None

sim = comply.Sim(config, robot="fr3", steps_per_action=20, foxglove="127.0.0.1:0")
url = sim.foxglove_url
assert url.startswith("ws://127.0.0.1:") and not url.endswith(":0"), url
obs = sim.reset()
viewer = watch(url, 3000, "/comply/state", "/comply/cycle", "/comply/outcome",
               "/comply/cartesian_command", "/tf")
start = obs["tcp_position"].copy()
deadline = time.monotonic() + 30.0
while not sim.foxglove_viewing:  # the viewer starting up (Node, its bundle)
    assert viewer.poll() is None and time.monotonic() < deadline, "the viewer never connected"
    time.sleep(0.01)
steps = 0
paced = []  # (simulated, wall) seconds of each step taken while the viewer watched
while viewer.poll() is None:
    watching = sim.foxglove_viewing
    wall = time.monotonic()
    before = obs["time"]
    target = start + np.array([0.0, 0.03 * np.sin(0.5 * obs["time"]), 0.0])
    obs, _, _, _, info = sim.step({"position": target})
    assert info["accepted"], info
    if watching and sim.foxglove_viewing:
        paced.append((obs["time"] - before, time.monotonic() - wall))
    steps += 1
counts = json.loads(viewer.stdout.read())
print(f"comply.Sim: {steps} steps, simulated {obs['time']:.2f} s; the viewer decoded {counts}")
assert counts["/comply/state"] > 100, counts
assert counts["/comply/cycle"] > 100, counts
assert counts["/comply/outcome"] > 20 and counts["/comply/cartesian_command"] > 20, counts
assert counts["/tf"] > 10, counts
# While the viewer watched, the steps kept to the wall clock (never ahead of it); unwatched, the
# Sim runs as fast as it can.
simulated = sum(s for s, _ in paced)
wall = sum(w for _, w in paced)
print(f"comply.Sim: {len(paced)} steps watched: {simulated:.2f} s simulated in {wall:.2f} s")
assert len(paced) > 20 and simulated <= wall * 1.02 + 0.03, (len(paced), simulated, wall)
print("ok")
