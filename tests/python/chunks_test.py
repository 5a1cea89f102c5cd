"""Timed chunks from Python: Sim.step(chunk) on the in-process simulator, and Client.send_chunk to
comply run --sim on loopback with the host's clock estimated from round trips (Client.clock()).
A late chunk and a malformed one are refused with their reasons. Prints the clock estimate.
Usage: chunks_test.py COMPLY_CLI SOURCE_DIR."""

import os
import sys
import tempfile
import time

import numpy as np

import comply
from live_host import running_host


def along_y(position, orientation, count, spacing, first=0.0, step=0.005):
    """`count` waypoints `spacing` s apart from `first`, `step` m further along y each."""
    return [{"time": first + spacing * k, "position": position + [0.0, step * k, 0.0],
             "orientation": orientation} for k in range(count)]


def check_sim(source, recording):
    sim = comply.Sim(f"{source}/config/sim/cartesian_impedance.yaml", robot="fr3",
                     steps_per_action=100, record=recording)
    obs = sim.reset()
    start = obs["tcp_position"].copy()
    chunk = along_y(start, obs["tcp_orientation"], 16, 0.05, first=0.05)
    chunk[0]["stiffness_translational"] = 1500.0  # holds for the waypoints after it
    obs, _, terminated, _, info = sim.step(chunk)
    assert info["accepted"] and not terminated, info
    for _ in range(8):
        obs, *_ = sim.step(None)
    moved = obs["tcp_position"] - start
    assert abs(moved[1] - 0.075) < 0.003 and abs(moved[0]) < 0.005, moved  # 15 x 5 mm along y

    _, _, _, _, info = sim.step(along_y(obs["tcp_position"], obs["tcp_orientation"], 3, 0.05,
                                        first=-1.0))
    assert not info["accepted"] and info["reason"] == "late_chunk", info
    try:
        sim.step([{"position": obs["tcp_position"]}])
    except ValueError as error:
        assert "chunk[0].time" in str(error), error
    else:
        raise AssertionError("a waypoint without a time was taken")
    _, _, _, _, info = sim.step([{"time": 0.1, "position": obs["tcp_position"]},
                                 {"time": 0.1, "position": obs["tcp_position"]}])
    assert info["reason"] == "invalid_chunk" and "waypoint 1's time" in info["message"], info
    _, _, _, _, info = sim.step([{"time": 0.1, "position": obs["tcp_position"]},
                                 {"time": float("nan"), "position": obs["tcp_position"]}])
    assert info["reason"] == "non_finite", info
    assert "waypoint 1 time is not finite" in info["message"], info
    sim.close()

    # The recording holds every chunk as sent, each waypoint's time its header stamp.
    chunks = comply.read_recording(recording)["/comply/cartesian_chunk"]
    # The played one, the late one, the one with two equal times, the one with a time that is not
    # a number (the one without a time never became a chunk).
    assert chunks.count == 4, chunks
    first = chunks["waypoints"][0]
    assert len(first) == 16 and first[0]["stiffness_translational"][0] == 1500.0, first[0]
    assert [w["header"]["stamp"]["nanosec"] for w in first[:3]] == [50_000_000, 100_000_000,
                                                                   150_000_000], first[:3]


