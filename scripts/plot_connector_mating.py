#!/usr/bin/env python3
"""Plots `comply experiment connector-mating`: per condition (columns), the peg tip's depth in the
socket, the axial contact force, the angle of the stiff task axis to the socket's axis and the tip's
distance from that axis over the insertion, one line per angular offset.

usage: plot_connector_mating.py OUT_DIR   (reads OUT_DIR/results.json and each trial's trace.csv,
                                           writes OUT_DIR/connector_mating.png)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from csv_columns import read_columns  # noqa: E402

INSERTION_START_S = 3.0
QUANTITIES = [
    ("depth_mm", "tip depth [mm]"),
    ("axial_force_n", "axial force [N] (20 ms mean)"),
    ("task_axis_to_socket_deg", "task z to socket axis [deg]"),
    ("tip_off_axis_mm", "tip off the socket axis [mm]"),
]


def read(path):
    return read_columns(path, lambda row: float(row["time_s"]) >= INSERTION_START_S)


def label(offset):
    return f"{offset:g}"


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip())
    out = sys.argv[1]
    with open(os.path.join(out, "results.json")) as handle:
        results = json.load(handle)
    conditions = list(dict.fromkeys(row["condition"] for row in results))
    offsets = sorted({row["offset_deg"] for row in results})
    colours = plt.get_cmap("viridis")
    figure, axes = plt.subplots(len(QUANTITIES), len(conditions), sharex=True, sharey="row",
                                figsize=(3.6 * len(conditions), 9), squeeze=False)
    for column, condition in enumerate(conditions):
        for row in results:
            if row["condition"] != condition:
                continue
            trace_file = os.path.join(out, f"{condition}_{label(row['offset_deg'])}deg", "trace.csv")
            if not os.path.exists(trace_file):
                continue
            trace = read(trace_file)
            shade = colours(offsets.index(row["offset_deg"]) / max(1, len(offsets) - 1))
            for line, (key, _) in enumerate(QUANTITIES):
                axes[line][column].plot(trace["time_s"], trace[key], color=shade, linewidth=1,
                                        label=f"{row['offset_deg']:g} deg"
                                        + ("" if row["seated"] else f" ({row['failure']})"))
        axes[0][column].set_title(condition)
        axes[0][column].legend(fontsize="x-small")
        axes[-1][column].set_xlabel("time [s]")
    for line, (_, title) in enumerate(QUANTITIES):
        axes[line][0].set_ylabel(title, fontsize="small")
        for axis in axes[line]:
            axis.grid(alpha=0.3)
    axes[2][0].set_ylim(0, 30)  # the online frames that turn away run off this scale
    figure.tight_layout()
    figure.savefig(os.path.join(out, "connector_mating.png"), dpi=90)


if __name__ == "__main__":
    main()
