"""The plot scripts' reader: a CSV file with a header row as one list of floats per column."""
import csv


def read_columns(path, keep=None):
    """{column: [values]} of `path`; `keep(row)` (a dict of strings) selects rows when given."""
    with open(path, newline="") as handle:
        rows = [row for row in csv.DictReader(handle) if keep is None or keep(row)]
    if not rows:
        raise SystemExit(f"{path}: no rows")
    return {key: [float(row[key]) for row in rows] for key in rows[0]}
