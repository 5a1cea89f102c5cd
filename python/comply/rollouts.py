"""Many episodes of comply.Sim in one call, spread over worker processes with dask.distributed
(on this machine or a cluster of them), with a row of results per episode (docs/rollouts.md).

    import comply

    def stiffness_sweep(episode, rng, obs):     # once per episode, with its first step
        return {"position": obs["tcp_position"] + [0.0, 0.0, -0.03],
                "stiffness_translational": [3000, 3000, 200 + 50 * episode]}

    results = comply.rollouts(comply.Schedule(stiffness_sweep), 200,
                              config="config/sim/cartesian_impedance.yaml", seconds=2.0)
    print(results.summary())
    results.column("tracking_error_rms_m"), results.to_csv("sweep.csv")

A policy called before every step is any other callable, `policy(observation, context)` with
context = dict(episode, step, time, rng), returning a command (a dict of schema keywords), a
timed chunk or None. Episode `e` draws from numpy.random.default_rng([seed, e]) whichever worker
runs it, so the rows do not depend on how the episodes were spread: cluster="serial" (every
episode in this process, no dask) gives the same numbers.

dask is imported only when a call uses it: `import comply` works where it is not installed.
"""

import math
import os
import socket
import sys
import threading
import time
import uuid

import numpy as np

from .rollout_results import RolloutResults

_SERIAL = "serial"

# A worker process's Sims, one per (config, robot, steps_per_action, thread): reset() gives a
# fresh plant, so a Sim carries nothing from one episode to the next, and building it (parsing
# the robot, the controller, the MuJoCo model) is not paid per episode. Keyed by thread too, as
# a Client with several threads per worker runs episodes at once.
_SIMS = {}


class RolloutError(RuntimeError):
    """An episode raised; `episode` is its index, the original exception its __cause__."""

    def __init__(self, episode, message):
        super().__init__(episode, message)  # both in args, so that it pickles
        self.episode = episode

    def __str__(self):
        return self.args[1]

    @classmethod
    def of(cls, episode, error):
        return cls(episode, f"episode {episode} failed: {type(error).__name__}: {error}")


class Schedule:
    """A command per episode, not per step: `fn(episode, rng, observation)` returns the command
    (a dict of schema keywords, a timed chunk or None) sent with the episode's first step, from
    reset()'s observation; the episode then runs on it. A stiffness sweep, a target per episode,
    a chunk planned once."""

    def __init__(self, fn):
        if not callable(fn):
            raise TypeError(f"Schedule(fn): fn must be callable, not {type(fn).__name__}")
        self.fn = fn

    def __repr__(self):
        return f"Schedule({getattr(self.fn, '__name__', self.fn)!r})"


