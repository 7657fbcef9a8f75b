#!/usr/bin/env python3
"""Two builds of rast_bench (or any Google Benchmark binary) compared in back-to-back pairs.

Each round runs every selected benchmark on build A and then on build B (the order swapped every
other round), one process each, and takes B's figure over A's. The report is, per benchmark and
per figure, the median of those pair ratios: on a shared machine whose speed drifts by a quarter
from one minute to the next, two runs seconds apart see the same machine, where rounds of a whole
benchmark list do not. Figures are the real time and every user counter ending in `_ms` (the frame
benchmarks' stage times). Below 1: B is faster.

    bench/compare_builds.py [--rounds 5] [--min-time 0.4] [--filter REGEX] BUILD_A BUILD_B

BUILD_A and BUILD_B are executables; a build that differs only by an environment variable can be
given as a two-line wrapper script (`VAR=1 exec path/to/rast_bench "$@"`).
"""

import argparse
import csv
import io
import statistics
import subprocess
import sys


def list_benchmarks(binary, pattern):
    listed = subprocess.run([binary, f"--benchmark_filter={pattern}", "--benchmark_list_tests"],
                            capture_output=True, text=True, check=True).stdout.split()
    if not listed:
        sys.exit(f"no benchmark of {binary} matches {pattern!r}")
    return listed


def run_once(binary, name, min_time):
    """The figures of one run of one benchmark (anchored to its whole name)."""
    done = subprocess.run([binary, f"--benchmark_filter=^{name}$", f"--benchmark_min_time={min_time}",
                           "--benchmark_format=csv"], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{binary} failed on {name}:\n{done.stderr}")
    # Google Benchmark prints its context on stderr and the table on stdout; the table may be
    # preceded by lines that are not CSV (warnings), so start at its header.
    lines = done.stdout.splitlines()
    header = next((i for i, line in enumerate(lines) if line.startswith("name,")), None)
    if header is None:
        sys.exit(f"{binary} printed no results for {name}")
    rows = list(csv.DictReader(io.StringIO("\n".join(lines[header:]))))
    if not rows or rows[0].get("error_occurred") == "true":
        sys.exit(f"{binary}: {name} reported an error: {rows[0].get('error_message') if rows else ''}")
    row = rows[0]
    figures = {"real_time": float(row["real_time"]), "unit": row.get("time_unit", "")}
    for key, value in row.items():
        if key.endswith("_ms") and value:
            figures[key] = float(value)
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build_a")
    parser.add_argument("build_b")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--min-time", type=float, default=0.4,
                        help="--benchmark_min_time of each run, seconds")
    parser.add_argument("--filter", default="BM_Frame(W4|W1)/0/threads:(1|2)/real_time|"
                        "BM_FrameW2Tiny/area:(1|10)/threads:(1|2)/",
                        help="benchmarks to compare (regex, as --benchmark_filter)")
    args = parser.parse_args()
    if args.rounds < 1:
        parser.error("--rounds must be at least 1")

    names = list_benchmarks(args.build_a, args.filter)
    ratios = {name: {} for name in names}
    absolute = {name: ([], []) for name in names}
    units = {}
    for r in range(args.rounds):
        for name in names:
            order = (args.build_a, args.build_b) if r % 2 == 0 else (args.build_b, args.build_a)
            results = {binary: run_once(binary, name, args.min_time) for binary in order}
            a, b = results[args.build_a], results[args.build_b]
            absolute[name][0].append(a["real_time"])
            absolute[name][1].append(b["real_time"])
            units[name] = a["unit"]
            for key in (a.keys() & b.keys()) - {"unit"}:
                if a[key] > 0:
                    ratios[name].setdefault(key, []).append(b[key] / a[key])
        print(f"round {r + 1} of {args.rounds} done", file=sys.stderr)

    print(f"B / A, median of {args.rounds} back-to-back pairs "
          f"(A: {args.build_a}, B: {args.build_b})")
    for name in names:
        keys = ["real_time"] + sorted(k for k in ratios[name] if k != "real_time")
        figures = " ".join(f"{k}={statistics.median(ratios[name][k]):.3f}"
                           for k in keys if k in ratios[name])
        a_ms, b_ms = (statistics.median(v) for v in absolute[name])
        print(f"{name}  {figures}  (real time, medians: A {a_ms:.3g} {units[name]}, "
              f"B {b_ms:.3g} {units[name]})")


if __name__ == "__main__":
    main()
