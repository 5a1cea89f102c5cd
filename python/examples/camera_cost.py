"""What a Sim camera costs on this machine: the time of a policy step (50 control cycles) with
and without cameras, at a few sizes, with shadows and reflections off (the default) and on, and
what recording the frames (PNG, into the MCAP file) adds; the first reset (which makes the GL
contexts) against a later one. Rendering is EGL offscreen: a GPU's driver where there is one,
Mesa's llvmpipe on the CPU otherwise (docs/simulation.md#cameras).

    PYTHONPATH=build/python python3 python/examples/camera_cost.py [--steps 40]
"""

import argparse
import os
import tempfile
import time

import comply

CONFIG = os.path.join(os.path.dirname(__file__), "..", "..", "config", "sim",
                      "cartesian_impedance.yaml")


def step_ms(cameras, steps, record=None):
    """Milliseconds per step (median of the steps), the first reset's and the second's."""
    sim = comply.Sim(CONFIG, robot="fr3", record=record, cameras=cameras)
    start = time.perf_counter()
    sim.reset()
    first_reset = time.perf_counter() - start
    start = time.perf_counter()
    sim.reset()
    second_reset = time.perf_counter() - start
    times = []
    for _ in range(steps):
        start = time.perf_counter()
        sim.step(None)
        times.append(time.perf_counter() - start)
    sim.close()
    times.sort()
    return 1e3 * times[len(times) // 2], 1e3 * first_reset, 1e3 * second_reset


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=40)
    args = parser.parse_args()
    plain, _, _ = step_ms(None, args.steps)
    print(f"no camera: {plain:.2f} ms per step")
    with tempfile.TemporaryDirectory() as folder:
        record = os.path.join(folder, "cost.mcap")
        for width, height in [(128, 96), (320, 240), (640, 480)]:
            camera = {"front": {"width": width, "height": height}}
            effects = {"front": dict(camera["front"], shadows=True, reflections=True)}
            bare, first, second = step_ms(camera, args.steps)
            rich, _, _ = step_ms(effects, args.steps)
            recorded, _, _ = step_ms(camera, args.steps, record)
            print(f"{width}x{height}: +{bare - plain:.1f} ms per frame "
                  f"(shadows and reflections on: +{rich - plain:.1f}), recorded "
                  f"+{recorded - bare:.1f} ms more; first reset {first:.0f} ms, "
                  f"a later one {second:.0f} ms")


if __name__ == "__main__":
    main()
