"""comply: live compliant control of torque-controlled arms, from Python.

Client connects to a `comply run` host by name and DDS domain; its send_cartesian() and
send_joint() take the command schema's field names as keywords (numpy arrays or sequences;
quaternions x y z w; a 3x3 gain block as 9 numbers row-major, 3 numbers (diagonal) or 1
(isotropic)). Sim is the same controller on an in-process MuJoCo plant, shaped like a Gymnasium
environment: reset() -> observation, step(command) -> (observation, reward, terminated,
truncated, info). frenet_frame() and darboux_frame() build task frames (x y z w).

    import comply
    client = comply.Client(name="comply", domain=0)
    s = client.state()
    stamp = client.send_cartesian(position=s["tcp_position"] + [0, 0, -0.02],
                                  orientation=s["tcp_orientation"],
                                  stiffness_translational=[3000, 3000, 500])
    print(client.outcome(stamp))

A Client may be shared by threads (one reading the state, another sending); close(), or leaving
a `with comply.Client(...) as client:` block, disconnects it and lets the host release its
command topics at once. A Client that only reads never holds them.

Both record to MCAP with record="path.mcap", in a folder that exists (close() finishes the file;
recording_stats() gives its counts). Client(..., record=...) keeps what it sent (its commands and requests, at their
stamps) and every state and diagnostics message it took. Sim(..., record=...) keeps every cycle,
command and outcome of every episode in one file, as `comply sim --record` does, on a simulated
clock that runs on across episodes; an episode starts where the cycle index is 0 again:

    sim = comply.Sim("config/sim/cartesian_impedance.yaml", robot="fr3", record="sim.mcap")
    ...
    sim.close()
    cycles = comply.read_recording("sim.mcap")["/comply/cycle"]
    starts = np.flatnonzero(cycles["state.cycle"] == 0)  # each episode's first row

comply.policy.PolicyRunner runs a chunking policy that infers while the arm moves, on a Sim or a
Client, with the delay the host measured handed to each inference (docs/policies.md).

rollouts() runs many Sim episodes in worker processes (dask.distributed, on this machine or on
the machines of a cluster; imported only when used) and returns a row per episode in episode
order: a Schedule(fn) gives each episode one command, any other callable is a policy called
every step; record=/dataset= keep every episode as MCAP and a LeRobot dataset
(docs/rollouts.md):

    results = comply.rollouts(comply.Schedule(lambda episode, rng, obs: {...}), 200,
                              config="config/sim/cartesian_impedance.yaml", seconds=2.0)
    print(results.summary()); results.column("tracking_error_rms_m")

read_recording(path) reads a recording (MCAP) into numpy columns per topic in pure Python
(numpy, zstandard), so it works where the C++ extension is not built:

    rec = comply.read_recording("run.mcap")
    rec["/comply/state"]["position"], rec["/comply/state"].log_time, rec.truncated
    rec["/comply/cycle"]["cartesian_in_force.stiffness_translational"]  # (n, 9)
"""

from .recording import Recording, RecordingError, Topic, read_recording
from .rollouts import RolloutError, Schedule, rollouts

_EXTENSION_NAMES = ["Client", "Sim", "darboux_frame", "export_lerobot", "frenet_frame"]
__all__ = ["Recording", "RecordingError", "RolloutError", "Schedule", "Topic", "read_recording",
           "rollouts"]

try:
    from ._comply import Client, Sim, darboux_frame, export_lerobot, frenet_frame
    __all__ += _EXTENSION_NAMES
except ModuleNotFoundError as _missing:
    # Only the extension's absence is forgiven (a source checkout, a dataset machine): the
    # recording reader does not need it. An extension that is there but fails to load raises.
    if _missing.name != f"{__name__}._comply":
        raise
    _extension_error = _missing

    def __getattr__(name):
        if name in _EXTENSION_NAMES:
            raise ImportError(f"comply.{name} needs the C++ extension comply._comply, which is "
                              f"not on this path (build the comply_python target and put "
                              f"build/python on PYTHONPATH)") from _extension_error
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
