"""record= on comply.Sim and comply.Client, read back with comply.read_recording: the Sim's
episodes (every cycle, the commands sent, one outcome each, the state the Sim returned; the Sim
waits for a busy disk rather than drop; a timing record per chunk), its episodes exported as a
LeRobot dataset (`comply export`), and what a client sent to and saw from a `comply run --sim`
host. A record= path in a missing folder is refused, and the folder not made. Usage:
test_recording_hosts.py COMPLY_CLI SOURCE_DIR (the build's python/ on PYTHONPATH)."""

import json
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

import comply

STEPS = 6  # per episode
STEPS_PER_ACTION = 20
EPISODES = 2
REJECTED_STEP = 3  # in every episode: a command with invalid gains


def constant(topic, name):
    """A constant of the topic's message definition, as the file itself holds it."""
    text = topic.schema.data.decode()
    return int(re.search(rf"\b{name}=(\d+)", text).group(1))


def stamps(topic, field):
    """A builtin_interfaces/Time column as int64 nanoseconds."""
    return topic[f"{field}.sec"].astype(np.int64) * 10**9 + topic[f"{field}.nanosec"]


def config_stiffness(source):
    """The controller's translational stiffness (isotropic) as CycleRecord holds it: 3x3, row
    major."""
    with open(f"{source}/config/sim/cartesian_impedance.yaml") as file:
        value = float(re.search(r"stiffness_translational:\s*([\d.]+)", file.read()).group(1))
    return (value * np.eye(3)).ravel()


def run_episode(sim):
    """reset() and STEPS steps; returns the observations at the step boundaries (from reset and
    every step but the last: the cycle that would read the last one never runs) and the commands
    sent, as (stamp ns, keywords, info)."""
    obs = sim.reset()
    boundaries, sent = [], []
    for step in range(STEPS):
        boundaries.append(obs)
        if step == REJECTED_STEP:
            command = {"stiffness_translational": -np.eye(3).ravel()}
        else:
            command = {"position": obs["tcp_position"] + [0.0, 0.002 * step, -0.003]}
        stamp = round(obs["time"] * 1e9)  # the Sim stamps a command with its simulated time
        obs, _, terminated, _, info = sim.step(command)
        assert not terminated, info
        assert info["accepted"] == (step != REJECTED_STEP), info
        sent.append((stamp, command, info))
    return boundaries, sent


def check_sim_cycles(rec, episodes, stiffness):
    cycles = rec["/comply/cycle"]
    per_episode = STEPS * STEPS_PER_ACTION
    assert cycles.count == EPISODES * per_episode, cycles
    # Episodes start where the cycle index restarts; the file's clock never goes back.
    assert np.array_equal(cycles["state.cycle"], np.tile(np.arange(per_episode), EPISODES))
    assert np.all(np.diff(cycles.log_time) > 0)
    for episode, (boundaries, _) in enumerate(episodes):
        rows = episode * per_episode + np.arange(STEPS) * STEPS_PER_ACTION
        want = np.array([obs["position"] for obs in boundaries])
        got = cycles["state.position"][rows]
        assert np.array_equal(got, want), (episode, np.abs(got - want).max())
    gains = cycles["cartesian_in_force.stiffness_translational"]
    assert gains.shape == (cycles.count, 9)
    assert np.array_equal(gains, np.tile(stiffness, (cycles.count, 1))), gains[0]
    assert len(cycles["cartesian_in_force"]) == cycles.count  # the list-of-dicts form stays
    assert cycles["cartesian_in_force"][0][0]["stiffness_translational"].shape == (9,)


def check_sim_commands(rec, episodes):
    commands, outcomes = rec["/comply/cartesian_command"], rec["/comply/outcome"]
    sent = [command for _, commands_sent in episodes for command in commands_sent]
    assert commands.count == len(sent) == EPISODES * STEPS, commands
    assert rec["/comply/joint_command"].count == 0
    sent_stamps = stamps(commands, "header.stamp")
    assert sent_stamps.tolist() == [stamp for stamp, _, _ in sent]
    for row, (_, command, _) in enumerate(sent):
        for name, value in command.items():
            assert np.array_equal(commands[name][row], value), (row, name)

    assert outcomes.count == len(sent), outcomes
    assert stamps(outcomes, "stamp").tolist() == sent_stamps.tolist()
    rejected = constant(outcomes, "OUTCOME_REJECTED")
    for row, (_, command, info) in enumerate(sent):
        if info["accepted"]:
            assert outcomes["outcome"][row] == constant(outcomes, "OUTCOME_APPLIED")
            assert outcomes["cycle"][row] == info["applied_cycle"]
            assert info["applied_cycle"] == (row % STEPS) * STEPS_PER_ACTION
        else:
            assert outcomes["outcome"][row] == rejected
            assert outcomes["reason"][row] == constant(outcomes, "REASON_INVALID_GAINS")
            assert outcomes["message"][row] == info["message"], outcomes["message"][row]


