#!/usr/bin/env python3
"""Exits 0 when the sweep results files hold the same runs with the same results, all but the
numbers that are wall times or name the host; prints the first difference otherwise.

Usage: sweep_results_equal.py RESULTS.jsonl OTHER.jsonl [...]"""
import json
import sys

WALL = {"wall_time_s", "host", "planning_time_s", "trajectory_time_s", "flight_wall_time_s",
        "solve_time_s", "latency_s"}


def without_wall_times(value):
    if isinstance(value, dict):
        return {k: without_wall_times(v) for k, v in value.items() if k not in WALL}
    if isinstance(value, list):
        return [without_wall_times(v) for v in value]
    return value


def load(path):
    with open(path, encoding="utf-8") as f:
        return [without_wall_times(json.loads(line)) for line in f]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    first = load(sys.argv[1])
    if not first:
        sys.exit(f"{sys.argv[1]}: no results")
    for other_path in sys.argv[2:]:
        other = load(other_path)
        if len(other) != len(first):
            sys.exit(f"{other_path}: {len(other)} runs, {sys.argv[1]}: {len(first)}")
        for a, b in zip(first, other):
            if a != b:
                keys = sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k))
                sub = sorted(k for k in set(a.get("summary", {})) | set(b.get("summary", {}))
                             if a.get("summary", {}).get(k) != b.get("summary", {}).get(k))
                sys.exit(f"{other_path}: run {a.get('id')} differs in {keys} {sub}")
    print(f"{len(first)} runs, the same in {len(sys.argv) - 1} files")


if __name__ == "__main__":
    main()
