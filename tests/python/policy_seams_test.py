"""Seams between chunks of a policy that infers while the arm moves, on the in-process Sim.

A synthetic flow-like policy (a smooth random curve, each chunk sampled with its own offset and
per-action noise) runs under comply.policy.PolicyRunner at 15, 30 and 50 Hz, with chunks of 16
and 50 actions, inference delays of 0 to 20 steps with +-30 % jitter and a 0.7 s first inference,
plainly replacing chunks and with the host's frozen prefix (mode "frozen"). For every chunk:

- the committed prefix the host gave at its observation (Sim.committed, every cycle of the chunk
  before) equals the reference the cycles then executed (from the recording) to 1e-9, up to the
  next takeover;
- the host's count of waypoints already past equals the one worked out here from when the chunk
  was sent and where it takes over (0 steps of error);
- the reference's per-cycle velocity change against the same change of the plan, cycle by
  cycle: each chunk's own curve from its takeover to the next (a cubic Hermite through it,
  evaluated here independently of the player, joined to the committed velocity where the chunk
  waited for its takeover). Keeping the committed prefix (frozen), every seam joins and the
  change never exceeds the plan's by more than 1e-6 m/s; a replaced chunk is blended in and the
  excess is reported;
- the tracking RMSE against the same chunks executed without latency (each from its
  observation), reported;

and LeRobot PR #4223's start: from standstill, a 0.7 s warm-up, 30 actions at 30 Hz: the host
counts 21 actions past and the reference meets every action after its blend. Prints the table.
Usage: policy_seams_test.py SOURCE_DIR."""

import math
import os
import sys
import tempfile

import numpy as np

import comply
from comply.policy import PolicyRunner, inpaint, keep_steps

BLEND_S = 0.1  # chunk_blend_time_s of the controller file


