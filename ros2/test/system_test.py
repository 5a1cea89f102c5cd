"""comply under ROS 2, end to end (make test-ros2; ROS 2 Humble sourced, the packages built).

1. FR3 in the MuJoCo plant under ros2_control with the Cartesian controller (comply_bringup):
   the controller is active; `ros2 topic pub --once` moves the TCP 2 cm and `ros2 topic echo`
   shows it within 2 mm; a NaN command is rejected, its reason on ~/diagnostics, the arm holds;
   comply's Python client (a process without ROS 2) commands it and `comply echo` reads it; the
   controller's update() timing over at least 10,000 cycles.
2. UR5e (6 joints) with the joint controller: a joint target, reached.
3. A plain rclcpp node commands `comply run --sim` and reads its state.

Usage: system_test.py COMPLY_CLI PYTHON_MODULE_DIR CONFIG_DIR
"""

import contextlib
import math
import os
import random
import signal
import subprocess
import sys
import time

import yaml

CLI, PYTHON_DIR, CONFIG_DIR = sys.argv[1:4]
DOMAIN = random.randint(1, 230)
ENV = dict(os.environ, ROS_DOMAIN_ID=str(DOMAIN))
results = []


def check(name, passed, detail):
    results.append((name, passed))
    print(f"{'PASS' if passed else 'FAIL'} {name}: {detail}", flush=True)


def ros2(*arguments, timeout=30):
    done = subprocess.run(['ros2', *arguments], env=ENV, capture_output=True, text=True,
                          timeout=timeout)
    return done.returncode, done.stdout + done.stderr


def echo(topic, timeout=15):
    """One message of `topic` as a dict (`ros2 topic echo --once` prints YAML)."""
    code, text = ros2('topic', 'echo', '--once', '--full-length', '--no-daemon', topic,
                      timeout=timeout)
    if code != 0:
        raise RuntimeError(f'ros2 topic echo {topic}: {text}')
    return yaml.safe_load(text.split('---')[0])


def publish(topic, message_type, message):
    code, text = ros2('topic', 'pub', '--once', '-w', '1', topic, message_type,
                      message)
    if code != 0:
        raise RuntimeError(f'ros2 topic pub {topic}: {text}')


def wait_for(predicate, timeout, period=0.5):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(period)
    return None


def distance(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


@contextlib.contextmanager
def launched(robot, controller, check_name):
    """comply_bringup for robot and controller; yields the controller's topic prefix and its first
    state once it is active (the check check_name), else None; stops the launch on leaving."""
    process = subprocess.Popen(
        ['ros2', 'launch', 'comply_bringup', 'comply.launch.py', f'robot:={robot}',
         f'controller:={controller}'], env=ENV, stdout=open(f'launch_{robot}.log', 'w'),
        stderr=subprocess.STDOUT, start_new_session=True)

    def active():
        code, text = ros2('control', 'list_controllers', timeout=20)
        return code == 0 and controller in text and 'active' in text.split(controller, 1)[1]
    try:
        became_active = bool(wait_for(active, 90, 1.0))
        check(check_name, became_active, 'ros2 control list_controllers')
        yield (f'/{controller}', echo(f'/{controller}/state')) if became_active else None
    finally:
        os.killpg(process.pid, signal.SIGINT)
        try:
            process.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)


def settled_at(topic, target, tolerance_m, timeout=20):
    """(state, error [m]) once the TCP rests within tolerance_m of target, measured 1 s later."""
    def near():
        state = echo(topic)
        speed = math.sqrt(sum(v * v for v in state['tcp_twist'][:3]))
        error = distance(state['tcp_position'], target)
        return (state, error) if error < tolerance_m and speed < 1e-3 else None
    if not wait_for(near, timeout):
        return None
    time.sleep(1.0)
    return near()


def cartesian_command(position, orientation, fields=1):
    # header: auto stamps it now (stamps must increase strictly; unstamped, all would be 0).
    return yaml.safe_dump({'header': 'auto', 'fields': fields, 'position': list(position),
                           'orientation': list(orientation)}, default_flow_style=True)


def python_client_without_ros(name, target, orientation):
    """comply's Python client in a process whose environment has no ROS 2 at all."""
    script = f'''
import comply
client = comply.Client(name={name!r}, domain={DOMAIN}, timeout=30.0)
client.send_cartesian(position={list(target)!r}, orientation={list(orientation)!r})
def near(state):
    return sum((a - b) ** 2 for a, b in zip(state["tcp_position"], {list(target)!r})) < 2e-3 ** 2
print("reached" if client.wait_until(near, timeout=15.0) else "missed")
'''
    bare = {'PATH': '/usr/bin:/bin', 'PYTHONPATH': PYTHON_DIR, 'HOME': os.environ.get('HOME', '/')}
    done = subprocess.run(['/usr/bin/python3', '-c', script], env=bare, capture_output=True,
                          text=True, timeout=90)
    return done.stdout.strip() + done.stderr.strip()[-400:]


def update_timing(topic):
    """Mean and p99 of update() [us] from the controller's compute-time histogram."""
    diagnostics = echo(topic)
    bins, width = diagnostics['compute_time_histogram'], diagnostics['histogram_bin']
    total = sum(bins)
    mean = sum((i + 0.5) * width * n for i, n in enumerate(bins)) / total
    running, p99 = 0, 0.0
    for i, n in enumerate(bins):
        running += n
        if running >= 0.99 * total:
            p99 = (i + 1) * width
            break
    return total, mean * 1e6, p99 * 1e6, diagnostics['overruns']


