"""make soak: `comply run --sim` under a random stream of valid and invalid commands from two
sender processes for SOAK_MINUTES (default 30). Every command must be accounted exactly once
(applied, or rejected with the expected reason; the second sender's commands are refused as
`other_publisher` while the first holds the topics), no FAULT may appear (none is injected), the
transport process (comply-transport, DDS) may not end, and the memory of the host and its
transport process must stay flat. Writes report.md, rss.csv and rss.png to the output folder.

Usage: soak.py COMPLY_CLI PYTHON_MODULE_DIR CONFIG_FILE OUT_DIR MINUTES
"""

import math
import multiprocessing
import os
import random
import subprocess
import sys
import time

CLI, PYTHON_DIR, CONFIG, OUT, MINUTES = sys.argv[1:6]
sys.path.insert(0, PYTHON_DIR)
import comply  # noqa: E402

DOMAIN = random.randint(1, 230)
NAME = 'soak'
SECONDS = float(MINUTES) * 60.0
RATE_HZ = 200.0  # per sender


def rss_kb(pid):
    with open(f'/proc/{pid}/status') as f:
        for line in f:
            if line.startswith('VmRSS:'):
                return int(line.split()[1])
    return 0


def transport_rss_kb(host_pid):
    """The RSS of the host's transport process (its child running comply-transport), 0 if none."""
    total = 0
    for entry in os.listdir('/proc'):
        if not entry.isdigit():
            continue
        try:
            with open(f'/proc/{entry}/stat') as f:
                parent = int(f.read().rsplit(')', 1)[1].split()[1])
            with open(f'/proc/{entry}/cmdline', 'rb') as f:
                program = f.read()
        except (OSError, IndexError, ValueError):
            continue
        if parent == host_pid and b'comply-transport' in program:
            total += rss_kb(int(entry))
    return total


def command(client, start, rng):
    """A random command and the reason it must be rejected for (None: valid)."""
    kind = rng.random()
    offset = [rng.uniform(-0.02, 0.02) for _ in range(3)]
    position = [start['tcp_position'][i] + offset[i] for i in range(3)]
    orientation = list(start['tcp_orientation'])
    if kind < 0.05:
        return client.send_cartesian(position=[math.nan, 0, 0], orientation=orientation), \
            'non_finite'
    if kind < 0.10:
        return client.send_cartesian(position=position,
                                     orientation=[2 * q for q in orientation]), \
            'invalid_quaternion'
    if kind < 0.15:
        far = [position[0] + 0.5, position[1], position[2]]
        return client.send_cartesian(position=far, orientation=orientation), 'pose_jump'
    if kind < 0.20:
        return client.send_cartesian(stiffness_translational=[[-1, 0, 0], [0, 1, 0], [0, 0, 1]]), \
            'invalid_gains'
    return client.send_cartesian(position=position, orientation=orientation), None


def sender(index, results):
    rng = random.Random(index)
    client = comply.Client(name=NAME, domain=DOMAIN, timeout=60.0)
    start = client.state()
    pending, counts = {}, {'sent': 0, 'applied': 0, 'missing': 0, 'wrong': 0}
    reasons = {}
    end = time.monotonic() + SECONDS
    next_send = time.monotonic()
    last_check = time.monotonic()
    while time.monotonic() < end:
        next_send += 1.0 / RATE_HZ
        while time.monotonic() < next_send:
            time.sleep(0.0005)
        stamp, expected = command(client, start, rng)
        pending[stamp] = (expected, time.monotonic())
        counts['sent'] += 1
        if time.monotonic() - last_check > 1.0:
            last_check = time.monotonic()
            settle(client, pending, counts, reasons, older_than=2.0)
    settle(client, pending, counts, reasons, older_than=-10.0, wait=5.0)
    results[index] = (counts, reasons)


def settle(client, pending, counts, reasons, older_than, wait=0.0):
    now = time.monotonic()
    for stamp, (expected, sent) in list(pending.items()):
        if now - sent < older_than:
            continue
        outcome = client.outcome(stamp, timeout=wait)
        if outcome is None:
            if now - sent > 10.0 or older_than < 0:
                counts['missing'] += 1
                del pending[stamp]
            continue
        del pending[stamp]
        reason = 'applied' if outcome['applied'] else outcome['reason']
        reasons[reason] = reasons.get(reason, 0) + 1
        counts['applied'] += outcome['applied']
        acceptable = {expected or 'applied', 'other_publisher', 'stale_stamp', 'queue_full'}
        if reason not in acceptable:
            counts['wrong'] += 1
            if len(counts.setdefault('wrong_examples', [])) < 5:
                counts['wrong_examples'].append(
                    f"expected {expected or 'applied'}, got {reason}: {outcome.get('message', '')}")


