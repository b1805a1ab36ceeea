"""Reading the studies' CSVs (hand, fidelity, PARTI, wiping): the rows of a file that has the
columns a figure needs, and its numeric columns grouped per run, each error naming the file in the
study's own exception class."""

import csv


def read_rows(path, required, what, error):
    """The rows of `path` as dicts. Raises `error` when the file cannot be read or lacks one of
    `required` ("<path>: not a <what> (no <columns> column)")."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f)
            missing = [c for c in required if c not in (reader.fieldnames or [])]
            if missing:
                raise error(f"{path}: not a {what} (no {', '.join(missing)} column)")
            return list(reader)
    except OSError as e:
        raise error(f"{path}: {e.strerror}") from e


def group_columns(path, rows, run_of, error, columns=None, skip=()):
    """{run_of(row): {column: [float]}} in file order: the given `columns`, or every column but those
    in `skip`. Raises `error` when there is no row or a cell is no number."""
    runs = {}
    try:
        for row in rows:
            group = runs.setdefault(run_of(row), {})
            for name in columns if columns is not None else [c for c in row if c not in skip]:
                group.setdefault(name, []).append(float(row[name]))
    except ValueError as e:
        raise error(f"{path}: {e}") from e
    if not runs:
        raise error(f"{path}: no samples")
    return runs
