#!/usr/bin/env python3
"""Plots `comply experiment surface-following`: a top view of the probe paths over the fixture, and
lateral error, tangential error and the normal contact force over time for each condition (the
impedance conditions solid, the force-controlled ones dashed).

usage: plot_surface_following.py OUT_DIR   (writes OUT_DIR/surface_following.png)
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from csv_columns import read_columns  # noqa: E402

CONDITIONS = [
    ("fixed_frame", "fixed-frame gains", "tab:red", "-"),
    ("task_aligned", "task-aligned gains", "tab:blue", "-"),
    ("task_aligned_displaced", "task-aligned, fixture displaced", "tab:green", "-"),
    ("force_sensor", "force 5 N, wrist sensor", "tab:purple", "--"),
    ("force_observer", "force 5 N, observer", "tab:orange", "--"),
    ("force_sensor_displaced", "force 5 N, sensor, fixture displaced", "tab:olive", "--"),
]
TARGET_N = 5.0


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip())
    out = sys.argv[1]
    fixture = read_columns(os.path.join(out, "fixture.csv"))
    figure = plt.figure(figsize=(11, 8))
    top = figure.add_subplot(2, 1, 1)
    mm = lambda values: [1e3 * v for v in values]  # noqa: E731
    top.plot(mm(fixture["x"]), mm(fixture["face_y"]), color="0.3", linewidth=3, label="fixture face")
    top.plot(mm(fixture["x"]), mm(fixture["face_y_displaced"]), color="0.6", linewidth=3,
             linestyle="--", label="displaced fixture face")
    axes = [figure.add_subplot(2, 3, 4 + i) for i in range(3)]
    for name, label, colour, style in CONDITIONS:
        trace_file = os.path.join(out, name, "trace.csv")
        if not os.path.exists(trace_file):
            continue
        trace = read_columns(trace_file)
        line = dict(color=colour, linewidth=1, linestyle=style)
        top.plot(mm(trace["tip_x"]), mm(trace["tip_y"]), label=label, **line)
        axes[0].plot(trace["time_s"], trace["lateral_mm"], **line)
        axes[1].plot(trace["time_s"], trace["tangential_mm"], **line)
        axes[2].plot(trace["time_s"], trace["normal_n"], **line)
    axes[2].axhline(TARGET_N, color="0.3", linewidth=0.8, linestyle=":")
    axes[2].set_ylim(0.0, 3.0 * TARGET_N)
    top.set_xlabel("x [mm]")
    top.set_ylabel("y [mm]")
    top.set_title("top view: probe tip (ball centre) over the fixture face")
    top.set_aspect("equal", adjustable="datalim")
    top.legend(fontsize="small", loc="upper left", ncol=2)
    top.grid(alpha=0.3)
    for axis, title in zip(axes, ["lateral error [mm]", "tangential error [mm]",
                                  "normal force [N] (20 ms mean; target dotted)"]):
        axis.set_title(title, fontsize="medium")
        axis.set_xlabel("time [s]")
        axis.grid(alpha=0.3)
    figure.tight_layout()
    figure.savefig(os.path.join(out, "surface_following.png"), dpi=100)


if __name__ == "__main__":
    main()
