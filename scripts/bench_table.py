#!/usr/bin/python3
"""Markdown tables from a Google Benchmark JSON file written by fastron_bench.

Usage: build/release/bench/fastron_bench --benchmark_out=bench.json --benchmark_out_format=json
       /usr/bin/python3 scripts/bench_table.py bench.json
Query speed-ups are ratios of benchmarks measured in the same run.
"""
import json
import re
import sys
from collections import defaultdict


def load(path):
    with open(path) as f:
        data = json.load(f)
    runs = {}
    for b in data["benchmarks"]:
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "mean":
            continue
        name = b["run_name"] if "run_name" in b else b["name"]
        args = dict(re.findall(r"(\w+):(\d+)", name))
        family = name.split("/")[0]
        runs[(family, tuple(sorted((k, int(v)) for k, v in args.items())))] = b
    return data["context"], runs


def ns(b):
    scale = {"ns": 1, "us": 1e3, "ms": 1e6, "s": 1e9}[b["time_unit"]]
    return b["real_time"] * scale


ROBOTS = ["rod2", "rod4", "baxter", "ur3", "panda", "psm"]


def geometry_table(runs):
    fk = {dict(a)["robot"]: b for (f, a), b in runs.items() if f == "BM_ForwardKinematics"}
    if not fk:
        return
    print("Time per exact check (ns): forward kinematics alone; FK + FCL as checkers are made "
          "(clearance bounds first, FCL asked about the pairs they leave), FCL's broad phase "
          "alone (`proveMotionsFree` off) and FK + GJK, with 0.1 m boxes placed near the robot; "
          "the share of the queries in collision in brackets; the last three columns time the "
          "same checkers on configurations FCL finds free only (\"-\": none among 16 384 "
          "samples):\n")
    print("| robot | obstacles | FK | FK + FCL | FCL, broad phase | FK + GJK | broad phase / FCL | "
          "FCL, free only | broad phase, free only | GJK, free only |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r, name in enumerate(ROBOTS):
        for n in (1, 3, 10, 30, 100):
            key = lambda bounds: (("bounds", bounds), ("obstacles", n), ("robot", r))
            fcl = runs.get(("BM_Check<FclChecker>", key(1)))
            broad = runs.get(("BM_Check<FclChecker>", key(0)))
            gjk = runs.get(("BM_Check<GjkChecker>", key(0)))
            if not fcl or not broad or not gjk:
                continue
            free = [runs.get(("BM_CheckFree<FclChecker>", key(1))),
                    runs.get(("BM_CheckFree<FclChecker>", key(0))),
                    runs.get(("BM_CheckFree<GjkChecker>", key(0)))]
            free_cells = " | ".join(
                "-" if not b or "error_occurred" in b else f"{ns(b):.0f}" for b in free)
            print(f"| {name} | {n} | {ns(fk[r]):.0f} | {ns(fcl):.0f} ({fcl['in_collision']:.0%}) | "
                  f"{ns(broad):.0f} | {ns(gjk):.0f} | {ns(broad) / ns(fcl):.1f}x | {free_cells} |")
    print()


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    context, runs = load(sys.argv[1])
    print(f"Machine: {context.get('num_cpus')} CPUs at {context.get('mhz_per_cpu')} MHz; "
          f"run {context.get('date')}.\n")
    geometry_table(runs)
    if not any(f == "BM_Train" for f, _ in runs):
        return

    train = defaultdict(dict)
    for (family, args), b in runs.items():
        if family == "BM_Train":
            a = dict(args)
            train[a["N"]][a["d"]] = b
    dims = sorted({d for row in train.values() for d in row})
    print("Training time (Algorithm 1 from scratch, uniform data, paper's gamma per d), "
          "with |S| and iterations:\n")
    print("| N | " + " | ".join(f"d = {d}" for d in dims) + " |")
    print("|---|" + "---|" * len(dims))
    for n in sorted(train):
        cells = []
        for d in dims:
            b = train[n].get(d)
            cells.append("" if b is None else
                         f"{ns(b) / 1e6:.1f} ms (|S| {b['support']:.0f}, {b['iterations']:.0f} it)")
        print(f"| {n} | " + " | ".join(cells) + " |")

    print("\nQuery time per configuration (ns) and the speed-up of the float path over the "
          "plain double loop:\n")
    print("| |S| | d | float RQ | float Gaussian | plain double RQ | batch RQ (per query) | speed-up |")
    print("|---|---|---|---|---|---|---|")
    keys = sorted({args for (family, args) in runs if family == "BM_QueryPlainDouble"},
                  key=lambda a: (dict(a)["S"], dict(a)["d"]))
    for args in keys:
        a = dict(args)
        rq = runs.get(("BM_QueryFloat<KernelType::RationalQuadratic>", args))
        g = runs.get(("BM_QueryFloat<KernelType::Gaussian>", args))
        plain = runs[("BM_QueryPlainDouble", args)]
        batch = runs.get(("BM_QueryBatch", args))
        per_query = ns(batch) / 1024 if batch else float("nan")
        print(f"| {a['S']} | {a['d']} | {ns(rq):.0f} | {ns(g):.0f} | {ns(plain):.0f} | "
              f"{per_query:.0f} | {ns(plain) / ns(rq):.1f}x |")


if __name__ == "__main__":
    main()
