"""Client.committed() against comply run --sim on loopback: the host's committed prefix over the
wire is the dict Sim.committed() gives (same keys, shapes and types), at exactly the times asked
for, on the chunk the host plays; a request the host refuses raises ValueError in its words; and
comply.policy.PolicyRunner in mode "frozen" on a Client hands each inference that prefix.
Prints what one answer costs the caller (n = 16 and 50) on this machine.
Usage: committed_test.py COMPLY_CLI SOURCE_DIR."""

import statistics
import sys
import time

import numpy as np

import comply
from comply.policy import PolicyRunner, inpaint
from live_host import running_host

DT = 0.05


def along_y(position, orientation, count, spacing, first=0.0, step=0.005):
    """`count` waypoints `spacing` s apart from `first`, `step` m further along y each."""
    return [{"time": first + spacing * k, "position": position + [0.0, step * k, 0.0],
             "orientation": orientation} for k in range(count)]


def sim_shape(source):
    """What Sim.committed() returns for 8 times: the dict the Client's must match."""
    sim = comply.Sim(f"{source}/config/sim/cartesian_impedance.yaml", robot="fr3")
    obs = sim.reset()
    committed = sim.committed(obs["time"], DT, 8)
    sim.close()
    return {key: (np.shape(value), type(value)) for key, value in committed.items()}


def check_prefix(client, shape):
    state = client.state()
    start = state["tcp_position"].copy()
    # 0.1 m/s along y for 1.5 s, from 0.1 s after the observation.
    chunk = along_y(start, state["tcp_orientation"], 31, DT, first=0.1)
    outcome = client.outcome(client.send_chunk(chunk, relative_to=state["stamp"]), timeout=2.0)
    assert outcome is not None and outcome["applied"], outcome
    line_start = state["stamp"] + 0.1
    while time.time() < line_start + 0.3:  # past the blend onto it
        time.sleep(0.01)
    observed = client.state()
    committed = client.committed(observed["stamp"], DT, 8, timeout=5.0)
    got = {key: (np.shape(value), type(value)) for key, value in committed.items()}
    assert got == shape, (got, shape)
    assert committed["known"] is True, committed["known"]
    times = observed["stamp"] + DT * np.arange(8)
    assert np.allclose(committed["time"], times, atol=1e-6, rtol=0.0), committed["time"] - times
    # The chunk's line at those times (to where the host's clock stood between its cycles).
    line = start[1] + 0.1 * (committed["time"] - line_start)
    assert np.abs(committed["position"][:, 1] - line).max() < 2e-3, committed["position"][:, 1]
    assert np.abs(committed["position"][:, [0, 2]] - start[[0, 2]]).max() < 1e-9, committed


def check_refusals(client):
    stamp = client.state()["stamp"]
    for dt, n, words in ((0.0, 4, "dt is 0"), (DT, 65, "count is 65: 1 to 64")):
        try:
            client.committed(stamp, dt, n, timeout=5.0)
        except ValueError as error:
            assert "the host refused the request: " + words in str(error), error
        else:
            raise AssertionError(f"committed(dt={dt}, n={n}) was answered")


def cost(client):
    """Wall time of one committed() call, request to dict, median of 50 (printed, not asserted)."""
    for n in (16, 50):
        spent = []
        for _ in range(50):
            stamp = client.state()["stamp"]
            begin = time.perf_counter()
            client.committed(stamp, DT, n, timeout=5.0)
            spent.append(time.perf_counter() - begin)
        print(f"Client.committed(n={n}): median {1e6 * statistics.median(spent):.0f} us, "
              f"max {1e6 * max(spent):.0f} us over {len(spent)} calls")


def check_runner(client):
    """Mode "frozen" on a Client: each inference gets the host's prefix (a Client has reset()
    and committed() like a Sim, yet runs on the wall clock), and every chunk takes over."""
    prefixes = []

    def policy(ctx):
        time.sleep(0.1)  # the inference
        prefixes.append(ctx["committed"])
        obs = ctx["observation"]
        planned = [np.asarray(obs["reference_position"]) + [0.0, 0.002 * k, 0.0]
                   for k in range(ctx["horizon"])]
        return [{"time": k * ctx["dt"], "position": p, "orientation": obs["tcp_orientation"]}
                for k, p in enumerate(inpaint(planned, ctx))]

    runner = PolicyRunner(client, policy, dt=1 / 30, horizon=16, mode="frozen")
    runner.run(seconds=4.0)
    assert len(prefixes) >= 8, len(prefixes)
    assert all(p is not None and p["known"] for p in prefixes), prefixes
    assert all(p["position"].shape == (16, 3) for p in prefixes)
    took = [r for r in runner.records if r["timing"] and r["timing"]["end"] == "took_over"]
    keeps = [r["keep"] for r in runner.records]
    assert len(took) == len(runner.records), (keeps, runner.delays())
    print(f"PolicyRunner frozen on a Client: {len(runner.records)} chunks, all took over; kept "
          f"{keeps}, host's counts {runner.delays()}")


def main():
    cli, source = sys.argv[1], sys.argv[2]
    shape = sim_shape(source)
    with running_host(cli, source, "committed_py") as (_, domain):
        client = comply.Client(name="committed_py", domain=domain, timeout=30.0)
        check_prefix(client, shape)
        check_refusals(client)
        cost(client)
        check_runner(client)
        client.close()
    print("ok")


if __name__ == "__main__":
    main()
