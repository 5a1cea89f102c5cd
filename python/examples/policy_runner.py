"""A chunking policy that infers while the arm moves, run by comply.policy.PolicyRunner: every
inference takes 150 ms (a model's, simulated), plans 16 actions at 30 Hz along a 4 cm circle from
where the observation's reference stands, and the chunk takes over at the waypoint after the
delay the host measured (mode "frozen": the policy keeps the actions the host had committed to).
Prints the host's delay count per chunk (waypoints already past when it took over), its
distribution, and the seams' jumps (docs/policies.md).

    PYTHONPATH=build/python python3 python/examples/policy_runner.py              # in-process Sim
    PYTHONPATH=build/python python3 python/examples/policy_runner.py --mode replace

Against a running host (`comply run --config config/sim/cartesian_impedance.yaml --sim`), the
same runner sends with Client.send_chunk and reads the delay from each chunk's outcome: --live.
"""

import argparse
import collections
import math
import time

import numpy as np

import comply
from comply.policy import PolicyRunner, inpaint

DT = 1.0 / 30.0  # the policy's step
HORIZON = 16  # actions per chunk
INFERENCE_S = 0.15  # from observation to chunk
RADIUS_M = 0.04
TURN_S = 4.0  # one turn of the circle


class CirclePolicy:
    """A circle in the y-z plane, planned from the observation's reference; with a committed
    prefix, its first actions are the host's and the rest fades back onto the circle."""

    def __init__(self, live):
        self.live = live  # on a Client the inference takes real time

    def __call__(self, ctx):
        if self.live:
            time.sleep(INFERENCE_S)
        obs = ctx["observation"]
        origin = np.asarray(obs["reference_position"], dtype=float)
        orientation = obs.get("reference_orientation", obs.get("tcp_orientation"))
        t0 = ctx["time"]

        def circle(t):
            angle = 2 * math.pi * t / TURN_S
            return np.array([0.0, RADIUS_M * math.sin(angle), RADIUS_M * (1 - math.cos(angle))])

        planned = [origin + circle(t0 + k * DT) - circle(t0) for k in range(HORIZON)]
        return [{"time": k * DT, "position": position, "orientation": orientation}
                for k, position in enumerate(inpaint(planned, ctx))]


def report(runner):
    timings = [r["timing"] for r in runner.records if r.get("timing")]
    took = [t for t in timings if t["end"] == "took_over"]
    refused = [r["refused"] for r in runner.records if r.get("refused")]
    print(f"{len(runner.records)} chunks sent, {len(took)} took over, {len(refused)} refused")
    if not took:
        print("no chunk timing came back (a host that does not report it?)")
        return
    counts = collections.Counter(t["waypoints_past"] for t in took)
    print("delay measured by the host [waypoints past at takeover]:")
    for delay in sorted(counts):
        print(f"  {delay:3d} steps ({delay * DT * 1000:5.0f} ms): {'#' * counts[delay]}")
    steady = took[1:]  # the first starts from rest
    if steady:
        jumps = np.array([t["position_jump"] for t in steady]) * 1000
        print(f"seam jump after the first [mm]: median {np.median(jumps):.2f}, "
              f"max {jumps.max():.2f}; starved {sum(t['starved'] for t in steady)} times")
    for reason in refused[:3]:
        print("refused:", reason)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--mode", default="frozen", choices=["replace", "frozen", "ensemble"])
    parser.add_argument("--seconds", type=float, default=6.0)
    parser.add_argument("--live", metavar="NAME", help="run against the comply run host NAME")
    parser.add_argument("--domain", type=int, default=0)
    args = parser.parse_args()
    if args.live:
        with comply.Client(name=args.live, domain=args.domain) as client:
            runner = PolicyRunner(client, CirclePolicy(live=True), dt=DT, horizon=HORIZON,
                                  mode=args.mode)
            runner.run(args.seconds)
    else:
        sim = comply.Sim("config/sim/cartesian_impedance.yaml", robot="fr3")
        runner = PolicyRunner(sim, CirclePolicy(live=False), dt=DT, horizon=HORIZON,
                              mode=args.mode, inference_delay=lambda: INFERENCE_S)
        runner.run(args.seconds)
    report(runner)


if __name__ == "__main__":
    main()
