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
"""

from ._comply import Client, Sim, darboux_frame, frenet_frame

__all__ = ["Client", "Sim", "darboux_frame", "frenet_frame"]