def rollouts(policy_or_schedule, episodes, cluster=None, *, config, robot="fr3", seconds=2.0,
             steps_per_action=50, seed=0, record=None, dataset=None, fps=30.0, task=None,
             success=None, progress=True, cameras=None):
    """Runs `episodes` episodes of comply.Sim(config, robot, steps_per_action): each a reset(),
    then steps until `seconds` of simulated time or termination (a FAULT). Returns
    RolloutResults, a row per episode in episode order.

    policy_or_schedule: a Schedule (a command per episode, sent with the first step) or a
      callable policy(observation, context) called before every step, context =
      dict(episode, step, time, rng); either returns a command dict, a timed chunk or None.
      Both run on the workers: they must pickle (cloudpickle takes lambdas and closures; a
      function of another module pickles by name, so that module must import on the workers)
      and what they change in their own state stays on the worker.
    cluster: None, a LocalCluster of os.cpu_count() single-threaded worker processes made and
      closed by the call; "serial", every episode in this process without dask; a scheduler's
      address ("tcp://host:8786") to spread over the machines of its workers; a
      distributed.Client, used as is and left open (or a distributed Cluster, which gets a
      client of its own).
    seed: episode e draws from numpy.random.default_rng([seed, e]), whichever worker runs it.
    success: success(observations, infos) -> bool, run on the worker with the episode's
      observations (reset()'s, then one per step) and infos (one per step); by default an
      episode succeeds when it did not terminate, no reflex tripped and every command was
      accepted.
    record: a folder (created) in which the worker that runs episode e records it to
      episode-{e:06d}.mcap (one Sim per episode). The workers write there themselves: spread
      over machines, it must be on a filesystem they all share, at the same path.
    dataset: a folder for a LeRobot dataset of every episode (comply.export_lerobot, in this
      process at the end, at `fps`, with `task`, default "comply rollout"); implies recording,
      to dataset/recordings when record is None.
    progress: a line to stderr per tenth of the episodes done.
    cameras: the Sim's cameras (Sim(cameras=...), docs/simulation.md#cameras): the policy sees
      observation["images"], and recorded episodes (and a dataset's videos) keep the frames.

    `config` and the recordings' folder are made absolute here: a worker on another machine
    needs them at the same path. Worker processes start by spawning, which imports the calling
    script again: a script that calls this needs `if __name__ == "__main__":`. An episode that
    raises raises RolloutError here, naming it.
    """
    episodes = int(episodes)
    if episodes < 1:
        raise ValueError(f"episodes must be at least 1, not {episodes}")
    if not callable(policy_or_schedule) and not isinstance(policy_or_schedule, Schedule):
        raise TypeError("rollouts() takes a comply.Schedule or a callable policy(observation, "
                        f"context), not {type(policy_or_schedule).__name__}")
    if not seconds > 0.0:
        raise ValueError(f"seconds must be > 0, not {seconds}")
    started = time.perf_counter()
    recording_dir = record
    if dataset is not None and recording_dir is None:
        recording_dir = os.path.join(dataset, "recordings")
    if recording_dir is not None:
        recording_dir = os.path.abspath(recording_dir)
        os.makedirs(recording_dir, exist_ok=True)
    spec = {
        "policy": policy_or_schedule,
        "config": os.path.abspath(config) if os.path.exists(config) else config,
        "robot": robot,
        "seconds": float(seconds),
        "steps_per_action": int(steps_per_action),
        "seed": int(seed),
        "record": recording_dir,
        "success": success,
        "cameras": cameras,
    }
    reporter = _Progress(episodes, started, progress)
    if isinstance(cluster, str) and cluster == _SERIAL:
        rows, workers, startup_s = _run_serial(spec, episodes, reporter), 1, 0.0
    else:
        rows, workers, startup_s = _run_distributed(spec, episodes, cluster, reporter)
    recordings = ([_recording_path(recording_dir, e) for e in range(episodes)]
                  if recording_dir is not None else [])
    summary = None
    if dataset is not None:
        from . import export_lerobot  # the extension's, which a source checkout may lack

        summary = export_lerobot(dataset, recordings, fps=fps, task=task or "comply rollout",
                                 robot_type=robot)
    return RolloutResults(rows, recordings=recordings, dataset=summary,
                          wall_s=time.perf_counter() - started, startup_s=startup_s,
                          workers=workers, steps_per_action=int(steps_per_action))


# ---- the caller's side ------------------------------------------------------------------------

class _Progress:
    """A line per tenth of the episodes: done / total, elapsed, steps/s so far."""

    def __init__(self, total, started, enabled):
        self.total, self.started, self.enabled = total, started, enabled
        self.done = self.steps = 0
        self.next_line = 1

    def episode_done(self, row):
        self.done += 1
        self.steps += row["steps"]
        if not self.enabled or self.done * 10 < self.next_line * self.total:
            return
        while self.done * 10 >= self.next_line * self.total:
            self.next_line += 1  # with fewer than 10 episodes, some tenths share a line
        elapsed = time.perf_counter() - self.started
        rate = self.steps / elapsed if elapsed > 0 else 0.0
        print(f"rollouts: {self.done}/{self.total} episodes, {elapsed:.1f} s, "
              f"{rate:.0f} steps/s", file=sys.stderr, flush=True)


def _run_serial(spec, episodes, reporter):
    sims = {}  # this call's, not the module's: the Sim goes when the call returns
    rows = []
    for episode in range(episodes):
        try:
            row = _run_episode(spec, episode, sims)
        except Exception as error:
            raise RolloutError.of(episode, error) from error
        rows.append(row)
        reporter.episode_done(row)
    return rows


def _run_distributed(spec, episodes, cluster, reporter):
    try:
        import distributed
    except ImportError as missing:
        if cluster is None or isinstance(cluster, str):
            raise ImportError("rollouts() over processes needs dask.distributed (Debian: "
                              "python3-distributed); cluster='serial' runs without it") from missing
        raise TypeError(_cluster_type_message(cluster)) from missing
    made = []  # what this call made, closed by it in reverse order
    begun = time.perf_counter()
    try:
        if cluster is None:
            local = distributed.LocalCluster(n_workers=os.cpu_count(), threads_per_worker=1,
                                             processes=True, dashboard_address=None)
            made.append(local)
            client = distributed.Client(local)
            made.append(client)
        elif isinstance(cluster, str):
            client = distributed.Client(cluster)
            made.append(client)
        elif isinstance(cluster, distributed.Client):
            client = cluster
        elif isinstance(cluster, distributed.deploy.Cluster):
            client = distributed.Client(cluster)
            made.append(client)
        else:
            raise TypeError(_cluster_type_message(cluster))
        startup_s = time.perf_counter() - begun if made else 0.0
        workers = len(client.scheduler_info().get("workers", {}))
        rows = _gather_in_order(distributed, client, spec, episodes, reporter)
        return rows, workers, startup_s
    finally:
        for thing in reversed(made):
            thing.close()


