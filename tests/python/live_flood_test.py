"""comply run --sim and a Python client sending valid commands back to back, far faster than the
1 kHz cycle: the client's writer is held back to the rate the host takes instead of dropping, so
every command has exactly one outcome, applied or queue_full (what the 64-entry intake cannot hold
between two cycles), and the controller stays active without a fault. A host that is stopped takes
nothing: the writer keeps what fits its history (at most 1000 commands, fewer when DDS's byte limit
for unacknowledged data comes first), then refuses with a clear error rather than block the
sender, and the host accounts for every command held once it runs again. (Stopped means the host's
process group: the host and its transport process, as a machine that stalls.)
Usage: live_flood_test.py COMPLY SOURCE_DIR."""

import os
import signal
import sys
import time

import comply
from live_host import running_host

COMMANDS = 5000
CYCLE_HZ = 1000
# The client's send rate is printed, not asserted: it is the machine's (10 to 20 kHz here, about
# 4 kHz beside a parallel build), and what the test holds is what the code does with the commands.
WRITER_KEEPS = 1000  # unacknowledged commands the client's writer holds at most


def main():
    cli, source = sys.argv[1], sys.argv[2]
    with running_host(cli, source, "flood") as (host, domain):
        client = comply.Client(name="flood", domain=domain, timeout=30.0)
        state = client.state()
        position, orientation = state["tcp_position"].copy(), state["tcp_orientation"]
        stamps = []
        t0 = time.perf_counter()
        for i in range(COMMANDS):
            # 1 mm steps along y and back: every command valid.
            target = position + [0.0, 0.001 * (i % 20 < 10), 0.0]
            stamps.append(client.send_cartesian(position=target, orientation=orientation))
        elapsed = time.perf_counter() - t0
        rate_hz = COMMANDS / elapsed
        counts, missing = {}, 0
        for stamp in stamps:
            # After one is missing, the rest get a short wait: a clear failure, not a test timeout.
            outcome = client.outcome(stamp, timeout=10.0 if missing == 0 else 0.1)
            if outcome is None:
                missing += 1
                continue
            key = "applied" if outcome["applied"] else outcome["reason"]
            counts[key] = counts.get(key, 0) + 1
        print(f"sent {COMMANDS} in {elapsed:.3f} s ({rate_hz / CYCLE_HZ:.0f}x the {CYCLE_HZ / 1000:.0f} kHz cycle); "
              f"outcomes {counts}; missing {missing}")
        assert missing == 0, f"{missing} commands without an outcome"
        assert set(counts) <= {"applied", "queue_full"}, counts
        assert counts.get("applied", 0) > 0, counts
        diagnostics = client.diagnostics()
        assert diagnostics["faults"] == 0, diagnostics
        assert diagnostics["rejections"]["queue_full"] == counts.get("queue_full", 0), diagnostics
        assert client.wait_until(lambda s: s["state"] == "active", timeout=2.0)

        os.killpg(host.pid, signal.SIGSTOP)
        held, refusal = [], None
        try:
            for _ in range(WRITER_KEEPS + 100):
                try:
                    held.append(client.send_cartesian(position=position, orientation=orientation))
                except RuntimeError as error:
                    refusal = str(error)
                    break
        finally:
            os.killpg(host.pid, signal.SIGCONT)
        print(f"stopped host: {len(held)} commands held, then: {refusal}")
        assert 0 < len(held) <= WRITER_KEEPS, f"{len(held)} sent to a stopped host"
        assert refusal is not None and "stopped or stalled" in refusal, refusal
        held_outcomes = [client.outcome(stamp, timeout=10.0) for stamp in held]
        assert all(outcome is not None for outcome in held_outcomes), "a held command was lost"
        assert client.wait_until(lambda s: s["state"] == "active", timeout=2.0)
    print("ok")


if __name__ == "__main__":
    main()
