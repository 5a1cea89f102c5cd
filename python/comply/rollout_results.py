"""What comply.rollouts() returns: a row of measures per episode, the recordings, the dataset,
and the call's throughput (docs/rollouts.md#results)."""

import csv
import math

import numpy as np


class RolloutResults:
    """What rollouts() returns: a row per episode in episode order (`rows`, a list of dicts),
    the recordings (MCAP paths in episode order; empty when not recording), the dataset's summary
    (export_lerobot's, or None), and the call's throughput."""

    def __init__(self, rows, *, recordings, dataset, wall_s, startup_s, workers,
                 steps_per_action):
        self.rows = rows
        self.recordings = recordings
        self.dataset = dataset
        self.wall_s = wall_s  # the whole call, the cluster's start and the export included
        self.startup_s = startup_s  # making the cluster and its client (0 when serial or given)
        self.workers = workers
        self.steps_per_action = steps_per_action

    def __len__(self):
        return len(self.rows)

    def __iter__(self):
        return iter(self.rows)

    def __getitem__(self, episode):
        return self.rows[episode]

    @property
    def steps(self):
        return int(sum(row["steps"] for row in self.rows))

    @property
    def steps_per_second(self):
        """Policy steps per second of the call's wall time."""
        return self.steps / self.wall_s if self.wall_s > 0 else math.inf

    @property
    def cycles_per_second(self):
        """Control cycles per second of the call's wall time (steps x steps_per_action)."""
        return self.steps_per_second * self.steps_per_action

    def column(self, name):
        """One column over the episodes as a numpy array."""
        if self.rows and name not in self.rows[0]:
            raise KeyError(f"no column {name!r}; the columns are {', '.join(self.rows[0])}")
        return np.array([row[name] for row in self.rows])

    def to_csv(self, path):
        """The rows as CSV, a header line of the column names; floats at full precision."""
        with open(path, "w", newline="") as file:
            if not self.rows:
                return
            writer = csv.DictWriter(file, fieldnames=list(self.rows[0]))
            writer.writeheader()
            writer.writerows(self.rows)

    def summary(self):
        """A few lines: the success rate, the means of the measures, the throughput."""
        n = len(self.rows)
        if n == 0:
            return "no episodes"
        succeeded = int(self.column("success").sum())
        lines = [f"{n} episodes on {self.workers} worker(s): {succeeded}/{n} succeeded "
                 f"({100.0 * succeeded / n:.1f} %), {int(self.column('rejected').sum())} "
                 f"commands rejected, {int(self.column('terminated').sum())} terminated"]
        unit = "m" if "tracking_error_rms_m" in self.rows[0] else "rad"
        scale, shown = (1000.0, "mm") if unit == "m" else (1000.0, "mrad")
        lines.append(
            f"mean tracking error {scale * self.column(f'tracking_error_rms_{unit}').mean():.3f} "
            f"{shown} RMS, {scale * self.column(f'tracking_error_max_{unit}').mean():.3f} {shown} "
            f"max; max contact force {self.column('max_contact_force_n').mean():.2f} N; energy "
            f"injected {self.column('energy_injected_j').mean():.4f} J, dissipated "
            f"{self.column('energy_dissipated_j').mean():.4f} J")
        lines.append(f"{self.steps} steps in {self.wall_s:.2f} s ({self.startup_s:.2f} s start-up):"
                     f" {self.steps_per_second:.0f} steps/s, {self.cycles_per_second:.0f} "
                     f"control cycles/s")
        return "\n".join(lines)

    def __repr__(self):
        return f"<RolloutResults {len(self.rows)} episodes, {self.steps_per_second:.0f} steps/s>"
