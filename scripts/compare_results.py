#!/usr/bin/python3
"""Compares two result folders of `fastron bench NAME --quick` (or of every experiment) and
says which CSV cells differ, leaving out the timing columns (names ending in _s), which no two
runs share. Used to check that a refactor changes no result (docs/reliability.md).

    scripts/compare_results.py BEFORE AFTER
Exit code 0 when every compared cell is equal, 1 otherwise."""
import csv
import pathlib
import sys


def rows(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


def compare(before, after):
    differing = 0
    for old in sorted(pathlib.Path(before).rglob("*.csv")):
        relative = old.relative_to(before)
        new = pathlib.Path(after) / relative
        if not new.exists():
            print(f"{relative}: missing in {after}")
            differing += 1
            continue
        a, b = rows(old), rows(new)
        header = a[0] if a and not any(c.replace(".", "").lstrip("-").isdigit() for c in a[0]) else []
        timing = {i for i, name in enumerate(header) if name.endswith("_s")}
        if len(a) != len(b):
            print(f"{relative}: {len(a)} rows before, {len(b)} after")
            differing += 1
            continue
        cells = [
            (r, c)
            for r, (x, y) in enumerate(zip(a, b))
            for c, (u, v) in enumerate(zip(x, y))
            if c not in timing and u != v
        ]
        if cells:
            r, c = cells[0]
            name = header[c] if header else f"column {c + 1}"
            print(f"{relative}: {len(cells)} cells differ, first row {r} {name}: {a[r][c]} -> {b[r][c]}")
            differing += 1
        else:
            print(f"{relative}: equal ({len(a)} rows, {len(timing)} timing columns left out)")
    return differing


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(1 if compare(sys.argv[1], sys.argv[2]) else 0)
