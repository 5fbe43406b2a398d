#!/usr/bin/python3
"""Two builds of fastron_bench compared on a noisy machine: runs them in turns, then prints each
benchmark's median time per build and the ratio, as a Markdown table.

Usage: /usr/bin/python3 scripts/bench_compare.py BEFORE_BENCH AFTER_BENCH FILTER [ROUNDS]
e.g.   git worktree add /tmp/before HEAD~1 && cmake -S /tmp/before -B /tmp/before/build -G Ninja \\
           -DFASTRON_BUILD_TESTS=OFF && ninja -C /tmp/before/build fastron_bench
       /usr/bin/python3 scripts/bench_compare.py /tmp/before/build/bench/fastron_bench \\
           build/release/bench/fastron_bench 'TaskSpaceQuery|ControlPoints<float>' 6

Turns, not one build after the other: a burst of load from elsewhere then falls on both builds,
and the median over the rounds leaves it out.
"""
import json
import statistics
import subprocess
import sys
import tempfile
from collections import defaultdict


def run(binary, pattern):
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([binary, f"--benchmark_filter={pattern}", "--benchmark_min_time=0.2",
                        f"--benchmark_out={out.name}", "--benchmark_out_format=json"],
                       check=True, stdout=subprocess.DEVNULL)
        with open(out.name) as f:
            data = json.load(f)
    scale = {"ns": 1, "us": 1e3, "ms": 1e6, "s": 1e9}
    return {b["name"]: b["real_time"] * scale[b["time_unit"]] for b in data["benchmarks"]}


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    before, after, pattern = sys.argv[1:4]
    rounds = int(sys.argv[4]) if len(sys.argv) == 5 else 5
    times = {before: defaultdict(list), after: defaultdict(list)}
    for r in range(rounds):
        for binary in (before, after):
            for name, t in run(binary, pattern).items():
                times[binary][name].append(t)
        print(f"round {r + 1} of {rounds}", file=sys.stderr)
    print(f"Medians of {rounds} rounds, ns (before: {before}; after: {after})\n")
    print("| benchmark | before | after | before / after |")
    print("|---|---|---|---|")
    for name in times[before]:
        if name not in times[after]:
            continue
        b = statistics.median(times[before][name])
        a = statistics.median(times[after][name])
        print(f"| {name} | {b:.1f} | {a:.1f} | {b / a:.2f}x |")


if __name__ == "__main__":
    main()
