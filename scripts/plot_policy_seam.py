#!/usr/bin/env python3
"""Draws one seam between two chunks of a policy that infers while the arm moves (docs/policies.md):
the FR3 on the in-process Sim, a 30 Hz policy of 16 actions along a smooth curve, each chunk off
by its own 2 mm, inference taking 150 ms. Left: the new chunk replaces the old one when it
arrives; right: it keeps the host's committed actions for the measured delay and takes over at
the waypoint after them, joining the curve in force there (mode "frozen"). Each panel shows the executed reference along y, the old
and new chunks' waypoints, the committed prefix the host gave at the new chunk's observation, and
the observation, arrival and takeover.

usage: PYTHONPATH=build/python plot_policy_seam.py SOURCE_DIR OUT.png
"""
import math
import os
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import comply  # noqa: E402
from comply.policy import PolicyRunner, inpaint  # noqa: E402

DT, HORIZON, DELAY_S = 1.0 / 30.0, 16, 0.15


def run(source, mode):
    rng = np.random.default_rng(3)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "seam.mcap")
        sim = comply.Sim(f"{source}/config/sim/cartesian_impedance.yaml", robot="fr3", record=path)
        obs = sim.reset()
        orientation = obs["tcp_orientation"].copy()
        plan = lambda t: 0.04 * math.sin(1.5 * t)  # noqa: E731
        committed = {}

        def policy(ctx):
            origin = ctx["observation"]["reference_position"].copy()
            offset = rng.normal(0.0, 0.002)
            committed[ctx["time"]] = sim.committed(ctx["time"], DT, HORIZON)
            planned = [origin + [0.0, plan(ctx["time"] + k * DT) - plan(ctx["time"]) + offset, 0.0]
                       for k in range(HORIZON)]
            return [{"time": k * DT, "position": p, "orientation": orientation}
                    for k, p in enumerate(inpaint(planned, ctx))]

        runner = PolicyRunner(sim, policy, dt=DT, horizon=HORIZON, mode=mode,
                              inference_delay=lambda: DELAY_S)
        runner.run(2.0, observation=obs)
        sim.close()
        cycles = comply.read_recording(path)["/comply/cycle"]
    stamp = cycles["state.header.stamp.sec"] + 1e-9 * cycles["state.header.stamp.nanosec"]
    return runner, committed, stamp, cycles["cartesian_in_force.position"][:, 1]


def draw(axis, source, mode, title):
    runner, committed, stamp, y = run(source, mode)
    took = [r for r in runner.records if r["timing"] and r["timing"]["end"] == "took_over"]
    old, new = took[-3], took[-2]  # a seam in steady state
    t0 = new["timing"]["takeover"]
    window = (stamp > t0 - 0.35) & (stamp < t0 + 0.3)
    base = y[window].min()
    mm = lambda v: 1000 * (np.asarray(v) - base)  # noqa: E731
    axis.plot(stamp[window] - t0, mm(y[window]), color="black", lw=1.5, label="executed reference")
    for record, colour, name in ((old, "tab:blue", "old chunk"), (new, "tab:orange", "new chunk")):
        times = record["observation"] + DT * np.arange(HORIZON) - t0
        values = [w["position"][1] for w in record["chunk"]]
        shown = (times > -0.35) & (times < 0.3)
        axis.plot(times[shown], mm(np.array(values)[shown]), "o", color=colour, ms=4, label=name)
    prefix = committed[new["observation"]]
    shown = (prefix["time"] - t0 > -0.35) & (prefix["time"] - t0 < 0.3)
    axis.plot(prefix["time"][shown] - t0, mm(prefix["position"][shown, 1]), "x", color="tab:green",
              label="committed at its observation")
    for t, style, name in ((new["observation"], ":", "observation"),
                           (new["sent_at"], "--", "arrival"), (t0, "-", "takeover")):
        axis.axvline(t - t0, color="grey", ls=style, lw=0.8)
        axis.text(t - t0, axis.get_ylim()[1], name, rotation=90, va="top", ha="right", fontsize=7)
    axis.axvspan(0.0, 0.1, color="grey", alpha=0.12)
    timing = new["timing"]
    axis.set_title(f"{title}: {timing['waypoints_past']} waypoints past, jump "
                   f"{1000 * timing['position_jump']:.2f} mm", fontsize=9)
    axis.set_xlabel("time from the takeover [s] (shaded: the blend)")
    axis.set_ylabel("reference y [mm]")
    axis.legend(fontsize=7, loc="lower right")


def main():
    source, out = sys.argv[1], sys.argv[2]
    figure, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=False)
    draw(axes[0], source, "replace", "replace on arrival")
    draw(axes[1], source, "frozen", "keep the committed prefix")
    figure.tight_layout()
    figure.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