def expect_missing_folder(make, folder):
    """make(path) with a path in the missing `folder` raises OSError naming it; nothing is made."""
    try:
        make(os.path.join(folder, "deeper", "run.mcap"))
    except OSError as error:
        missing = os.path.join(folder, "deeper")
        assert f"the folder '{missing}' does not exist (create it first" in str(error), error
    else:
        raise AssertionError("a recording in a missing folder was accepted")
    assert not os.path.exists(folder), folder


def check_sim(source, folder):
    config = f"{source}/config/sim/cartesian_impedance.yaml"
    expect_missing_folder(lambda path: comply.Sim(config, robot="fr3", record=path),
                          os.path.join(folder, "missing"))
    os.mkdir(os.path.join(folder, "runs"))
    path = os.path.join(folder, "runs", "sim.mcap")
    sim = comply.Sim(f"{source}/config/sim/cartesian_impedance.yaml", robot="fr3",
                     steps_per_action=STEPS_PER_ACTION, record=path)
    episodes = [run_episode(sim) for _ in range(EPISODES)]
    sim.close()
    sim.close()  # idempotent
    stats = sim.recording_stats()
    sim.step(None)  # the Sim carries on, unrecorded
    rec = comply.read_recording(path)
    assert not rec.truncated
    assert stats["error"] == "" and stats["dropped"] == 0, stats
    assert stats["written"] == sum(rec.message_counts.values()), (stats, rec.message_counts)
    assert rec.metadata["comply_run"]["host"] == "comply.Sim"
    # Offline: a full lane waits for the writer, so every cycle is in the file (the count below).
    assert rec.metadata["comply_recording"]["when_full"] == "wait", rec.metadata
    check_sim_cycles(rec, episodes, config_stiffness(source))
    check_sim_commands(rec, episodes)
    assert comply.Sim(f"{source}/config/sim/cartesian_impedance.yaml").recording_stats() is None
    print(f"sim: {EPISODES} episodes, {stats['written']} messages recorded")
    return path


