#!/usr/bin/env python3
"""Compares two folders of generated measurements (docs/measurements) ignoring time columns.

    tools/measurements_diff.py OLD_DIR NEW_DIR

A refactoring must leave every table identical but for what a clock measured: CSV columns whose
name ends in _ms (or holds "time"), and the Markdown cells of such columns, are dropped; rows
are compared as a set, since charts order some tables by time. Prints one line per file and
exits 1 when any differs beyond its time columns.
"""
import csv
import io
import pathlib
import re
import sys

TIME_COLUMN = re.compile(r"(_ms$|time|cpu|_ns_per_)", re.IGNORECASE)
MD_TIME_HEADER = re.compile(r"(ms\b|time|CPU)", re.IGNORECASE)
GENERATED_LINE = re.compile(r"^(Generated|Made) ")


def csv_rows(text):
    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        return set()
    keep = [i for i, name in enumerate(rows[0]) if not TIME_COLUMN.search(name)]
    return {tuple(row[i] for i in keep if i < len(row)) for row in rows}


def md_rows(text):
    rows, keep = set(), None
    for line in text.splitlines():
        if GENERATED_LINE.match(line) or not line.strip():
            continue
        if not line.startswith("|"):
            rows.add((line,))
            keep = None
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if keep is None:  # a table's header row
            keep = [i for i, c in enumerate(cells) if not MD_TIME_HEADER.search(c)]
        rows.add(tuple(cells[i] for i in keep if i < len(cells)))
    return rows


def main():
    if len(sys.argv) != 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    old, new = map(pathlib.Path, sys.argv[1:])
    differ = False
    for path in sorted(old.glob("*.csv")) + sorted(old.glob("*.md")):
        other = new / path.name
        if not other.exists():
            print(f"missing {path.name}")
            differ = True
            continue
        compare = csv_rows if path.suffix == ".csv" else md_rows
        a, b = compare(path.read_text()), compare(other.read_text())
        if a == b:
            print(f"same    {path.name}")
        else:
            differ = True
            print(f"DIFFERS {path.name}: {len(a - b)} rows only in {old}, {len(b - a)} only in {new}")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
