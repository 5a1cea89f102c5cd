#!/usr/bin/env python3
"""Plots `comply experiment output-modes`: the probe's normal force on the table from the first
touch for every kind of drive (left), and the 3 kg tool's 5 cm step in admittance, declared and
not (right).

usage: plot_output_modes.py OUT_DIR   (writes OUT_DIR/output_modes.png)
"""
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from csv_columns import read_columns  # noqa: E402


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip())
    out = sys.argv[1]
    contacts = sorted(glob.glob(os.path.join(out, "contact_*.csv")))
    if not contacts:
        sys.exit(f"no contact traces in {out}")
    figure, (force_axis, tool_axis) = plt.subplots(1, 2, figsize=(11, 4))
    for path in contacts:
        mode = os.path.splitext(os.path.basename(path))[0].removeprefix("contact_")
        trace = read_columns(path)
        force_axis.plot(trace["time_s"], trace["force_n"], linewidth=1, label=f"{mode} drives")
    force_axis.axhline(30.0, color="grey", linestyle=":", linewidth=1, label="K x 3 cm")
    force_axis.set_xlabel("time after the first touch [s]")
    force_axis.set_ylabel("normal force [N]")
    force_axis.set_title("UR5e pressing a rigid table")
    force_axis.legend()
    for name, label in [("tool_declared", "declared"), ("tool_undeclared", "not declared")]:
        path = os.path.join(out, name + ".csv")
        if os.path.exists(path):
            trace = read_columns(path)
            tool_axis.plot(trace["time_s"], trace["error_mm"], linewidth=1, label=label)
    tool_axis.axhline(0.0, color="grey", linestyle=":", linewidth=1)
    tool_axis.set_xlabel("time after the step [s]")
    tool_axis.set_ylabel("TCP - target along the step [mm]")
    tool_axis.set_title("3 kg tool, 5 cm step, position drives")
    tool_axis.set_ylim(-55, 15)
    tool_axis.legend()
    figure.tight_layout()
    figure.savefig(os.path.join(out, "output_modes.png"), dpi=110)


if __name__ == "__main__":
    main()