def check_export(cli, source, recording, folder):
    """`comply export --lerobot` splits the Sim's file into its episodes where the cycle count
    starts again: as many episodes as reset() began, each from its own first cycle (frame 0 at
    its time 0), rows numbered across them. The Parquet files read with hyparquet
    (tests/export/read_parquet.mjs)."""
    dataset = os.path.join(folder, "dataset")
    done = subprocess.run([cli, "export", "--lerobot", dataset, recording, "--fps", "100"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with open(os.path.join(dataset, "meta", "info.json")) as file:
        info = json.load(file)
    assert info["total_episodes"] == EPISODES, info

    def read(*parts):
        text = subprocess.run(["node", f"{source}/tests/export/read_parquet.mjs",
                               os.path.join(dataset, *parts)],
                              capture_output=True, text=True, check=True).stdout
        return json.loads(text)

    episodes = read("meta", "episodes", "chunk-000", "file-000.parquet")["rows"]
    assert [int(e["episode_index"]) for e in episodes] == list(range(EPISODES)), episodes
    frames = read("data", "chunk-000", "file-000.parquet")["rows"]
    assert len(frames) == info["total_frames"] == sum(int(e["length"]) for e in episodes)
    for episode in episodes:
        start, end = int(episode["dataset_from_index"]), int(episode["dataset_to_index"])
        # STEPS x STEPS_PER_ACTION cycles of 1 ms at 100 fps: about 12 frames each.
        assert end - start >= STEPS * STEPS_PER_ACTION // 10 - 1, episode
        own = frames[start:end]
        assert [int(f["frame_index"]) for f in own] == list(range(end - start)), own
        assert all(f["episode_index"] == episode["episode_index"] for f in own)
        assert [int(f["index"]) for f in own] == list(range(start, end))
    print(f"export: {EPISODES} episodes, {len(frames)} frames")


def check_sim_chunks(source, folder):
    """Chunks that took over, one superseded and one dropped while they waited for their
    takeover: /comply/chunk_timing holds one row per chunk, with the numbers step() gave in
    info["chunks"] (times on the recording's clock, which starts at the Sim's time 0)."""
    path = os.path.join(folder, "runs", "chunks.mcap")
    sim = comply.Sim(f"{source}/config/sim/cartesian_impedance.yaml", robot="fr3",
                     steps_per_action=50, record=path)
    obs = sim.reset()
    origin, start, orientation = obs["time"], obs["tcp_position"].copy(), obs["tcp_orientation"]

    def on_line(count, keep=None):
        """`count` waypoints 50 ms apart from now on one line along y (0.1 m/s from the
        origin): each chunk continues the one before without a jump."""
        now = obs["time"]
        chunk = [{"time": 0.05 * k, "orientation": orientation,
                  "position": start + [0.0, 0.1 * (now + 0.05 * k - origin), 0.0]}
                 for k in range(count)]
        return sim.step(chunk, keep=keep)

    records = []
    # Steps of 50 ms: a chunk kept to its waypoint 2 takes over two steps later; one kept to its
    # waypoint 5 is superseded by the next, and one kept to its waypoint 4 dropped by a command.
    plan = [(40, None), (20, 2), (None, None), (None, None), (20, 5), (20, 2), (None, None),
            (None, None), (20, 4), ("command", None), (None, None)]
    for count, keep in plan:
        if count is None:
            obs, _, _, _, info = sim.step(None)
        elif count == "command":
            obs, _, _, _, info = sim.step({"position": obs["tcp_position"]})
        else:
            obs, _, _, _, info = on_line(count, keep)
            assert info["accepted"], info
        records += info["chunks"]
    sim.close()
    ends = sorted(record["end"] for record in records)
    assert ends == ["dropped", "superseded", "took_over", "took_over", "took_over"], records

    rows = comply.read_recording(path)["/comply/chunk_timing"]
    assert rows.count == len(records), (rows.count, records)
    end_codes = {name: constant(rows, f"END_{name.upper()}")
                 for name in ("took_over", "superseded", "dropped")}
    by_sequence = {int(sequence): row for row, sequence in enumerate(rows["sequence_number"])}
    assert sorted(by_sequence) == sorted(record["sequence"] for record in records)
    times = ("observation", "received", "takeover", "requested_takeover", "first_waypoint",
             "last_waypoint")
    numbers = ("waypoints", "waypoints_past", "position_jump", "rotation_jump", "velocity_jump",
               "angular_velocity_jump", "starved", "rest")
    for record in records:
        row = by_sequence[record["sequence"]]
        assert rows["end"][row] == end_codes[record["end"]], (row, record)
        for name in numbers:
            assert rows[name][row] == record[name], (name, rows[name][row], record)
        for name in times:
            got = stamps(rows, name)[row]
            if np.isnan(record[name]):
                assert got == 0, (name, got, record)  # all zero: not said, or never
            else:
                assert abs(got - record[name] * 1e9) <= 1.0, (name, got, record)
        if record["end"] == "took_over":
            assert rows["takeover_cycle"][row] == record["takeover_cycle"], record
    kept = [record for record in records
            if record["end"] == "took_over" and not np.isnan(record["requested_takeover"])]
    assert kept and all(record["waypoints_past"] >= 2 for record in kept), kept
    print(f"sim: {rows.count} chunk timing records, ends {ends}")


def check_client(cli, source, folder):
    from live_host import running_host  # beside this file

    path = os.path.join(folder, "client.mcap")
    with running_host(cli, source, "pyrec") as (_, domain):
        expect_missing_folder(
            lambda path: comply.Client(name="pyrec", domain=domain, timeout=30.0, record=path),
            os.path.join(folder, "missing"))
        client = comply.Client(name="pyrec", domain=domain, timeout=30.0, record=path)
        state = client.state()
        assert state is not None
        sent = {}
        for k in range(5):
            position = state["tcp_position"] + [0.0, 0.0, -0.001 * k]
            stamp = client.send_cartesian(position=position, orientation=state["tcp_orientation"])
            sent[stamp] = position
        activated = client.activate()  # already active: carried out, harmless
        assert client.outcome(activated, timeout=5.0)["applied"]
        assert all(client.outcome(stamp, timeout=5.0)["applied"] for stamp in sent)
        assert client.state() is not None and client.diagnostics() is not None
        client.close()
        client.close()
        stats = client.recording_stats()
    rec = comply.read_recording(path)
    assert not rec.truncated and stats["error"] == "" and stats["dropped"] == 0, stats
    assert rec.metadata["comply_client"] == {"host": "pyrec", "domain": str(domain),
                                             "network": "loopback"}, rec.metadata
    assert rec.metadata["comply_recording"]["when_full"] == "drop", rec.metadata
    commands = rec["/pyrec/cartesian_command"]
    sent_stamps = stamps(commands, "header.stamp")
    assert np.array_equal(commands.log_time, sent_stamps)  # logged when sent, at its stamp
    assert sent_stamps.tolist() == list(sent)
    assert np.array_equal(commands["position"], list(sent.values()))
    # Besides the request sent: the discovery probes (REQUEST_PROBE) sent before the commands.
    requests = rec["/pyrec/request"]
    request_stamps = stamps(requests, "header.stamp")
    probes = requests["request"] == constant(requests, "REQUEST_PROBE")
    assert probes.any() and request_stamps[probes].max() < min(sent), requests["request"]
    assert requests["request"][~probes].tolist() == [constant(requests, "REQUEST_ACTIVATE")]
    assert request_stamps[~probes].tolist() == [activated]
    states, diagnostics = rec["/pyrec/state"], rec["/pyrec/diagnostics"]
    assert states.count >= 1 and diagnostics.count >= 1, rec.message_counts
    assert states["position"].shape == (states.count, 7)
    assert rec["/pyrec/joint_command"].count == 0
    print(f"client: {len(sent)} commands, {np.count_nonzero(probes)} probe(s), "
          f"{states.count} states, {diagnostics.count} diagnostics recorded")


def main():
    cli, source = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as folder:
        recording = check_sim(source, folder)
        check_sim_chunks(source, folder)
        if not os.access(cli, os.X_OK):
            print(f"skip: the Sim's recording passed; the host {cli} is not built, so the "
                  f"client's and the export are not tested")
            return
        check_export(cli, source, recording, folder)
        check_client(cli, source, folder)
    print("ok")


if __name__ == "__main__":
    main()
