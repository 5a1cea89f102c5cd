"""A stiffness sweep in one call of comply.rollouts: every episode steps the FR3's target 3 cm
down (and up to 5 mm sideways, drawn from the episode's rng), one z stiffness per episode from
100 to 5000 N/m, log-spaced over the episodes; 2 s each. Prints the summary, the tracking error
per stiffness band and the throughput (docs/rollouts.md).

    PYTHONPATH=build/python python3 python/examples/rollout_sweep.py                 # every core
    PYTHONPATH=build/python python3 python/examples/rollout_sweep.py --cluster serial
    PYTHONPATH=build/python python3 python/examples/rollout_sweep.py --episodes 20 \\
        --dataset out/sweep                                      # and a LeRobot dataset of it
    PYTHONPATH=build/python python3 python/examples/rollout_sweep.py \\
        --cluster tcp://scheduler:8786                             # the workers of a scheduler
"""

import argparse
import os

import numpy as np

import comply

STIFFNESS_Z_N_PER_M = (100.0, 5000.0)
STEP_M = np.array([0.0, 0.0, -0.03])
JITTER_M = 0.005  # sideways, per episode
STIFFNESS_XY_N_PER_M = 3000.0
BANDS = 5  # rows of the table, equal numbers of episodes


def stiffness_sweep(episodes):
    """The schedule: episode e's command, sent once with its first step."""
    stiffness_z = np.geomspace(*STIFFNESS_Z_N_PER_M, episodes)

    def command(episode, rng, obs):
        offset = STEP_M + [*rng.uniform(-JITTER_M, JITTER_M, 2), 0.0]
        return {"position": obs["tcp_position"] + offset,
                "stiffness_translational": [STIFFNESS_XY_N_PER_M, STIFFNESS_XY_N_PER_M,
                                            stiffness_z[episode]]}

    return comply.Schedule(command), stiffness_z


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--episodes", type=int, default=200)
    parser.add_argument("--seconds", type=float, default=2.0, help="per episode, simulated")
    parser.add_argument("--cluster", default="local",
                        help="serial (this process), local (a worker per core) or a scheduler "
                             "address (tcp://host:8786)")
    parser.add_argument("--dataset", help="a folder for a LeRobot dataset of every episode")
    parser.add_argument("--csv", help="a file for the rows")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()

    source = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    schedule, stiffness_z = stiffness_sweep(args.episodes)
    results = comply.rollouts(
        schedule, args.episodes, None if args.cluster == "local" else args.cluster,
        config=os.path.join(source, "config/sim/cartesian_impedance.yaml"), robot="fr3",
        seconds=args.seconds, seed=args.seed, dataset=args.dataset, task="step 3 cm down")

    print(results.summary())
    error_mm = 1000.0 * results.column("tracking_error_rms_m")
    print("\nz stiffness [N/m]   tracking error RMS [mm]")
    for band in np.array_split(np.arange(args.episodes), min(BANDS, args.episodes)):
        print(f"{stiffness_z[band[0]]:7.0f} - {stiffness_z[band[-1]]:7.0f}   "
              f"{error_mm[band].mean():8.3f}")
    print(f"\n{results.steps_per_second:.0f} steps/s, {results.cycles_per_second:.0f} control "
          f"cycles/s on {results.workers} worker(s), {results.wall_s:.1f} s in all "
          f"({results.startup_s:.1f} s starting the cluster)")
    if results.dataset is not None:
        print(f"dataset {args.dataset}: {results.dataset['episodes']} episodes, "
              f"{results.dataset['frames']} frames")
    if args.csv:
        results.to_csv(args.csv)


if __name__ == "__main__":
    main()
