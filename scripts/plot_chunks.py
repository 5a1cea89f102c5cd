#!/usr/bin/env python3
"""Plots `comply experiment chunks`: for stepped setpoints and timed chunks, over one second of
the circle, the y coordinate of the target, the controller's reference and the TCP (top), the
reference's speed (middle) and the largest joint torque rate (bottom), with the torque-rate limit
dotted. Every condition whose trace is in OUT_DIR is drawn.

usage: plot_chunks.py OUT_DIR   (writes OUT_DIR/chunks.png)
"""
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from csv_columns import read_columns  # noqa: E402

WINDOW_S = (2.0, 3.0)  # a second of steady tracking
TORQUE_RATE_LIMIT = 1000.0  # N m/s, torque_rate_limit_nm_per_s of the controller file


def window(trace, key):
    pairs = [(t, v) for t, v in zip(trace["time_s"], trace[key]) if WINDOW_S[0] <= t <= WINDOW_S[1]]
    return [t for t, _ in pairs], [v for _, v in pairs]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip())
    out = sys.argv[1]
    # Stepped first, then chunks by rate: "stepped_15hz" before "chunks_10hz".
    def order(path):
        name = os.path.splitext(os.path.basename(path))[0]
        mode, _, rate = name.partition("_")
        return (mode != "stepped", float(rate.rstrip("hz") or 0))

    traces = sorted(glob.glob(os.path.join(out, "*.csv")), key=order)
    if not traces:
        sys.exit(f"no traces in {out}")
    figure, axes = plt.subplots(3, len(traces), figsize=(4.5 * len(traces), 8), sharex=True,
                                squeeze=False)
    for column, path in enumerate(traces):
        name = os.path.splitext(os.path.basename(path))[0]
        trace = read_columns(path)
        top, middle, bottom = axes[0][column], axes[1][column], axes[2][column]
        for key, label, style in [("target_y", "circle", ":"), ("reference_y", "reference", "-"),
                                  ("tcp_y", "TCP", "-")]:
            t, values = window(trace, key)
            top.plot(t, [1e3 * v for v in values], style, linewidth=1, label=label)
        top.set_title(name.replace("_", " "))
        top.set_ylabel("y [mm]")
        t, speed = window(trace, "reference_speed")
        middle.plot(t, speed, linewidth=1, color="tab:purple")
        middle.set_ylabel("reference speed [m/s]")
        t, rate = window(trace, "torque_rate")
        bottom.plot(t, rate, linewidth=1, color="tab:red")
        bottom.axhline(TORQUE_RATE_LIMIT, color="0.3", linestyle=":", linewidth=1)
        bottom.set_ylabel("max joint torque rate [N m/s]")
        bottom.set_xlabel("time [s]")
        if column == 0:
            top.legend(loc="best", fontsize=8)
    figure.tight_layout()
    figure.savefig(os.path.join(out, "chunks.png"), dpi=110)


if __name__ == "__main__":
    main()