class FlowLikePolicy:
    """A smooth random curve (two sines per axis, up to 0.1 m/s) planned from the observed
    reference, sampled with noise: each chunk its own offset (1 mm) and every action its own
    (0.1 mm), as samples of a flow policy disagree."""

    def __init__(self, start, orientation, seed):
        rng = np.random.default_rng(seed)
        self.start, self.orientation, self.rng = start, orientation, rng
        self.amplitude = rng.uniform(0.005, 0.015, (3, 2))
        self.omega = 2 * math.pi * rng.uniform(0.2, 0.5, (3, 2))
        self.phase = rng.uniform(0, 2 * math.pi, (3, 2))

    def plan(self, t):
        wave = self.amplitude * (np.sin(self.omega * t + self.phase) - np.sin(self.phase))
        return self.start + wave.sum(axis=1)

    def __call__(self, ctx):
        # Planned from where the observation says the reference is.
        offset = (ctx["observation"]["reference_position"] - self.plan(ctx["time"]) +
                  self.rng.normal(0.0, 0.001, 3))
        planned = [self.plan(ctx["time"] + k * ctx["dt"]) + offset + self.rng.normal(0.0, 0.0001, 3)
                   for k in range(ctx["horizon"])]
        # With a committed prefix (mode "frozen"): the kept actions, then back onto the plan over
        # half the rest.
        fade = max(5, (ctx["horizon"] - keep_steps(ctx)) // 2)
        return [{"time": k * ctx["dt"], "position": position, "orientation": self.orientation}
                for k, position in enumerate(inpaint(planned, ctx, fade))]


def hermite(times, points, t, joined=None):
    """The chunk's curve's position and velocity at `t` (docs/chunks.md's rules: interval-weighted
    mean of the neighbouring secants, the secant at the first waypoint, zero at the last; holds
    outside). `joined`: (waypoint, velocity) where a chunk that waited for its takeover joins the
    reference in force, which sets that waypoint's velocity."""
    n = len(times)
    if t < times[0]:
        return points[0], np.zeros(3)
    if t >= times[-1]:
        return points[-1], np.zeros(3)
    secants = np.diff(points, axis=0) / np.diff(times)[:, None]
    slopes = np.zeros_like(points)
    slopes[0] = secants[0]
    for k in range(1, n - 1):
        h0, h1 = times[k] - times[k - 1], times[k + 1] - times[k]
        slopes[k] = (h1 * secants[k - 1] + h0 * secants[k]) / (h0 + h1)
    if joined is not None:
        slopes[joined[0]] = joined[1]
    k = np.searchsorted(times, t, side="right") - 1
    h = times[k + 1] - times[k]
    s = (t - times[k]) / h
    h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2
    d00, d10, d01, d11 = 6 * s * s - 6 * s, 3 * s * s - 4 * s + 1, -6 * s * s + 6 * s, 3 * s * s - 2 * s
    position = h00 * points[k] + h10 * h * slopes[k] + h01 * points[k + 1] + h11 * h * slopes[k + 1]
    velocity = (d00 * points[k] + d10 * h * slopes[k] + d01 * points[k + 1] +
                d11 * h * slopes[k + 1]) / h
    return position, velocity


def plan_velocity(took, contexts, records, dt, horizon, t):
    """The velocity of the plan in force at `t`: the chunk that took over last at or before it,
    on its own curve (joined to the committed velocity at its takeover waypoint if it waited)."""
    r = None
    for candidate in took:
        if candidate["timing"]["takeover"] <= t + 1e-12:
            r = candidate
    times = r["observation"] + dt * np.arange(horizon)
    points = np.array([w["position"] for w in r["chunk"]])
    joined = None
    timing = r["timing"]
    if r["keep"] is not None and abs(timing["takeover"] - timing["requested_takeover"]) < 1e-9:
        committed = contexts[records.index(r)]
        joined = (r["keep"], committed["twist"][r["keep"]][:3])
    return hermite(times, points, t, joined)[1]


def expected_past(record, dt, horizon, period):
    """Waypoints before the chunk's takeover, worked out from when it was sent: at once (the cycle
    it reached), or, when it keeps the running chunk until its waypoint `keep` and arrived before
    it, that waypoint's time."""
    takeover = record["sent_at"]
    if record["keep"] is not None:
        takeover = max(takeover, record["observation"] + record["keep"] * dt)
    times = record["observation"] + dt * np.arange(horizon)
    return int(np.sum(times < takeover - 1e-9))


def run_scenario(source, rate_hz, horizon, delay_steps, mode, seed, seconds=3.0, first_s=0.7):
    dt = 1.0 / rate_hz
    rng = np.random.default_rng(seed)
    inferences = []
    contexts = []  # the committed prefix at each observation, on the policy's steps
    delays = []

    def delay():
        delays.append(first_s if not delays else delay_steps * dt * (1.0 + rng.uniform(-0.3, 0.3)))
        return delays[-1]

    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "seams.mcap")
        sim = comply.Sim(f"{source}/config/sim/cartesian_impedance.yaml", robot="fr3",
                         record=path)
        obs = sim.reset()
        policy = FlowLikePolicy(obs["tcp_position"].copy(), obs["tcp_orientation"].copy(), seed)
        period = sim.period

        def observed(ctx):
            # What the host commits to from this observation on, every cycle of the chunk before.
            cycles = int(round(horizon * dt / period))
            inferences.append(sim.committed(ctx["time"], period, cycles))
            contexts.append(sim.committed(ctx["time"], dt, horizon))
            return policy(ctx)

        runner = PolicyRunner(sim, observed, dt=dt, horizon=horizon, mode=mode,
                              inference_delay=delay)
        runner.run(seconds, observation=obs)
        sim.close()
        cycles = comply.read_recording(path)["/comply/cycle"]
        stamp = cycles["state.header.stamp.sec"] + 1e-9 * cycles["state.header.stamp.nanosec"]
        reference = cycles["cartesian_in_force.position"]
        twist = cycles["cartesian_in_force.twist"][:, :3]
    return evaluate(runner, inferences, contexts, stamp, reference, twist, dt, horizon, period)