def check_client(cli, source):
    with running_host(cli, source, "chunks") as (_, domain):
        client = comply.Client(name="chunks", domain=domain, timeout=30.0)
        for _ in range(50):  # round trips for the clock estimate
            client.outcome(client.send_cartesian(), timeout=1.0)
        clock = client.clock()
        assert clock is not None and clock["samples"] >= 40, clock
        # One machine: one clock, so the offset is what the estimate gets wrong, and a round trip's
        # estimate is never wrong by more than half of that round trip (whatever the machine's
        # load made it).
        assert clock["round_trip"] > 0.0, clock
        assert abs(clock["offset"]) <= 0.5 * clock["round_trip"] + 1e-9, clock
        assert clock["one_way_latency"] == 0.5 * clock["round_trip"], clock
        print(f"clock on loopback: offset {1e6 * clock['offset']:.0f} us, one-way latency "
              f"{1e6 * clock['one_way_latency']:.0f} us, round trip "
              f"{1e6 * clock['round_trip']:.0f} us over {clock['samples']} samples")

        state = client.state()
        start = state["tcp_position"].copy()
        # Times after the observation the "policy" acted on: its stamp on the host's clock.
        chunk = along_y(start, state["tcp_orientation"], 8, 0.05, first=0.1)
        try:
            client.send_chunk(chunk, relative_to=state["stamp"], keep=8)
        except ValueError as error:
            assert "keep=8: a chunk of 8 waypoints takes over at one of them (0 to 7)" in str(
                error), error
        else:
            raise AssertionError("keep=8 of 8 waypoints was sent")
        stamp = client.send_chunk(chunk, relative_to=state["stamp"])
        outcome = client.outcome(stamp, timeout=2.0)
        assert outcome is not None and outcome["applied"], outcome
        # Its timing record: the observation it was planned for travelled with it (one offset
        # maps the record onto the host's clock, so the times keep their differences).
        timing = outcome["chunk"]
        assert timing is not None and timing["end"] == "took_over", outcome
        assert abs(timing["observation"] - state["stamp"]) < 0.25, timing
        assert abs(timing["first_waypoint"] - timing["observation"] - 0.1) < 1e-6, timing
        assert timing["waypoints"] == 8 and timing["requested_takeover"] != timing[
            "requested_takeover"], timing  # NaN: at once
        deadline = state["stamp"] + 0.1 + 7 * 0.05 + 0.3
        while time.time() < deadline:
            time.sleep(0.02)
        state = client.state()
        assert abs(state["reference_position"][1] - (start[1] + 0.035)) < 1e-6, state
        assert abs(state["tcp_position"][1] - (start[1] + 0.035)) < 0.01, state

        # Relative to the host's clock now, as estimated, asking to take over at its waypoint 2
        # (none plays: the reference holds until then); then one entirely past.
        stamp = client.send_chunk(along_y(state["tcp_position"], state["tcp_orientation"], 4,
                                          0.05, first=0.05), keep=2)
        outcome = client.outcome(stamp, timeout=2.0)
        assert outcome["applied"], outcome
        timing = outcome["chunk"]
        assert abs(timing["requested_takeover"] - timing["first_waypoint"] - 0.1) < 1e-6, timing
        # At its waypoint 2's time (the record's times carry the cycle's scheduling jitter on
        # the wall clock), its waypoints 0 and 1 past.
        assert timing["takeover"] > timing["requested_takeover"] - 0.002, timing
        assert timing["waypoints_past"] >= 2 and timing["starved"], timing
        stamp = client.send_chunk(along_y(state["tcp_position"], state["tcp_orientation"], 4,
                                          0.05), relative_to=state["stamp"] - 5.0)
        late = client.outcome(stamp, timeout=2.0)
        assert late is not None and late["reason"] == "late_chunk", late
        check_refusals(client, client.state())


def check_refusals(client, state):
    """Chunks the host refuses are answered with their reason, never as another chunk or with no
    answer: one of 65 waypoints (the host's outcome), and times the wire's stamps cannot carry
    (refused before they are sent: a time that is not a number, one past 2038)."""
    position, orientation = state["tcp_position"], state["tcp_orientation"]
    stamp = client.send_chunk(along_y(position, orientation, 65, 0.01, first=0.1, step=1e-4),
                              relative_to=state["stamp"])
    outcome = client.outcome(stamp, timeout=2.0)
    assert outcome is not None and outcome["reason"] == "invalid_chunk", outcome
    assert "1 to 64 waypoints, this one 65" in outcome["message"], outcome

    nan_time = along_y(position, orientation, 2, 0.05, first=0.1)
    nan_time[1]["time"] = float("nan")
    try:
        client.send_chunk(nan_time, relative_to=state["stamp"])
    except ValueError as error:
        assert "waypoint 1 time is not finite" in str(error), error
    else:
        raise AssertionError("a chunk with a time that is not a number was sent")

    far = state["stamp"] + 1e9
    try:
        client.send_chunk(along_y(position, orientation, 2, 0.05), relative_to=far)
    except ValueError as error:
        text = str(error)
        assert "invalid_chunk" in text and "ahead of the host's clock" in text, text
        assert str(int(far)) in text, text  # the time as sent, not wrapped into the past
    else:
        raise AssertionError("a chunk 1e9 s ahead was sent")


def main():
    cli, source = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as folder:
        check_sim(source, os.path.join(folder, "chunks.mcap"))
    check_client(cli, source)
    print("ok")


if __name__ == "__main__":
    main()