def main():
    os.makedirs(OUT, exist_ok=True)
    host = subprocess.Popen([CLI, 'run', '--config', CONFIG, '--sim', '--domain', str(DOMAIN),
                             '--name', NAME, '--duration', str(SECONDS + 60)],
                            stdout=open(f'{OUT}/host.log', 'w'), stderr=subprocess.STDOUT)
    time.sleep(3)
    manager = multiprocessing.Manager()
    results = manager.dict()
    senders = [multiprocessing.Process(target=sender, args=(i, results)) for i in range(2)]
    for process in senders:
        process.start()
    rss = []
    t0 = time.monotonic()
    with open(f'{OUT}/rss.csv', 'w') as f:
        f.write('time_s,rss_kb,host_kb,transport_kb\n')
        while any(p.is_alive() for p in senders):
            host_kb, transport_kb = rss_kb(host.pid), transport_rss_kb(host.pid)
            sample = (time.monotonic() - t0, host_kb + transport_kb)
            rss.append(sample)
            f.write(f'{sample[0]:.1f},{sample[1]},{host_kb},{transport_kb}\n')
            f.flush()
            print(f'\rsoak: {sample[0] / 60:5.1f} of {float(MINUTES):.1f} min, RSS host '
                  f'{host_kb / 1024:.1f} MB + transport {transport_kb / 1024:.1f} MB', end='',
                  flush=True)
            time.sleep(10)
    print()
    for process in senders:
        process.join()
    diagnostics = comply.Client(name=NAME, domain=DOMAIN, timeout=30.0).diagnostics(timeout=5)
    host.send_signal(2)
    host.wait(timeout=30)
    with open(f'{OUT}/host.log') as f:
        summary = [line for line in f if 'transport restarts' in line]
    restarts = int(summary[-1].rsplit('transport restarts', 1)[1]) if summary else -1
    report(rss, dict(results), diagnostics, restarts)


def report(rss, results, diagnostics, restarts):
    warm = [kb for t, kb in rss if t > 60] or [kb for _, kb in rss]
    lines = [f'# Soak: {MINUTES} min, 2 senders at {RATE_HZ:.0f} Hz each', '',
             '| sender | sent | applied | missing | wrong outcome | outcomes by reason |',
             '|---|---|---|---|---|---|']
    failed = False
    for index, (counts, reasons) in sorted(results.items()):
        lines.append(f"| {index} | {counts['sent']} | {counts['applied']} | {counts['missing']} | "
                     f"{counts['wrong']} | {dict(sorted(reasons.items()))} |")
        failed |= counts['missing'] > 0 or counts['wrong'] > 0
        for example in counts.get('wrong_examples', []):
            lines.append(f'|   | sender {index}: {example} | | | | |')
    faults = diagnostics['faults'] if diagnostics else -1
    overruns = diagnostics.get('overruns', -1) if diagnostics else -1
    growth = (warm[-1] - warm[0]) / 1024 if warm else 0.0
    last_fault = diagnostics.get('last_fault', '') if diagnostics else ''
    lines += ['', f'host: faults {faults}, overruns {overruns}, cycles '
                  f"{diagnostics.get('cycles', '?') if diagnostics else '?'}"
                  + (f', last fault: {last_fault}' if last_fault else ''),
              f'transport restarts {restarts}',
              f'RSS of the host and its transport process after the first minute: '
              f'{warm[0] / 1024:.1f} MB -> {warm[-1] / 1024:.1f} MB (max {max(warm) / 1024:.1f} MB, '
              f'growth {growth:.2f} MB); curve: rss.csv, rss.png']
    failed |= faults != 0 or growth > 5.0 or restarts != 0
    lines.append('')
    lines.append('FAILED' if failed else 'ok')
    with open(f'{OUT}/report.md', 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('\n'.join(lines))
    try:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
        figure, axes = plt.subplots(figsize=(7, 3))
        axes.plot([t / 60 for t, _ in rss], [kb / 1024 for _, kb in rss])
        axes.set_xlabel('time [min]')
        axes.set_ylabel('RSS, host + transport [MB]')
        axes.set_title('comply run --sim under two senders')
        figure.tight_layout()
        figure.savefig(f'{OUT}/rss.png', dpi=120)
    except ImportError:
        print('matplotlib missing: no rss.png')
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