def evaluate(runner, inferences, contexts, stamp, reference, twist, dt, horizon, period):
    index = {round(t / period): i for i, t in enumerate(stamp)}
    records = runner.records
    took = [r for r in records if r["timing"] and r["timing"]["end"] == "took_over"]
    takeovers = sorted(r["timing"]["takeover"] for r in took)
    prefix_error = 0.0
    for committed, record in zip(inferences, records):
        later = [t for t in takeovers if t >= record["observation"] - 1e-9]
        until = later[0] if later else math.inf
        for t, p in zip(committed["time"], committed["position"]):
            i = index.get(round(t / period))
            if t < until - 1e-9 and i is not None and t <= stamp[-1]:
                prefix_error = max(prefix_error, float(np.abs(p - reference[i]).max()))
    delay_error = max((abs(r["timing"]["waypoints_past"] -
                           expected_past(r, dt, horizon, period)) for r in took), default=0)
    # The first chunk after the warm-up starts from rest: its seam is reported apart.
    steady = took[1:]
    # Per-cycle velocity change from the second takeover on: the reference's against the plan's
    # (the chunks' own curves, each from its takeover to the next, evaluated here), cycle by cycle.
    excess = velocity_error = plan_step = 0.0
    if steady:
        start = index.get(round(steady[0]["timing"]["takeover"] / period), len(stamp))
        plan = np.array([plan_velocity(took, contexts, records, dt, horizon, t)
                         for t in stamp[start:]])
        if len(plan) > 1:
            reference_step = np.abs(np.diff(twist[start:], axis=0)).max(axis=1)
            planned_step = np.abs(np.diff(plan, axis=0)).max(axis=1)
            excess = float((reference_step - planned_step).max())
            plan_step = float(planned_step.max())
            velocity_error = float(np.abs(twist[start:] - plan).max())
    return {"chunks": len(records), "took_over": len(took),
            "refused": sum(1 for r in records if r.get("refused")),
            "prefix_error": prefix_error, "delay_error": delay_error,
            "first": took[0]["timing"] if took else None,
            "position_jump": max((r["timing"]["position_jump"] for r in steady), default=0.0),
            "velocity_jump": max((r["timing"]["velocity_jump"] for r in steady), default=0.0),
            "excess": excess, "plan_dv": plan_step, "velocity_error": velocity_error,
            "joined": sum(1 for r in steady if r["keep"] is not None and
                          abs(r["timing"]["takeover"] - r["timing"]["requested_takeover"]) < 1e-9),
            "steady": len(steady),
            "delays": [r["timing"]["waypoints_past"] for r in took],
            "reference": (stamp, reference), "records": records}


def check_warm_start(source):
    """LeRobot PR #4223: from standstill a 0.7 s first inference, 30 actions at 30 Hz. The host
    counts the 21 actions whose time passed during the warm-up, blends in from rest, and the
    reference then meets every action it reaches (to 1e-9) until the next chunk takes over."""
    dt, horizon = 1.0 / 30.0, 30
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "warm.mcap")
        sim = comply.Sim(f"{source}/config/sim/cartesian_impedance.yaml", robot="fr3",
                         record=path)
        obs = sim.reset()
        start = obs["tcp_position"].copy()

        def policy(ctx):  # 2 cm/s along y from where the observation's reference is
            origin = ctx["observation"]["reference_position"]
            return [{"time": k * dt, "position": origin + [0.0, 0.02 * k * dt, 0.0],
                     "orientation": obs["tcp_orientation"]} for k in range(horizon)]

        delays = iter([0.7] + [0.3] * 100)
        runner = PolicyRunner(sim, policy, dt=dt, horizon=horizon, replan_steps=15,
                              inference_delay=lambda: next(delays))
        runner.run(1.5, observation=obs)
        sim.close()
        cycles = comply.read_recording(path)["/comply/cycle"]
    period = 0.001
    stamp = cycles["state.header.stamp.sec"] + 1e-9 * cycles["state.header.stamp.nanosec"]
    reference = cycles["cartesian_in_force.position"]
    first, second = runner.records[0], runner.records[1]
    assert first["timing"]["waypoints_past"] == 21, first["timing"]
    assert abs(first["timing"]["takeover"] - 0.7) < 1e-9, first["timing"]
    met = 0
    for k in range(horizon):
        t = first["observation"] + k * dt
        i = int(round(t / period))
        on_grid = abs(stamp[i] - t) < 1e-9
        if on_grid and 0.7 + BLEND_S <= t < second["timing"]["takeover"] - 1e-9:
            action = start + [0.0, 0.02 * k * dt, 0.0]
            assert np.abs(reference[i] - action).max() < 1e-9, (k, reference[i], action)
            met += 1
    assert met >= 2, met
    print(f"warm start: {first['timing']['waypoints_past']} of 30 actions past at "
          f"{first['timing']['takeover']:.3f} s, seam {1000 * first['timing']['position_jump']:.2f}"
          f" mm, then {met} actions on the cycle grid met to 1e-9")


