#!/usr/bin/env python3
"""Plots the contact-speed sweep (tests/sim/contact_speed_sweep_test.cpp): a probe on the simulated
FR3 driven into a hand's spring (75 N/mm) from three poses. Left, the spring's peak force against
the commanded speed, with the contact-speed stage and without, the hands' quasi-static limit, and
(crosses) a reference that runs on through the contact with the stage on; right, the probe's speed
at the first touch, and (dots) the stage's v_max along the motion there.

usage: plot_contact_speed.py SWEEP_CSV OUT_PNG
       (the test writes $TMPDIR/comply_contact_speed_sweep/sweep.csv)
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LIMIT_N = 140.0
COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:purple"]


def read_runs(path):
    """{pose: {(reference, governed): [row]}} with the numbers as floats, in file order."""
    runs = {}
    with open(path, newline="") as handle:
        for row in csv.DictReader(handle):
            key = (row["reference"], row["governed"] == "1")
            numbers = {name: float(value) for name, value in row.items()
                       if name not in ("pose", "reference", "governed")}
            runs.setdefault(row["pose"], {}).setdefault(key, []).append(numbers)
    if not runs:
        sys.exit(f"{path}: no runs")
    return runs


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip())
    runs = read_runs(sys.argv[1])
    figure, (force_axis, speed_axis) = plt.subplots(1, 2, figsize=(12, 5.2))
    for colour, (pose, by_kind) in zip(COLOURS, runs.items()):
        for governed, style, label in [(False, "--o", "off"), (True, "-s", "on")]:
            rows = by_kind.get(("stop", governed), [])
            commanded = [row["commanded_m_per_s"] for row in rows]
            force_axis.plot(commanded, [row["peak_force_n"] for row in rows], style, color=colour,
                            markersize=4, linewidth=1, label=f"{pose}, stage {label}")
            speed_axis.plot(commanded, [row["contact_speed_m_per_s"] for row in rows], style,
                            color=colour, markersize=4, linewidth=1)
        governed_rows = by_kind.get(("stop", True), [])
        speed_axis.plot([row["commanded_m_per_s"] for row in governed_rows],
                        [row["limit_m_per_s"] for row in governed_rows], ":.", color=colour,
                        linewidth=1)
        through = by_kind.get(("through", True), [])
        if through:
            force_axis.plot([row["commanded_m_per_s"] for row in through],
                            [row["peak_force_n"] for row in through], "x", color=colour,
                            markersize=7, label=f"{pose}, on, reference runs on 20 mm")
    force_axis.axhline(LIMIT_N, color="tab:red", linewidth=1.5, label="hands, quasi-static: 140 N")
    force_axis.set_xlabel("commanded speed [m/s]")
    force_axis.set_ylabel("peak spring force [N]")
    force_axis.set_title("FR3 probe into 75 N/mm: peak force")
    speed_axis.set_xlabel("commanded speed [m/s]")
    speed_axis.set_ylabel("speed at the first touch [m/s]")
    speed_axis.set_title("speed at the touch (dotted: the stage's v_max there)")
    figure.legend(*force_axis.get_legend_handles_labels(), loc="lower center", ncol=4,
                  fontsize=8)
    figure.tight_layout(rect=(0.0, 0.12, 1.0, 1.0))
    figure.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
