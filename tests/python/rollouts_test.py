"""comply.rollouts over dask.distributed against the same episodes in this process.

A two-worker LocalCluster gives exactly the rows cluster="serial" gives (every column but the
wall time and the worker's name, compared with ==), for a seeded Schedule (random targets and
stiffnesses per episode) and for a policy called every step; the rows come back in episode order
when the episodes finish out of it; another seed gives other rows (so the comparison can fail).
record= writes one MCAP per episode with every cycle, dataset= a LeRobot dataset of every
episode; an episode that raises on a worker raises here naming it. Skipped without
dask.distributed. Usage: rollouts_test.py SOURCE_DIR (the build's python/ on PYTHONPATH, which
the workers inherit)."""

import csv
import json
import os
import sys
import tempfile
import time

import numpy as np

import comply

EPISODES = 6
SECONDS = 0.5
STEPS_PER_ACTION = 50  # 20 Hz at 1 kHz: 10 steps per episode
VOLATILE = ("wall_s", "worker")  # where and how fast, not what happened


def random_target(episode, rng, obs):
    """Once per episode: a target up to 2 cm away, anisotropic stiffness from the rng."""
    return {"position": obs["tcp_position"] + rng.uniform(-0.02, 0.02, 3),
            "stiffness_translational": rng.uniform(500.0, 4000.0, 3)}


def wandering(obs, context):
    """Every step: a small random move of the reference. Episode 0 thinks for a while first, so
    the episodes finish out of order on two workers."""
    if context["episode"] == 0 and context["step"] == 0:
        time.sleep(1.0)
    if context["step"] % 3 == 2:
        return None  # hold: None sends nothing
    return {"position": obs["reference_position"] + context["rng"].normal(0.0, 0.003, 3)}


def fails_on_three(obs, context):
    if context["episode"] == 3 and context["step"] == 4:
        raise ValueError("the policy gave up")
    return None


def outcome(results):
    return [{k: v for k, v in row.items() if k not in VOLATILE} for row in results.rows]


def check_rows(results, episodes):
    assert len(results) == episodes, len(results)
    assert np.array_equal(results.column("episode"), np.arange(episodes)), results.column("episode")
    steps = round(SECONDS / (STEPS_PER_ACTION * 0.001))
    assert np.all(results.column("steps") == steps), results.column("steps")
    assert np.allclose(results.column("sim_time_s"), SECONDS), results.column("sim_time_s")
    assert results.column("success").all(), results.rows
    assert np.all(results.column("tracking_error_max_m") >= results.column("tracking_error_rms_m"))


def check_same(serial, spread, what):
    a, b = outcome(serial), outcome(spread)
    for row_a, row_b in zip(a, b):
        assert row_a == row_b, f"{what}: serial {row_a} != 2 workers {row_b}"


def check_recordings(results, episodes):
    assert len(results.recordings) == episodes, results.recordings
    for episode, path in enumerate(results.recordings):
        assert os.path.basename(path) == f"episode-{episode:06d}.mcap", path
        recording = comply.read_recording(path)
        assert not recording.truncated, path
        cycles = recording["/comply/cycle"]
        want = results.rows[episode]["steps"] * STEPS_PER_ACTION
        assert cycles.count == want, (path, cycles.count, want)
        assert np.array_equal(cycles["state.cycle"], np.arange(want)), path  # one episode


