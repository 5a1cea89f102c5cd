"""comply run --sim and Python clients that read, send, leave and share one Client between threads.
The host's command_timeout_s is 600 s: a sender let in here was let in because the one before it
never held the topics, or left, never because its silence timed out.

- A client that only reads (a dashboard), constructed first, does not take the command topics:
  a sending client's commands are applied.
- A sender that close()s releases the topics at once: the host names no publisher any more and a
  second sender's first command is applied; the closed client raises.
- `comply send --request deactivate` while a client holds the topics is refused (other_publisher)
  and exits 1; the holder's own deactivate() is carried out.
- One Client, one thread sending and one reading, across a restart of the host's transport
  process: both threads carry on.

Usage: live_publisher_test.py COMPLY_CLI SOURCE_DIR."""

import os
import signal
import subprocess
import sys
import tempfile
import threading
import time

import comply
from live_host import running_host

NAME = "pub"
RESUME_TIMEOUT_S = 60.0  # a failure condition only: the test asserts what resumes, not how fast


def patient_config(source, folder):
    """The live tests' controller with command_timeout_s 600: no silence times out here."""
    with open(f"{source}/config/sim/cartesian_impedance.yaml") as original:
        text = original.read()
    assert "command_timeout_s: 0.5" in text
    path = os.path.join(folder, "patient.yaml")
    with open(path, "w") as patient:
        patient.write(text.replace("command_timeout_s: 0.5", "command_timeout_s: 600.0"))
    return path


def pose_of(client):
    state = client.state(timeout=5.0)
    assert state is not None
    return dict(position=state["tcp_position"], orientation=state["tcp_orientation"])


def publisher(client):
    """The writer the host names as holding the command topics ("" when none)."""
    diagnostics = client.diagnostics(timeout=5.0)
    assert diagnostics is not None
    return diagnostics["publisher"]


def applied(client, stamp):
    outcome = client.outcome(stamp, timeout=10.0)
    assert outcome is not None, "no outcome"
    return outcome["applied"], outcome


def reader_does_not_hold(domain):
    dashboard = comply.Client(name=NAME, domain=domain, timeout=30.0)
    assert dashboard.state() is not None and dashboard.diagnostics() is not None
    assert publisher(dashboard) == "", "a client that only read took the command topics"
    sender = comply.Client(name=NAME, domain=domain, timeout=30.0)
    ok, outcome = applied(sender, sender.send_cartesian(**pose_of(sender)))
    assert ok, f"a reading client locked the sender out: {outcome}"
    return dashboard, sender


def close_releases(domain, dashboard, sender):
    assert publisher(dashboard) != ""
    sender.close()
    sender.close()  # idempotent
    try:
        sender.state()
        raise AssertionError("a closed client still reads")
    except RuntimeError as error:
        assert "closed" in str(error), error
    deadline = time.monotonic() + RESUME_TIMEOUT_S
    while publisher(dashboard) != "":  # the host saw the writers go
        assert time.monotonic() < deadline, "close() did not release the command topics"
        time.sleep(0.05)
    with comply.Client(name=NAME, domain=domain, timeout=30.0) as second:
        ok, outcome = applied(second, second.send_cartesian(**pose_of(second)))
        assert ok, f"the second sender was refused after the first closed: {outcome}"
    while publisher(dashboard) != "":  # leaving the `with` block closed it
        assert time.monotonic() < deadline, "leaving `with` did not release the topics"
        time.sleep(0.05)


