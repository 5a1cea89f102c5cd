#!/usr/bin/env python3
"""Plots `comply experiment passivity`: per scenario (columns), the arm's energy (kinetic plus the
controller's springs; log scale for the adversarial scenarios) and the stiffness along base x that
the law read, over time, for each condition that ran. The dotted line is the start energy plus the
tank's initial energy, the most the arm can hold with the tank on while the reference stands still
(not drawn for the normal task, whose moving reference does work).

usage: plot_passivity.py OUT_DIR   (writes OUT_DIR/passivity.png)
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from csv_columns import read_columns  # noqa: E402

# (folder, title, log scale): the adversarial runs span four decades, the normal task starts at 0.
SCENARIOS = [
    ("free_space_stiffness", "free space, stiffness switched", True),
    ("free_space_frame", "free space, task frame turned", True),
    ("wall_contact", "pressing on a wall, stiffness switched", True),
    ("normal_task", "normal task (10 cm out and back, one step)", False),
]
CONDITIONS = [
    ("none", "no gain stage", "tab:red"),
    ("ramps", "ramps", "tab:orange"),
    ("tank", "ramps + tank", "tab:blue"),
    ("tank_only", "tank alone (ablation)", "tab:green"),
]
TANK_INITIAL_J = 1.0  # passivity.tank_initial_j, its default


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip())
    out = sys.argv[1]
    figure, axes = plt.subplots(2, len(SCENARIOS), figsize=(16, 7), sharex="col")
    for column, (scenario, title, log_scale) in enumerate(SCENARIOS):
        energy_axis, stiffness_axis = axes[0][column], axes[1][column]
        start_j = None
        for name, label, colour in CONDITIONS:
            trace_file = os.path.join(out, scenario, name + ".csv")
            if not os.path.exists(trace_file):
                continue
            trace = read_columns(trace_file)
            start_j = trace["energy_j"][0] if start_j is None else start_j
            energy_axis.plot(trace["time_s"], trace["energy_j"], color=colour, linewidth=1,
                             label=label)
            stiffness_axis.plot(trace["time_s"], trace["stiffness_x_n_per_m"], color=colour,
                                linewidth=1)
        if start_j is not None and log_scale:
            energy_axis.axhline(start_j + TANK_INITIAL_J, color="0.3", linestyle=":", linewidth=1,
                                label="start + tank's initial energy")
        if log_scale:
            energy_axis.set_yscale("log")
        energy_axis.set_title(title, fontsize="medium")
        stiffness_axis.set_xlabel("time [s]")
        for axis in (energy_axis, stiffness_axis):
            axis.grid(alpha=0.3)
    axes[0][0].set_ylabel("arm energy [J] (kinetic + springs)")
    axes[1][0].set_ylabel("stiffness along base x the law read [N/m]")
    axes[0][0].legend(fontsize="small", loc="lower right")
    figure.tight_layout()
    figure.savefig(os.path.join(out, "passivity.png"), dpi=100)


if __name__ == "__main__":
    main()
