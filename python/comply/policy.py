"""Run a chunking policy on a comply host: observe, infer in the background, send the chunk
relative to its observation, and hand the next inference what only the host knows, the delay it
measured in the policy's own steps and the actions it has committed to (docs/policies.md).

    import comply
    from comply.policy import PolicyRunner

    def policy(ctx):                        # ctx: observation, dt, horizon, delay_steps, committed
        obs = ctx["observation"]
        return [{"time": k * ctx["dt"], "position": ..., "orientation": ...}
                for k in range(ctx["horizon"])]

    runner = PolicyRunner(comply.Sim("config/sim/cartesian_impedance.yaml", robot="fr3"),
                          policy, dt=1 / 30, horizon=16, inference_delay=lambda: 0.15)
    runner.run(seconds=5.0)
    print(runner.delays())                  # the host's count per chunk

On a `Sim` the inference runs in simulated time: the chunk reaches the host `inference_delay()`
seconds after its observation (a number or a callable, e.g. with jitter), and the arm moves on
meanwhile. On a `Client` the policy runs in a background thread on the wall clock, and the chunk
is sent when it returns.

Modes (`mode`):
- "replace" (default): each chunk replaces the last from the cycle it arrives in; the host blends
  the seam over chunk_blend_time_s.
- "frozen": real-time chunking (Black, Galliker, Levine 2025): the policy is given the host's
  committed actions for the expected delay (ctx["committed"], from the host's own chunk player)
  to keep, and the chunk takes over at waypoint `delay_steps` (the host's newest count, at least
  1), so the takeover point is explicit. When inference ran past that waypoint, the runner keeps
  the committed actions up to the first waypoint still ahead when the chunk reaches the host and
  takes over there (inpaint()), so the seam stays on the committed curve. The first chunk's count
  measures the warm-up from standstill, not the delay while the arm moves: it is not handed on.
- "ensemble": temporal ensembling (ACT, Zhao et al. 2023): each sent chunk is the exponentially
  weighted mean (weight exp(-ensemble_decay * i), i = 0 for the oldest) of every chunk's action
  for the same time, the new one's where it alone plans.
"""

import math
import threading
import time

import numpy as np

_MODES = ("replace", "frozen", "ensemble")


def keep_steps(ctx):
    """The waypoint a chunk planned in `ctx` takes over at in mode "frozen": the host's delay
    count, at least 1 and short of the chunk's end."""
    return min(max(1, ctx["delay_steps"]), ctx["horizon"] - 1)


def inpaint(planned, ctx, fade_steps=5, keep=None):
    """A chunk's positions (an array, a row per action) that keep the host's committed actions
    up to waypoint `keep` (default keep_steps(ctx)), where it takes over, and then ease back onto
    `planned` over `fade_steps` actions, leaving the committed curve with its velocity there: a
    stand-in for the guided inpainting of real-time chunking, for policies that cannot condition
    on the prefix. `planned` as is when ctx holds no committed prefix.

    The host joins a chunk that waits for its takeover to the reference's velocity at that
    waypoint (docs/policies.md); a chunk that turned there within one step would ask the arm for
    that turn in one step."""
    planned = np.asarray(planned, dtype=float)
    committed = ctx["committed"]
    if committed is None or not committed["known"]:
        return planned
    keep = keep_steps(ctx) if keep is None else keep
    dt = ctx["dt"]
    velocity = committed["twist"][:, :3] if "twist" in committed else committed["velocity"]
    out = planned.copy()
    out[:keep + 1] = committed["position"][:keep + 1]
    # The planned curve's velocity at the takeover: its central difference (one-sided at an end).
    before, after = max(keep - 1, 0), min(keep + 1, len(planned) - 1)
    planned_velocity = (planned[after] - planned[before]) / ((after - before) * dt)
    gap = committed["position"][keep] - planned[keep]
    gap_velocity = velocity[keep] - planned_velocity
    length = fade_steps * dt
    for k in range(keep + 1, min(len(out), keep + fade_steps)):
        s = (k - keep) / fade_steps  # a cubic from the gap (and its rate) down to nothing
        out[k] += (2 * s**3 - 3 * s**2 + 1) * gap + (s**3 - 2 * s**2 + s) * length * gap_velocity
    return out


