#!/usr/bin/env python3
"""Plots a `comply sim` log: tracking error, joint torques, tool contact force (with the
controller's estimate of it when the momentum observer ran, and the wrist sensor's reading in
admittance: their columns are in the log), for drives that take positions how far each joint is
from its command, and, when the energy tank was on, the tank's energies and gain fraction over
time.

usage: plot_sim_log.py log.csv plot.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402


def read_columns(path):
    with open(path, newline="") as handle:
        reader = csv.reader(handle)
        header = next(reader)
        columns = {name: [] for name in header}
        for row in reader:
            for name, value in zip(header, row):
                columns[name].append(float(value))
    return header, columns


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip())
    header, data = read_columns(sys.argv[1])
    time = data["time_s"]
    torques = [name for name in header if name.startswith("tau")]
    cartesian = "position_error_mm" in data
    force = [
        (fx * fx + fy * fy + fz * fz) ** 0.5
        for fx, fy, fz in zip(data["contact_fx"], data["contact_fy"], data["contact_fz"])
    ]
    in_contact = max(force, default=0.0) > 1e-6
    tank = "tank_energy_j" in data  # log.csv has the tank's columns only when it was on
    commands = [name for name in header if name.startswith("qcmd")]  # drives taking positions
    admittance = "sensor_fx" in data

    rows = 2 + int(in_contact) + int(bool(commands)) + int(tank)
    figure, axes = plt.subplots(rows, 1, sharex=True, figsize=(9, 2.6 * rows + 0.6))
    if cartesian:
        axes[0].plot(time, data["position_error_mm"], label="position [mm]", color="tab:blue")
        axes[0].set_ylabel("position error [mm]")
        twin = axes[0].twinx()
        twin.plot(time, data["orientation_error_deg"], color="tab:orange", label="orientation")
        twin.set_ylabel("orientation error [deg]", color="tab:orange")
        axes[0].set_title("tracking error (reference - measured TCP)")
    else:
        axes[0].plot(time, data["joint_error_rad"], color="tab:blue")
        axes[0].set_ylabel("max |q_ref - q| [rad]")
        axes[0].set_title("tracking error")
    axes[0].grid(alpha=0.3)

    for index, name in enumerate(torques):
        axes[1].plot(time, data[name], label=f"joint {index + 1}", linewidth=1.0)
    axes[1].set_ylabel("virtual arm's torque [N m]" if admittance else "commanded torque [N m]")
    axes[1].legend(ncol=min(len(torques), 7), fontsize="small", loc="upper right")
    axes[1].grid(alpha=0.3)

    if in_contact:
        axes[2].plot(time, force, color="tab:red", label="contact (simulator)")
        if "estimated_fx" in data:  # observer.enabled: what the controller sees
            estimate = [
                (fx * fx + fy * fy + fz * fz) ** 0.5
                for fx, fy, fz in zip(data["estimated_fx"], data["estimated_fy"],
                                      data["estimated_fz"])
            ]
            axes[2].plot(time, estimate, color="tab:purple", linewidth=1.0,
                         label="estimated (momentum observer)")
            axes[2].legend(fontsize="small", loc="upper right")
        if admittance:  # the wrench the virtual arm answered
            sensed = [
                (fx * fx + fy * fy + fz * fz) ** 0.5
                for fx, fy, fz in zip(data["sensor_fx"], data["sensor_fy"], data["sensor_fz"])
            ]
            axes[2].plot(time, sensed, color="tab:green", linewidth=1.0,
                         label="wrist sensor (tool and tare off)")
            axes[2].legend(fontsize="small", loc="upper right")
        axes[2].set_ylabel("tool contact force [N]")
        axes[2].grid(alpha=0.3)

    if commands:
        row = 2 + int(in_contact)
        for index, name in enumerate(commands):
            lag = [1e3 * (c - q) for c, q in zip(data[name], data[f"q{index}"])]
            axes[row].plot(time, lag, label=f"joint {index + 1}", linewidth=1.0)
        axes[row].set_ylabel("command - measured [mrad]")
        axes[row].set_title("the drives' position command against the joints")
        axes[row].legend(ncol=min(len(commands), 7), fontsize="small", loc="upper right")
        axes[row].grid(alpha=0.3)

    if tank:
        axes[-1].plot(time, data["tank_energy_j"], label="task tank", color="tab:green")
        if cartesian:
            axes[-1].plot(time, data["nullspace_tank_energy_j"], label="nullspace tank",
                          color="tab:olive")
        axes[-1].set_ylabel("tank energy [J]")
        axes[-1].legend(fontsize="small", loc="upper left")
        twin = axes[-1].twinx()
        twin.plot(time, data["gain_fraction"], color="tab:purple")
        twin.set_ylabel("gain fraction [-]", color="tab:purple")
        twin.set_ylim(-0.05, 1.05)
        axes[-1].set_title("energy tank (gain fraction: commanded stiffness change in force)")
        axes[-1].grid(alpha=0.3)
    axes[-1].set_xlabel("time [s]")
    figure.tight_layout()
    figure.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
