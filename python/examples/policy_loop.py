"""A policy-style loop: 20 Hz pose + stiffness commands streamed to a running host.

    build/apps/comply/comply run --config config/sim/cartesian_impedance.yaml --sim   # terminal 1
    PYTHONPATH=build/python python3 python/examples/policy_loop.py                      # terminal 2

The "policy" draws a 4 cm circle in the y-z plane and softens the stiffness along z while the
TCP is in the lower half, as a learned policy that outputs pose and gains would.
"""

import math
import time

import numpy as np

import comply


def main():
    client = comply.Client(name="comply", domain=0)
    state = client.state()
    centre = state["tcp_position"].copy()
    orientation = state["tcp_orientation"]
    rate_hz, seconds = 20.0, 10.0
    rejected = 0
    start = time.monotonic()
    for k in range(int(rate_hz * seconds)):
        time.sleep(max(0.0, start + k / rate_hz - time.monotonic()))
        angle = 2 * math.pi * k / (rate_hz * 4.0)  # one turn every 4 s
        target = centre + 0.04 * np.array([0.0, math.sin(angle), math.cos(angle) - 1.0])
        soft_z = 300.0 if math.cos(angle) < 0 else 3000.0
        stamp = client.send_cartesian(position=target, orientation=orientation,
                                      stiffness_translational=[3000.0, 3000.0, soft_z],
                                      stiffness_rotational=300.0)
        outcome = client.outcome(stamp, timeout=0.02)
        rejected += 0 if outcome is None or outcome["applied"] else 1
    state = client.state()
    print(f"done: TCP {np.round(state['tcp_position'], 4)}, {rejected} commands rejected")


if __name__ == "__main__":
    main()