def main():
    source = sys.argv[1]
    try:
        import distributed
    except ImportError:
        print("skip: dask.distributed is not installed (Debian: python3-distributed)")
        return
    config = f"{source}/config/sim/cartesian_impedance.yaml"
    common = dict(config=config, robot="fr3", seconds=SECONDS, steps_per_action=STEPS_PER_ACTION,
                  progress=False)
    schedule = comply.Schedule(random_target)

    serial = comply.rollouts(schedule, EPISODES, "serial", seed=7, **common)
    check_rows(serial, EPISODES)
    other_seed = comply.rollouts(schedule, EPISODES, "serial", seed=8, **common)
    assert outcome(other_seed) != outcome(serial), "seeds 7 and 8 gave the same rows"
    serial_policy = comply.rollouts(wandering, EPISODES, "serial", seed=7, **common)
    check_rows(serial_policy, EPISODES)

    with tempfile.TemporaryDirectory() as folder, \
            distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                     dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        spread = comply.rollouts(schedule, EPISODES, client, seed=7, **common)
        check_rows(spread, EPISODES)
        check_same(serial, spread, "schedule")
        workers = set(spread.column("worker"))
        assert len(workers) == 2 and all(not w.endswith(f"/{os.getpid()}") for w in workers), \
            workers  # both workers imported the extension and ran episodes

        spread_policy = comply.rollouts(wandering, EPISODES, client, seed=7, **common)
        check_same(serial_policy, spread_policy, "policy")
        # Episode 0 slept 1 s on its worker; the other worker ran the rest meanwhile.
        assert spread_policy.rows[0]["wall_s"] > 1.0, spread_policy.rows[0]

        # Recording: one file per episode, written by the workers, each Sim built for it: the
        # same rows as the cached Sims gave.
        recorded = comply.rollouts(schedule, 3, client, seed=7, record=f"{folder}/rec", **common)
        check_same(serial, recorded, "recorded")
        check_recordings(recorded, 3)
        assert recorded.dataset is None

        try:
            comply.rollouts(fails_on_three, EPISODES, client, **common)
            raise AssertionError("the failing episode did not raise")
        except comply.RolloutError as error:
            assert error.episode == 3 and "episode 3" in str(error), error
            assert "the policy gave up" in str(error), error
        assert client.status == "running"  # a given client stays open, and usable
        again = comply.rollouts(schedule, 2, client, seed=7, **common)
        check_same(serial, again, "after an error")

        # The dataset, in this process, from recordings the call put under it.
        made = comply.rollouts(schedule, 3, "serial", seed=7, dataset=f"{folder}/ds",
                               task="random targets", success=lambda obs, infos: len(obs) == 11
                               and len(infos) == 10, **common)
        assert made.column("success").all(), made.rows
        assert made.dataset["episodes"] == 3, made.dataset
        assert made.recordings[0].startswith(f"{folder}/ds/recordings/"), made.recordings
        check_recordings(made, 3)
        with open(f"{folder}/ds/meta/info.json") as file:
            info = json.load(file)
        assert info["total_episodes"] == 3 and info["robot_type"] == "fr3", info

        made.to_csv(f"{folder}/rows.csv")
        with open(f"{folder}/rows.csv") as file:
            table = list(csv.DictReader(file))
        assert len(table) == 3 and float(table[2]["tracking_error_rms_m"]) == \
            made.rows[2]["tracking_error_rms_m"], table[2]

    # A joint controller's tracking error is in joint space, its columns in rad.
    joint = comply.rollouts(lambda obs, context: {"position": obs["reference_joint_position"] +
                                                  context["rng"].normal(0.0, 0.01, 7)},
                            2, "serial", **dict(common, config=f"{source}/config/sim/"
                                                "joint_impedance.yaml"))
    assert "tracking_error_rms_m" not in joint.rows[0], joint.rows[0]
    assert np.all(joint.column("tracking_error_rms_rad") > 0.0), joint.rows

    try:
        comply.rollouts(fails_on_three, EPISODES, "serial", **common)
        raise AssertionError("the failing episode did not raise")
    except comply.RolloutError as error:
        assert error.episode == 3 and isinstance(error.__cause__, ValueError), error
    for bad, kind in (((schedule, 0, "serial"), ValueError), ((schedule, 2, 42), TypeError)):
        try:
            comply.rollouts(*bad, **common)
            raise AssertionError(f"{bad} was accepted")
        except kind as error:
            assert "episodes" in str(error) or "cluster" in str(error), error
    print(serial.summary())
    print(spread.summary())
    print("ok")


if __name__ == "__main__":
    main()