class PolicyRunner:
    def __init__(self, host, policy, *, dt, horizon, mode="replace", inference_delay=0.0,
                 replan_steps=None, ensemble_decay=0.01, arrival_margin_s=0.005):
        if mode not in _MODES:
            raise ValueError(f"mode {mode!r}: one of {', '.join(_MODES)}")
        if not dt > 0.0 or horizon < 2:
            raise ValueError("dt > 0 and a horizon of at least 2 actions")
        self.host = host
        self.policy = policy
        self.dt = float(dt)
        self.horizon = int(horizon)
        self.mode = mode
        self.replan_steps = int(replan_steps) if replan_steps else max(1, self.horizon // 2)
        self.ensemble_decay = float(ensemble_decay)
        # Client: from the chunk's send to the host's intake (DDS, the transport process).
        self.arrival_margin_s = float(arrival_margin_s)
        self._delay = inference_delay if callable(inference_delay) else (lambda: inference_delay)
        # A Sim steps simulated time; a Client (which has committed() and reset() too) does not.
        self._simulated = hasattr(host, "step")
        self.records = []  # one per chunk: sent, and the host's timing record once known
        self._delay_steps = 0
        self._ensemble = []  # (times, positions) of the chunks sent, for "ensemble"

    # ---- what a policy author reads ------------------------------------------------------------
    def delays(self):
        """The host's count of waypoints already past when each chunk took over (None while it
        has not)."""
        return [r["timing"]["waypoints_past"] if r.get("timing") else None for r in self.records]

    # ---- the loop --------------------------------------------------------------------------------
    def run(self, seconds, observation=None):
        """Runs for `seconds` of the host's time from `observation` (a Sim's reset() by default)."""
        if self._simulated:
            return self._run_sim(seconds, observation)
        return self._run_client(seconds)

    def _context(self, observation, observation_time):
        ctx = {"observation": observation, "time": observation_time, "dt": self.dt,
               "horizon": self.horizon, "delay_steps": self._delay_steps, "committed": None}
        if self.mode == "frozen":
            ctx["committed"] = self._committed(observation_time)
        return ctx

    def _committed(self, observation_time):
        """The host's committed prefix at the observation, where the host answers it."""
        if not hasattr(self.host, "committed"):
            return None
        return self.host.committed(observation_time, self.dt, self.horizon)

    def _chunk_to_send(self, chunk, ctx, elapsed_s):
        """The chunk as sent, and the waypoint it takes over at (None: at once). `elapsed_s`: how
        long after its observation the chunk will reach the host."""
        keep = None
        if self.mode == "frozen":
            keep = min(keep_steps(ctx), len(chunk) - 1)
            # The first waypoint still ahead when it arrives: a takeover before it would be one
            # the host has already passed, and the seam would leave the committed curve.
            # (Sent as planned when no chunk of this runner plays yet, the prefix then being the
            # arm at rest, or when its last waypoint is due by then: the host blends it in or
            # refuses it as late.)
            due = math.ceil(elapsed_s / self.dt - 1e-9)
            committed = ctx["committed"]
            if (keep < due < len(chunk) - 1 and self._took_over() and committed is not None
                    and committed["known"]):
                positions = inpaint([w["position"] for w in chunk], ctx, keep=due)
                chunk = [dict(w, position=p) for w, p in zip(chunk, positions)]
                keep = due
        elif self.mode == "ensemble":
            chunk = self._ensembled(chunk, ctx["time"])
        return chunk, keep

    def _took_over(self):
        """Whether a chunk of this runner has taken over: its curve is what the host commits to."""
        return any(r["timing"] and r["timing"]["end"] == "took_over" for r in self.records)

    def _ensembled(self, chunk, observation_time):
        times = np.array([observation_time + w["time"] for w in chunk])
        positions = np.array([np.asarray(w["position"], dtype=float) for w in chunk])
        self._ensemble = [(t, p) for t, p in self._ensemble if t[-1] >= times[0] - 1e-9]
        self._ensemble.append((times, positions))
        out = []
        for k, waypoint in enumerate(chunk):
            total, weight = np.zeros_like(positions[k]), 0.0
            for age, (t, p) in enumerate(self._ensemble):  # oldest first: i = 0
                match = np.flatnonzero(np.abs(t - times[k]) < 1e-6)
                if match.size:
                    w = math.exp(-self.ensemble_decay * age)
                    total, weight = total + w * p[match[0]], weight + w
            out.append(dict(waypoint, position=total / weight))
        return out

    def _note(self, stamp, observation_time, chunk, keep, sent_at, info=None):
        record = {"stamp": stamp, "observation": observation_time, "sent_at": sent_at,
                  "chunk": chunk, "keep": keep, "timing": None}
        self.records.append(record)
        if info is not None:
            self._take_timings(info.get("chunks", []))
        return record

    def _take_timings(self, timings):
        """Timing records from the host, each matched to the chunk sent on its observation."""
        for timing in timings:
            for record in self.records:
                if record["timing"] is None and abs(record["observation"] -
                                                    timing["observation"]) < 1e-6:
                    self._hand_on(record, timing)
                    break

    def _hand_on(self, record, timing):
        """Keeps a chunk's timing record; its count becomes the next inference's delay_steps,
        but for the first chunk's (the warm-up from standstill)."""
        record["timing"] = timing
        if timing["end"] == "took_over" and record is not self.records[0]:
            self._delay_steps = timing["waypoints_past"]

    def _next_observation(self, observation_time, keep, cycle_s=0.0):
        """replan_steps after this observation, but not before the cycle that takes the chunk just
        sent over has run (`cycle_s` after an observation on a Sim, which precedes its cycle): a
        chunk sent while it waits would supersede it, and the committed prefix the next inference
        keeps (which counts on its takeover) would not be executed."""
        later = observation_time + self.replan_steps * self.dt
        if keep is None:
            return later
        return max(later, observation_time + keep * self.dt + cycle_s)

    # ---- Sim: simulated time ---------------------------------------------------------------------
    def _run_sim(self, seconds, observation):
        sim = self.host
        obs = observation if observation is not None else sim.reset()
        period = sim.period
        end = obs["time"] + seconds
        while obs["time"] < end - 1e-9:
            observation_time = obs["time"]
            ctx = self._context(obs, observation_time)
            chunk = self.policy(ctx)
            wait = max(0, int(round(max(0.0, float(self._delay())) / period)))
            if wait > 0:
                obs, _, terminated, _, info = sim.step(None, steps=wait)
                self._take_timings(info.get("chunks", []))
                if terminated:
                    return obs
            sent, keep = self._chunk_to_send(chunk, ctx, obs["time"] - observation_time)
            # Until the next observation: replan_steps of the policy's steps after this one's,
            # but at least one cycle from now.
            next_observation = self._next_observation(observation_time, keep, period)
            cycles = max(1, math.ceil((next_observation - obs["time"]) / period - 1e-9))
            sent_at = obs["time"]
            obs, _, terminated, _, info = sim.step(sent, relative_to=observation_time, keep=keep,
                                                   steps=cycles)
            self._note(None, observation_time, sent, keep, sent_at, info)
            if not info["accepted"]:
                self.records[-1]["refused"] = f'{info["reason"]}: {info["message"]}'
            if terminated:
                break
        return obs

    # ---- Client: wall clock, inference in a thread ---------------------------------------------
    def _run_client(self, seconds):
        client = self.host
        state = client.state(1.0)
        if state is None:
            raise RuntimeError("no state from the host within 1 s: is comply run up?")
        end = state["stamp"] + seconds
        result = {}
        while state is not None and state["stamp"] < end:
            observation_time = state["stamp"]
            observed_at = time.monotonic()
            ctx = self._context(state, observation_time)
            worker = threading.Thread(target=lambda c=ctx: result.update(chunk=self.policy(c)))
            worker.start()
            while worker.is_alive():  # the arm moves on the last chunk meanwhile
                worker.join(0.005)
            elapsed = time.monotonic() - observed_at + self.arrival_margin_s
            sent, keep = self._chunk_to_send(result.pop("chunk"), ctx, elapsed)
            stamp = client.send_chunk(sent, relative_to=observation_time, keep=keep)
            record = self._note(stamp, observation_time, sent, keep, None)
            outcome = client.outcome(stamp, 0.5)
            if outcome is not None and outcome.get("chunk"):
                self._hand_on(record, outcome["chunk"])
            next_observation = self._next_observation(observation_time, keep)
            state = client.state(1.0)
            while state is not None and state["stamp"] < next_observation:
                state = client.state(1.0)
        return state
