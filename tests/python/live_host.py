"""comply run --sim (FR3, Cartesian impedance) on a random loopback domain for the live tests:
started on entering, stopped by SIGTERM on leaving, which it must answer with exit 0."""

import contextlib
import random
import signal
import subprocess


@contextlib.contextmanager
def running_host(cli, source, name, extra=(), config=None):
    """Yields (host process, domain); `extra`: more arguments for `comply run`; `config`: the
    controller file instead of config/sim/cartesian_impedance.yaml."""
    domain = random.randint(1, 230)
    config = config or f"{source}/config/sim/cartesian_impedance.yaml"
    host = subprocess.Popen([cli, "run", "--config", config, "--robot", "fr3", "--sim",
                             "--domain", str(domain), "--name", name, *extra],
                            start_new_session=True)  # a group of its own: it and its transport
    try:
        yield host, domain
    finally:
        host.send_signal(signal.SIGTERM)
        code = host.wait(timeout=10)
    assert code == 0, f"comply run exited {code} on SIGTERM"