def request_refused(cli, domain):
    with comply.Client(name=NAME, domain=domain, timeout=30.0) as holder:
        ok, outcome = applied(holder, holder.send_cartesian(**pose_of(holder)))
        assert ok, outcome
        sent = subprocess.run([cli, "send", "--domain", str(domain), "--name", NAME, "--request",
                               "deactivate"], capture_output=True, text=True, timeout=120)
        assert sent.returncode == 1, (sent.returncode, sent.stdout, sent.stderr)
        assert "request refused" in sent.stdout and "other_publisher" in sent.stdout, sent.stdout
        assert holder.state()["state"] == "active", "another process deactivated the arm"
        ok, outcome = applied(holder, holder.deactivate())
        assert ok and outcome["command_kind"] == "request", outcome
        assert holder.wait_until(lambda s: s["state"] == "inactive", timeout=RESUME_TIMEOUT_S)
        ok, outcome = applied(holder, holder.activate())
        assert ok, outcome
        assert holder.wait_until(lambda s: s["state"] == "active", timeout=RESUME_TIMEOUT_S)


def transport_process(host):
    """The pid of the comply-transport process `host` runs."""
    for entry in os.listdir("/proc"):
        try:
            with open(f"/proc/{entry}/stat") as stat, open(f"/proc/{entry}/cmdline", "rb") as cmd:
                parent = int(stat.read().rsplit(")", 1)[1].split()[1])
                if parent == host.pid and b"comply-transport" in cmd.read():
                    return int(entry)
        except (OSError, ValueError):
            continue
    raise AssertionError("the host runs no transport process")


def running(pid):
    """Whether process `pid` runs (a zombie has ended)."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def two_threads_across_a_transport_restart(host, domain):
    client = comply.Client(name=NAME, domain=domain, timeout=30.0)
    pose = pose_of(client)
    stop = threading.Event()
    applied_stamps, state_stamps, failures = [], [], []

    # Both threads poll the client often, as a policy's threads would: their calls overlap.
    def send():
        while not stop.is_set():
            try:
                stamp = client.send_cartesian(**pose)
                outcome = client.outcome(stamp, timeout=0.05)
                if outcome is not None and outcome["applied"]:
                    applied_stamps.append(stamp * 1e-9)
            except RuntimeError:  # no host matched, or none acknowledging: the restart
                time.sleep(0.05)
            except Exception as error:  # anything else ends the test
                failures.append(repr(error))
                raise
            time.sleep(0.005)

    def read():
        while not stop.is_set():
            try:
                state = client.state(timeout=0.02)
                if state is not None:
                    state_stamps.append(state["stamp"])
                client.diagnostics(timeout=0.0)
            except Exception as error:
                failures.append(repr(error))
                raise

    threads = [threading.Thread(target=send), threading.Thread(target=read)]
    for thread in threads:
        thread.start()
    try:
        deadline = time.monotonic() + RESUME_TIMEOUT_S
        while not (applied_stamps and state_stamps):
            assert time.monotonic() < deadline, "two threads never got going"
            time.sleep(0.05)
        pid = transport_process(host)
        os.kill(pid, signal.SIGKILL)
        while running(pid):
            time.sleep(0.01)
        killed = time.time()  # wall clock, as stamps are: nothing later came through the old one
        deadline = time.monotonic() + RESUME_TIMEOUT_S
        while not (applied_stamps and applied_stamps[-1] > killed and
                   state_stamps and state_stamps[-1] > killed):
            assert not failures, failures
            assert time.monotonic() < deadline, (
                f"not resumed: a command applied after the restart {applied_stamps[-1] > killed}, "
                f"a state after it {state_stamps[-1] > killed}")
            time.sleep(0.05)
    finally:
        stop.set()
        for thread in threads:
            thread.join(timeout=RESUME_TIMEOUT_S)
    assert not any(thread.is_alive() for thread in threads), "a thread hangs in the client"
    assert not failures, failures
    client.close()


def main():
    cli, source = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as folder:
        config = patient_config(source, folder)
        with running_host(cli, source, NAME, config=config) as (host, domain):
            dashboard, sender = reader_does_not_hold(domain)
            close_releases(domain, dashboard, sender)
            request_refused(cli, domain)
            two_threads_across_a_transport_restart(host, domain)
    print("ok")


if __name__ == "__main__":
    main()