def _cluster_type_message(cluster):
    return (f"cluster must be None (a local cluster), 'serial', a scheduler address, a "
            f"distributed.Client or a distributed Cluster, not {type(cluster).__name__}")


def _gather_in_order(distributed, client, spec, episodes, reporter):
    # The spec (the policy with it) travels once to the cluster, not once per episode.
    [spec_future] = client.scatter([spec], broadcast=True, hash=False)
    token = uuid.uuid4().hex[:8]
    futures = {}
    for episode in range(episodes):
        future = client.submit(_run_episode_on_worker, spec_future, episode, pure=False,
                               key=f"comply-rollout-{token}-{episode:06d}")
        futures[future] = episode
    rows = [None] * episodes
    for future in distributed.as_completed(futures):
        episode = futures[future]
        if future.status == "error":
            error = future.exception()
            # The rest are still queued: a client that outlives the call must not run them.
            client.cancel([f for f in futures if not f.done()] + [spec_future])
            raise RolloutError.of(episode, error) from error
        rows[episode] = future.result()
        reporter.episode_done(rows[episode])
    return rows


def _recording_path(folder, episode):
    return os.path.join(folder, f"episode-{episode:06d}.mcap")


# ---- the worker's side ------------------------------------------------------------------------

def _run_episode_on_worker(spec, episode):
    return _run_episode(spec, episode, _SIMS)


def _run_episode(spec, episode, sims):
    """One episode: reset(), then steps until spec["seconds"] of simulated time or a FAULT.
    `sims` caches unrecorded Sims; a recorded episode has a Sim (and a file) of its own."""
    from . import Sim  # at call time: the package imports this module before the extension

    begun = time.perf_counter()
    if spec["record"] is not None:
        sim = Sim(spec["config"], robot=spec["robot"], steps_per_action=spec["steps_per_action"],
                  record=_recording_path(spec["record"], episode), cameras=spec["cameras"])
        try:
            row = _play(sim, spec, episode)
        finally:
            sim.close()
    else:
        key = (spec["config"], spec["robot"], spec["steps_per_action"], repr(spec["cameras"]),
               threading.get_ident())
        sim = sims.get(key)
        if sim is None:
            sim = sims[key] = Sim(spec["config"], robot=spec["robot"],
                                  steps_per_action=spec["steps_per_action"],
                                  cameras=spec["cameras"])
        row = _play(sim, spec, episode)
    row["worker"] = f"{socket.gethostname()}/{os.getpid()}"
    row["wall_s"] = time.perf_counter() - begun
    return row


def _play(sim, spec, episode):
    policy = spec["policy"]
    rng = np.random.default_rng([spec["seed"], episode])
    obs = sim.reset()
    cycle_s = sim.period * spec["steps_per_action"]
    # The last step ends at or past `seconds`; a nanosecond's slack for 0.5 s / 0.05 s's rounding.
    steps_wanted = max(1, math.ceil(spec["seconds"] / cycle_s - 1e-9))
    cartesian = sim.cartesian
    observations, infos = [obs], []
    errors = np.empty(steps_wanted)
    max_force_n = 0.0
    rejected = 0
    terminated = reflex = False
    scheduled = isinstance(policy, Schedule)
    for step in range(steps_wanted):
        if scheduled:
            command = policy.fn(episode, rng, obs) if step == 0 else None
        else:
            command = policy(obs, {"episode": episode, "step": step, "time": obs["time"],
                                   "rng": rng})
        obs, _, terminated, truncated, info = sim.step(command)
        observations.append(obs)
        infos.append(info)
        if cartesian:
            errors[step] = np.linalg.norm(obs["tcp_position"] - obs["reference_position"])
        else:
            errors[step] = np.linalg.norm(obs["position"] - obs["reference_joint_position"])
        max_force_n = max(max_force_n, float(np.linalg.norm(obs["contact_wrench"][:3])))
        rejected += not info["accepted"]
        reflex = reflex or bool(obs["reflex_tripped"])
        if terminated or truncated:
            break
    steps = len(infos)
    errors = errors[:steps]
    if spec["success"] is not None:
        succeeded = bool(spec["success"](observations, infos))
    else:
        succeeded = not terminated and not reflex and rejected == 0
    unit = "m" if cartesian else "rad"
    return {
        "episode": episode,
        "seed": spec["seed"],
        "steps": steps,
        "sim_time_s": float(obs["time"]),
        "success": succeeded,
        "terminated": bool(terminated),
        f"tracking_error_rms_{unit}": float(np.sqrt(np.mean(errors**2))),
        f"tracking_error_max_{unit}": float(errors.max()),
        "max_contact_force_n": max_force_n,
        "energy_injected_j": float(obs["energy_injected"]),
        "energy_dissipated_j": float(obs["energy_dissipated"]),
        "rejected": rejected,
    }
