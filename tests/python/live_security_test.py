"""comply.Client(security=...) against comply run --security: a keystore from
scripts/create-keystore.sh, the host on its /comply/host enclave, this client on /comply/client.
The client hears the host and its command is applied (the C++ test tests/live/live_security_test.cpp
shows that a client without credentials is never heard).
Usage: live_security_test.py COMPLY SOURCE_DIR."""

import os
import subprocess
import sys
import tempfile

import comply
from live_host import running_host


def main():
    cli, source = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as folder:
        keystore = os.path.join(folder, "keystore")
        subprocess.run([f"{source}/scripts/create-keystore.sh", keystore, "/comply/host",
                        "/comply/client"], check=True, stdout=subprocess.DEVNULL)
        enclaves = os.path.join(keystore, "enclaves", "comply")
        with running_host(cli, source, "secure_py",
                          ["--security", os.path.join(enclaves, "host")]) as (_, domain):
            client = comply.Client(name="secure_py", domain=domain, timeout=20.0,
                                   security=os.path.join(enclaves, "client"))
            state = client.state()
            assert state is not None, "no state from the secure host"
            stamp = client.send_cartesian(position=state["tcp_position"],
                                          orientation=state["tcp_orientation"])
            outcome = client.outcome(stamp, timeout=10.0)
            assert outcome is not None and outcome["applied"], outcome
            try:
                comply.Client(name="secure_py", domain=domain, security=folder)
                raise AssertionError("a folder without the enclave's files was taken")
            except RuntimeError as error:
                assert "is not there" in str(error), error
    print("ok")


if __name__ == "__main__":
    main()
