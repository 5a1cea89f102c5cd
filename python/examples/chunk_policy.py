"""A policy that acts in timed chunks, as diffusion policies and VLAs do: every 0.1 s it looks at
the arm, plans 16 steps of 1/15 s ahead (a 4 cm circle in the y-z plane, softer along z in the
lower half), and sends them as one chunk with a stiffness per step. Its compute takes 30 ms, so
each chunk's first waypoints are already past when it arrives: the controller skips them and
takes over from the chunk before without a jump (docs/chunks.md). Plots the circle, the
controller's reference and the TCP, and the joint torques: in the lower half the soft spring
leaves the TCP a centimetre above the reference, what a soft axis gives away in free space.

    PYTHONPATH=build/python python3 python/examples/chunk_policy.py              # in-process
    PYTHONPATH=build/python python3 python/examples/chunk_policy.py --plot out.png

Against a running host (`comply run --config config/sim/cartesian_impedance.yaml --sim`), the same
policy sends with Client.send_chunk(chunk, relative_to=state["stamp"]): see --live.
"""

import argparse
import math
import time

import numpy as np

import comply

POLICY_HZ = 10.0  # how often the policy acts
STEP_S = 1.0 / 15.0  # spacing of its steps
STEPS = 16  # steps per chunk
COMPUTE_S = 0.03  # from observation to action
RADIUS_M = 0.04
TURN_S = 4.0  # one turn of the circle


def plan(centre, orientation, t_obs):
    """The chunk for the observation at `t_obs`: times relative to it."""
    chunk = []
    for k in range(STEPS):
        t = t_obs + k * STEP_S
        angle = 2 * math.pi * t / TURN_S
        lower = math.cos(angle) < 0
        chunk.append({
            "time": k * STEP_S,
            "position": centre + RADIUS_M * np.array([0.0, math.sin(angle), math.cos(angle) - 1]),
            "orientation": orientation,
            # Soft along z in the lower half, where a task would touch a surface.
            "stiffness_translational": [1500.0, 1500.0, 300.0 if lower else 1500.0],
        })
    return chunk


def run_sim(seconds):
    """The in-process simulator, 10 ms per step: returns the trace."""
    sim = comply.Sim("config/sim/cartesian_impedance.yaml", robot="fr3", steps_per_action=10)
    obs = sim.reset()
    centre, orientation = obs["tcp_position"].copy(), obs["tcp_orientation"]
    trace = {"time": [], "reference": [], "tcp": [], "torque": []}
    pending = None  # (time it reaches the host, observation time, chunk)
    next_obs = 0.0
    while sim.time < seconds:
        command = None
        if sim.time >= next_obs - 1e-9:
            pending = (sim.time + COMPUTE_S, sim.time, plan(centre, orientation, sim.time))
            next_obs += 1.0 / POLICY_HZ
        if pending and sim.time >= pending[0] - 1e-9:
            # Sim.step takes a chunk's times relative to this step: shift them to the observation.
            late_by = sim.time - pending[1]
            command = [dict(w, time=w["time"] - late_by) for w in pending[2]]
            pending = None
        obs, _, terminated, _, info = sim.step(command)
        assert info["accepted"] and not terminated, info
        trace["time"].append(obs["time"])
        trace["reference"].append(obs["reference_position"])
        trace["tcp"].append(obs["tcp_position"])
        trace["torque"].append(obs["torque_command"])
    return {key: np.array(value) for key, value in trace.items()}, centre


def run_live(name, domain, seconds):
    """A running host: chunks relative to the observation's stamp on the host's clock."""
    client = comply.Client(name=name, domain=domain)
    state = client.state()
    centre, orientation = state["tcp_position"].copy(), state["tcp_orientation"]
    start = state["stamp"]
    trace = {"time": [], "reference": [], "tcp": [], "torque": []}
    rejected = 0
    while state["stamp"] - start < seconds:
        t_obs = state["stamp"]
        chunk = plan(centre, orientation, t_obs - start)
        time.sleep(COMPUTE_S)
        outcome = client.outcome(client.send_chunk(chunk, relative_to=t_obs), timeout=0.05)
        rejected += 0 if outcome is None or outcome["applied"] else 1
        while True:
            state = client.state()
            trace["time"].append(state["stamp"] - start)
            trace["reference"].append(state["reference_position"])
            trace["tcp"].append(state["tcp_position"])
            trace["torque"].append(state["torque_command"])
            if state["stamp"] >= t_obs + 1.0 / POLICY_HZ:
                break
    clock = client.clock()
    print(f"{rejected} chunks rejected; host clock offset {1e3 * clock['offset']:.3f} ms, "
          f"one-way latency {1e3 * clock['one_way_latency']:.3f} ms")
    return {key: np.array(value) for key, value in trace.items()}, centre


def plot(trace, centre, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = trace["time"]
    circle = np.linspace(0, 2 * math.pi, 200)
    figure, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    axes[0].plot(1e3 * RADIUS_M * np.sin(circle), 1e3 * RADIUS_M * (np.cos(circle) - 1), ":",
                 color="0.5", label="planned circle")
    for key, label in (("reference", "reference"), ("tcp", "TCP")):
        offset = trace[key] - centre
        axes[0].plot(1e3 * offset[:, 1], 1e3 * offset[:, 2], linewidth=1, label=label)
    axes[0].set(xlabel="y [mm]", ylabel="z [mm]", title="path (soft along z below the middle)")
    axes[0].axis("equal")
    axes[0].legend(fontsize=8)
    for key, label in (("reference", "reference"), ("tcp", "TCP")):
        axes[1].plot(t, 1e3 * (trace[key][:, 2] - centre[2]), linewidth=1, label=label)
    axes[1].set(xlabel="time [s]", ylabel="z [mm]", title="height over time")
    axes[1].legend(fontsize=8)
    axes[2].plot(t, trace["torque"], linewidth=0.8)
    axes[2].set(xlabel="time [s]", ylabel="torque [N m]", title="joint torques")
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    print(f"wrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seconds", type=float, default=8.0)
    parser.add_argument("--live", metavar="NAME", help="send to the running host NAME instead")
    parser.add_argument("--domain", type=int, default=0, help="the running host's DDS domain")
    parser.add_argument("--plot", metavar="PNG", default="chunk_policy.png")
    args = parser.parse_args()
    trace, centre = run_live(args.live, args.domain, args.seconds) if args.live else run_sim(args.seconds)
    settled = trace["time"] > 1.0
    error = np.linalg.norm(trace["tcp"][settled] - trace["reference"][settled], axis=1)
    print(f"TCP behind the reference: RMS {1e3 * np.sqrt(np.mean(error ** 2)):.2f} mm, "
          f"max {1e3 * error.max():.2f} mm")
    plot(trace, centre, args.plot)


if __name__ == "__main__":
    main()
