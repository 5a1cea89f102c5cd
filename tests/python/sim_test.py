"""comply.Sim: the in-process simulator shaped like a Gymnasium env. Usage: sim_test.py SOURCE."""

import sys
import tempfile

import numpy as np

import comply


TANK_KEYS = ("passivity", "tank_energy", "nullspace_tank_energy", "energy_injected",
             "energy_dissipated", "energy_refused", "gain_fraction")


def check_tank(obs):
    """The energy tank's account under ControllerState's names: 0 (gain_fraction 1) when off."""
    missing = [key for key in TANK_KEYS if key not in obs]
    assert not missing, f"missing {missing} in {sorted(obs)}"
    if not obs["passivity"]:
        assert obs["gain_fraction"] == 1.0, obs
        assert all(obs[key] == 0.0 for key in TANK_KEYS[1:-1]), obs


def check_reflex(source):
    """The contact reflex on the observer (commanded torque: the joints' friction is in the
    estimate while the arm moves), its threshold below that friction: the motion trips it, the
    observation says so, and while it holds the next command is refused as reflex_latched."""
    with open(f"{source}/config/sim/cartesian_impedance.yaml") as base, \
            tempfile.TemporaryDirectory() as folder:
        path = f"{folder}/reflex.yaml"
        with open(path, "w") as out:
            out.write(base.read() + "    observer:\n      enabled: true\n"
                      "    reflex:\n      enabled: true\n      force_n: 3.0\n")
        sim = comply.Sim(path, robot="fr3", steps_per_action=50)
        obs = sim.reset()
        assert not obs["reflex_tripped"] and not obs["reflex_wrench"].any(), obs
        target = obs["tcp_position"] + np.array([0.08, 0.0, 0.0])
        for _ in range(20):  # 1 s at 20 Hz
            obs, _, terminated, _, info = sim.step({"position": target})
            assert not terminated, info
            if obs["reflex_tripped"]:
                break
        assert obs["reflex_tripped"], obs
        assert np.linalg.norm(obs["reflex_wrench"][:3]) > 3.0, obs["reflex_wrench"]
        _, _, terminated, _, info = sim.step({"position": target})
        assert not info["accepted"] and info["reason"] == "reflex_latched", info
        assert not terminated and info["state"] == "active", info


def main():
    source = sys.argv[1]
    sim = comply.Sim(f"{source}/config/sim/cartesian_impedance.yaml", robot="fr3",
                     steps_per_action=50)
    obs = sim.reset()
    assert obs["position"].shape == (sim.dof,) and sim.cartesian
    check_tank(obs)
    target = obs["tcp_position"] + np.array([0.0, 0.03, -0.05])
    for _ in range(60):  # 3 s at 20 Hz
        result = sim.step({"position": target, "stiffness_translational": [2000, 2000, 2000]})
        assert len(result) == 5
        obs, reward, terminated, truncated, info = result
        assert info["accepted"], info
        assert not terminated and not truncated
    check_tank(obs)
    error = np.linalg.norm(obs["tcp_position"] - target)
    assert error < 0.002, f"TCP {obs['tcp_position']} is {error * 1000:.1f} mm from {target}"
    assert abs(sim.time - 3.0) < 1e-6, sim.time
    _, _, _, _, info = sim.step({"stiffness_translational": -np.eye(3)})
    assert not info["accepted"] and info["reason"] == "invalid_gains", info
    try:
        sim.step({"positon": target})
        raise AssertionError("a misspelt keyword was accepted")
    except ValueError as error:
        assert "positon" in str(error)
    # The wrist sensor, compensated by the cycle: zero after a tare while the arm holds still.
    assert obs["sensor_wrench"].shape == (6,), obs["sensor_wrench"]
    sim.tare()
    obs, _, _, _, _ = sim.step({"position": target})
    assert np.linalg.norm(obs["sensor_wrench"][:3]) < 0.2, obs["sensor_wrench"]
    frame = comply.darboux_frame([1, 0, 0], [0, 0, 1])
    assert np.allclose(np.linalg.norm(frame), 1.0)
    assert sim.reset()["position"].shape == (sim.dof,)
    check_reflex(source)
    print("ok")


if __name__ == "__main__":
    main()