def check_runner_options():
    """Temporal ensembling averages the chunks' actions for the same time, the oldest weighted
    exp(0), the next exp(-m); a mode that does not exist is refused."""
    runner = PolicyRunner(object(), None, dt=0.1, horizon=3, mode="ensemble", ensemble_decay=0.5)
    first = [{"time": 0.1 * k, "position": [1.0 * k, 0.0, 0.0]} for k in range(3)]
    runner._ensembled(first, 0.0)
    second = [{"time": 0.1 * k, "position": [10.0, 0.0, 0.0]} for k in range(3)]
    sent = runner._ensembled(second, 0.1)  # at 0.1 and 0.2 both planned, at 0.3 only the new
    w = math.exp(-0.5)
    assert abs(sent[0]["position"][0] - (1.0 + w * 10.0) / (1.0 + w)) < 1e-12, sent
    assert abs(sent[1]["position"][0] - (2.0 + w * 10.0) / (1.0 + w)) < 1e-12, sent
    assert sent[2]["position"][0] == 10.0, sent
    try:
        PolicyRunner(object(), None, dt=0.1, horizon=3, mode="average")
    except ValueError as error:
        assert "replace, frozen, ensemble" in str(error), error
    else:
        raise AssertionError("an unknown mode was taken")


def tracking_rmse(r, dt, horizon):
    """RMS distance [m] between the executed reference and the same chunks executed without
    latency (each from its observation on, until the next one's observation), from the first
    takeover plus the blend on: what acting on older observations cost."""
    stamp, reference = r["reference"]
    took = sorted((x for x in r["records"] if x["timing"] and x["timing"]["end"] == "took_over"),
                  key=lambda x: x["observation"])
    if not took:
        return float("nan")
    begin = int(np.searchsorted(stamp, took[0]["timing"]["takeover"] + BLEND_S))
    squares = []
    for t, executed in zip(stamp[begin:], reference[begin:]):
        chunk = [x for x in took if x["observation"] <= t + 1e-12][-1]
        times = chunk["observation"] + dt * np.arange(horizon)
        points = np.array([w["position"] for w in chunk["chunk"]])
        squares.append(np.sum((executed - hermite(times, points, t)[0]) ** 2))
    return float(np.sqrt(np.mean(squares))) if squares else float("nan")


def main():
    source = sys.argv[1]
    check_runner_options()
    check_warm_start(source)

    print("| rate [Hz] | actions | delay [steps] | mode | chunks | took over | refused | "
          "prefix error [m] | delay error [steps] | seams joined | max seam jump [mm] | "
          "max seam velocity jump [m/s] | dv/cycle over the plan's [m/s] | plan dv/cycle [m/s] | "
          "RMSE vs no latency [mm] | delays (host) |")
    print("|" + "---|" * 16)
    failures = []
    for rate in (15, 30, 50):
        for horizon in (16, 50):
            for delay_steps in (0, 5, 10, 20):
                for mode in ("replace", "frozen"):
                    r = run_scenario(source, rate, horizon, delay_steps, mode, seed=rate + horizon)
                    rmse = tracking_rmse(r, 1.0 / rate, horizon)
                    print(f"| {rate} | {horizon} | {delay_steps} | {mode} | {r['chunks']} | "
                          f"{r['took_over']} | {r['refused']} | {r['prefix_error']:.1e} | "
                          f"{r['delay_error']} | {r['joined']}/{r['steady']} | "
                          f"{1000 * r['position_jump']:.2f} | {r['velocity_jump']:.3f} | "
                          f"{r['excess']:+.1e} | {r['plan_dv']:.5f} | {1000 * rmse:.2f} | "
                          f"{sorted(set(r['delays']))[:6]} |", flush=True)
                    name = f"{rate} Hz {horizon} {delay_steps} {mode}"
                    if r["prefix_error"] > 1e-9:
                        failures.append(f"{name}: prefix {r['prefix_error']:.2e}")
                    if r["delay_error"] != 0:
                        failures.append(f"{name}: delay off by {r['delay_error']}")
                    # Keeping the committed prefix, every seam joins the curve in force and the
                    # reference is never rougher than the plan (a replaced chunk is blended in).
                    if mode == "frozen" and r["joined"] != r["steady"]:
                        failures.append(f"{name}: {r['steady'] - r['joined']} seams not joined")
                    if mode == "frozen" and r["excess"] > 1e-6:
                        failures.append(f"{name}: velocity change {r['excess']:.2e} over the "
                                        "plan's in a cycle")
    for failure in failures:
        print("FAIL", failure)
    if failures:
        sys.exit(1)
    print("ok")


if __name__ == "__main__":
    main()
