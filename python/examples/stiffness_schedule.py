"""Stiffness scheduling across task phases, in the in-process simulator (no host needed):
approach stiff, then soften along z for contact, then stiffen again to retract.

    PYTHONPATH=build/python python3 python/examples/stiffness_schedule.py
"""

import numpy as np

import comply

PHASES = [  # (name, seconds, z offset from the start [m], stiffness along x, y, z [N/m])
    ("approach", 2.0, -0.05, [3000, 3000, 3000]),
    ("comply", 2.0, -0.08, [3000, 3000, 200]),
    ("retract", 2.0, 0.0, [3000, 3000, 3000]),
]


def main():
    sim = comply.Sim("config/sim/cartesian_impedance.yaml", robot="fr3", steps_per_action=50)
    obs = sim.reset()
    start = obs["tcp_position"].copy()
    for name, seconds, dz, stiffness in PHASES:
        command = {"position": start + [0.0, 0.0, dz], "stiffness_translational": stiffness}
        for _ in range(int(seconds * 20)):
            obs, _, terminated, _, info = sim.step(command)
            assert info["accepted"] and not terminated, info
        error_mm = 1000 * np.linalg.norm(obs["tcp_position"] - command["position"])
        print(f"{name:9s} t = {sim.time:4.1f} s  z = {obs['tcp_position'][2]:.4f} m  "
              f"error {error_mm:5.2f} mm  stiffness {stiffness}")


if __name__ == "__main__":
    main()
