"""comply run --sim and a Python client streaming 10,000 commands at 1 kHz, a tenth of them
invalid in seven ways: every command has exactly one outcome, applied or rejected with the right
reason. Then SIGTERM: the host exits 0. Usage: live_client_test.py COMPLY_CLI SOURCE_DIR."""

import math
import signal
import sys
import time

import numpy as np

import comply
from live_host import running_host

COMMANDS = 10000


def invalid(i, pose):
    """The i-th invalid command: (keywords, is_joint, expected reason)."""
    position, orientation = pose
    kind = (i // 10) % 7
    if kind == 0:
        return dict(position=[math.nan, 0.0, 0.0], orientation=orientation), False, "non_finite"
    if kind == 1:
        return dict(position=position, orientation=orientation * 1.1), False, "invalid_quaternion"
    if kind == 2:
        return dict(stiffness_translational=-np.eye(3), stiffness_rotational=np.eye(3)), False, \
            "invalid_gains"
    if kind == 3:  # (a joint vector of the wrong size is refused by the client itself)
        return dict(damping_mode="ratio", damping_ratio=[1, 1, -1, 1, 1, 1]), False, \
            "invalid_gains"
    if kind == 4:
        return dict(position=position + [0.5, 0, 0], orientation=orientation), False, "pose_jump"
    if kind == 5:  # finite, but faster than any arm
        return dict(twist=[1e12, 0, 0, 0, 0, 0]), False, "out_of_range"
    return dict(stiffness=np.full(7, 10.0)), True, "wrong_kind"


def main():
    cli, source = sys.argv[1], sys.argv[2]
    with running_host(cli, source, "py") as (_, domain):
        client = comply.Client(name="py", domain=domain, timeout=30.0)
        state = client.state()
        tank = ("passivity", "tank_energy", "nullspace_tank_energy", "energy_injected",
                "energy_dissipated", "energy_refused", "gain_fraction")
        assert all(key in state for key in tank), sorted(state)
        start_position = state["tcp_position"].copy()
        orientation = state["tcp_orientation"]
        expected = {}
        t0 = time.perf_counter()
        for i in range(COMMANDS):
            while time.perf_counter() < t0 + i * 1e-3:
                pass
            angle = 2 * math.pi * i / 2000
            position = start_position + [0.0, 0.01 * math.sin(angle), 0.01 * (math.cos(angle) - 1)]
            if i % 10 == 9:
                keywords, joint, reason = invalid(i, (position, orientation))
                send = client.send_joint if joint else client.send_cartesian
                stamp = send(**keywords)
            else:
                stamp = client.send_cartesian(position=position, orientation=orientation)
                reason = None
            expected[stamp] = reason
        elapsed = time.perf_counter() - t0
        wrong, missing, applied = [], 0, 0
        for stamp, reason in expected.items():
            outcome = client.outcome(stamp, timeout=10.0)
            if outcome is None:
                missing += 1
            elif reason is None and not outcome["applied"]:
                wrong.append(("applied", outcome))
            elif reason is not None and outcome["reason"] != reason:
                wrong.append((reason, outcome))
            else:
                applied += 1 if reason is None else 0
        print(f"sent {COMMANDS} in {elapsed:.2f} s; applied {applied}; missing {missing}; "
              f"wrong {len(wrong)}")
        assert missing == 0, f"{missing} commands without an outcome"
        assert not wrong, f"wrong outcomes, first: {wrong[:3]}"
        assert applied == COMMANDS * 9 // 10
        diagnostics = client.diagnostics()
        for name in ("pose_jump", "out_of_range"):  # one tenth of the commands, in seven ways
            assert diagnostics["rejections"][name] >= COMMANDS // 70 - 1, diagnostics
        force_axes(client)
        assert client.wait_until(lambda s: s["state"] == "active", timeout=2.0)
    dead_host(cli, source)
    print("ok")


def force_axes(client):
    """Force along a task axis from Python: a selection other than 0/1 is refused, a valid one
    applied; the state says how filtered its contact wrench is."""
    half = client.send_cartesian(force_axes=[0, 0, 0.5, 0, 0, 0], wrench_target=np.zeros(6))
    outcome = client.outcome(half, timeout=10.0)
    assert outcome["reason"] == "out_of_range", outcome
    axis = client.send_cartesian(force_axes=[0, 0, 1, 0, 0, 0], wrench_target=np.zeros(6))
    assert client.outcome(axis, timeout=10.0)["applied"]
    released = client.send_cartesian(force_axes=np.zeros(6), wrench_target=np.zeros(6))
    assert client.outcome(released, timeout=10.0)["applied"]
    state = client.state()
    assert state["contact_wrench_bandwidth"] >= 0.0, state


def dead_host(cli, source):
    """A client whose host stops: state() and diagnostics() say so (None) instead of repeating the
    last ones (diagnostics() once did), and a send raises instead of vanishing."""
    with running_host(cli, source, "gone") as (host, domain):
        client = comply.Client(name="gone", domain=domain, timeout=30.0)
        state = client.state()
        assert state is not None and 0.0 <= state["age"] < 0.5, state
        diagnostics = client.diagnostics()
        assert diagnostics is not None and 0.0 <= diagnostics["age"] < 1.5, diagnostics
        pose = dict(position=state["tcp_position"], orientation=state["tcp_orientation"])
        assert client.outcome(client.send_cartesian(**pose), timeout=5.0)["applied"]
        host.send_signal(signal.SIGTERM)
        assert host.wait(timeout=10) == 0
        assert client.state(timeout=0.5) is None, "a stopped host's last state was returned"
        assert client.diagnostics(timeout=0.5) is None, \
            "a stopped host's last diagnostics were returned"
        deadline = time.monotonic() + 10.0
        while True:  # the host's reader unmatches once its process has gone
            try:
                client.send_cartesian(**pose)
            except RuntimeError as error:
                assert "no comply host" in str(error), error
                break
            assert time.monotonic() < deadline, "sends to a stopped host never raised"
            time.sleep(0.05)


if __name__ == "__main__":
    main()