def fr3_cartesian():
    with launched('fr3', 'cartesian_impedance', 'fr3: controller active') as started:
        if not started:
            return
        base, state = started
        target = [state['tcp_position'][0], state['tcp_position'][1] + 0.02,
                  state['tcp_position'][2] - 0.02]
        orientation = state['tcp_orientation']
        publish(f'{base}/cartesian_command', 'comply_msgs/msg/CartesianCommand',
                cartesian_command(target, orientation))
        reached = settled_at(f'{base}/state', target, 2e-3)
        check('fr3: ros2 topic pub moves the TCP', reached is not None,
              f'final error {reached[1] * 1e3:.3f} mm' if reached else 'not within 2 mm')

        publish(f'{base}/cartesian_command', 'comply_msgs/msg/CartesianCommand',
                cartesian_command([math.nan, target[1], target[2]], orientation))
        rejected = wait_for(lambda: (lambda d: d if 'non_finite' in d['last_rejection'] or
                                     'position' in d['last_rejection'] else None)(
                                         echo(f'{base}/diagnostics')), 10)
        holding = settled_at(f'{base}/state', target, 2e-3, timeout=5)
        check('fr3: NaN command rejected, arm holds', bool(rejected) and holding is not None,
              f"diagnostics: '{rejected['last_rejection'] if rejected else ''}'; "
              f"TCP {holding[1] * 1e3:.3f} mm from the held target" if holding else 'moved')

        # Unstamped (stamp 0, older than every command applied so far): refused, stamps
        # increase strictly under ros2_control as under comply run.
        unstamped = yaml.safe_load(cartesian_command(target, orientation))
        del unstamped['header']
        publish(f'{base}/cartesian_command', 'comply_msgs/msg/CartesianCommand',
                yaml.safe_dump(unstamped, default_flow_style=True))
        stale = wait_for(lambda: (lambda d: d if 'stale_stamp' in d['last_rejection'] else None)(
            echo(f'{base}/diagnostics')), 10)
        check('fr3: an unstamped command is refused as stale', bool(stale),
              f"diagnostics: '{stale['last_rejection'] if stale else ''}'")

        target2 = [target[0] - 0.02, target[1], target[2]]
        outcome = python_client_without_ros('cartesian_impedance', target2, orientation)
        check('fr3: Python client without ROS 2 commands it', outcome.startswith('reached'),
              outcome)
        done = subprocess.run([CLI, 'echo', '--name', 'cartesian_impedance', '--domain',
                               str(DOMAIN), '--count', '1', '--json'], capture_output=True,
                              text=True, timeout=30)
        echoed = done.stdout.strip().splitlines()
        check('fr3: comply echo reads its state', done.returncode == 0 and bool(echoed) and
              '"tcp_position"' in echoed[0], (echoed[0][:120] if echoed else done.stderr[-200:]))

        wait_for(lambda: update_timing(f'{base}/diagnostics')[0] >= 10000, 30)
        cycles, mean_us, p99_us, overruns = update_timing(f'{base}/diagnostics')
        check('fr3: update() timing', cycles >= 10000,
              f'{cycles} cycles: mean {mean_us:.1f} us, p99 {p99_us:.0f} us, '
              f'{overruns} overruns')


def ur5e_joint():
    with launched('ur5e', 'joint_impedance', 'ur5e: joint controller active') as started:
        if not started:
            return
        base, state = started
        target = list(state['position'])
        target[1] += 0.1
        target[2] -= 0.1
        publish(f'{base}/joint_command', 'comply_msgs/msg/JointCommand',
                yaml.safe_dump({'header': 'auto', 'fields': 1, 'position': target},
                               default_flow_style=True))

        def near():
            s = echo(f'{base}/state')
            error = max(abs(a - b) for a, b in zip(s['position'], target))
            return (s, error) if error < 5e-3 and max(map(abs, s['velocity'])) < 1e-3 else None
        reached = wait_for(near, 20)
        check('ur5e: ros2 topic pub moves the joints', reached is not None,
              f'largest joint error {reached[1] * 1e3:.2f} mrad, TCP at '
              f'{[round(x, 4) for x in reached[0]["tcp_position"]]}' if reached else 'not reached')


def rclcpp_to_comply_run():
    host = subprocess.Popen([CLI, 'run', '--config', f'{CONFIG_DIR}/sim/cartesian_impedance.yaml',
                             '--robot', 'fr3', '--sim', '--domain', str(DOMAIN), '--name',
                             'rclcpp_probe_host', '--duration', '60'], stdout=subprocess.DEVNULL,
                            stderr=subprocess.STDOUT)
    try:
        done = subprocess.run(['ros2', 'run', 'comply_ros2_control', 'comply_rclcpp_probe',
                               'rclcpp_probe_host', '30'], env=ENV, capture_output=True,
                              text=True, timeout=60)
        check('rclcpp node commands comply run --sim', done.returncode == 0,
              (done.stdout + done.stderr).strip()[-300:])
    finally:
        host.send_signal(signal.SIGINT)
        host.wait(timeout=20)


def main():
    print(f'ROS_DOMAIN_ID {DOMAIN}', flush=True)
    for scenario in (fr3_cartesian, ur5e_joint, rclcpp_to_comply_run):
        try:
            scenario()
        except Exception as error:  # noqa: BLE001 - report and go on to the next scenario
            check(scenario.__name__, False, f'{type(error).__name__}: {error}')
    ros2('daemon', 'stop')  # the ros2 CLI started one for this domain
    failed = [name for name, passed in results if not passed]
    print(f'{len(results) - len(failed)} of {len(results)} checks passed')
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
