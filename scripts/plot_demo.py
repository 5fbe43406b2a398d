#!/usr/bin/python3
"""Plots of `fastron demo` (demo.png): time to a valid plan per tick and checker, its split into
plan / verify / repair, and the model's accuracy and support set over the run.

Usage: /usr/bin/python3 scripts/plot_demo.py OUTPUT_DIR   (reads the ticks.csv the demo wrote there)
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COLOURS = {"Fastron": "tab:blue", "GJK": "tab:orange", "FCL": "tab:green"}


def number(text):
    return float("nan") if text == "nan" else float(text)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    with open(out / "ticks.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    methods = list(dict.fromkeys(r["method"] for r in rows))
    fig, (left, middle, right) = plt.subplots(1, 3, figsize=(17, 4.6))

    for m in methods:
        solved = [r for r in rows if r["method"] == m and r["solved"] == "1"]
        left.plot([int(r["tick"]) for r in solved], [number(r["total_s"]) * 1e3 for r in solved],
                  "o-", ms=3, color=COLOURS.get(m, "grey"), label=m)
    left.set_yscale("log")
    left.set_xlabel("tick (the boxes moved)")
    left.set_ylabel("plan + verify + repair (ms)")
    left.set_title("RRT-Connect: time to a valid plan")
    left.grid(alpha=0.3)
    left.legend()

    x = np.arange(len(methods))
    bottom = np.zeros(len(methods))
    for key, label, hatch in (("plan_s", "plan", ""), ("verify_s", "verify (FCL)", "//"),
                              ("repair_s", "repair (FCL)", "..")):
        heights = []
        for m in methods:
            values = [number(r[key]) * 1e3 for r in rows if r["method"] == m and r["solved"] == "1"]
            heights.append(np.mean(values) if values else 0.0)
        middle.bar(x, heights, 0.6, bottom=bottom, hatch=hatch, edgecolor="black",
                   color=[COLOURS.get(m, "grey") for m in methods], label=label)
        bottom += np.array(heights)
    middle.set_xticks(x, methods)
    middle.set_ylabel("mean time per query (ms)")
    middle.set_title("where the time goes")
    middle.grid(axis="y", alpha=0.3)
    middle.legend()

    fcl = [r for r in rows if r["method"] == "FCL"]
    ticks = [int(r["tick"]) for r in fcl]
    for key, label in (("accuracy", "accuracy"), ("tpr", "TPR"), ("tnr", "TNR")):
        right.plot(ticks, [number(r[key]) for r in fcl], label=label)
    right.set_ylim(0.5, 1.02)
    right.set_xlabel("tick")
    right.set_ylabel("rate against FCL on fresh configurations")
    right.set_title("the model while it follows the boxes")
    right.grid(alpha=0.3)
    support = right.twinx()
    support.plot(ticks, [number(r["support"]) for r in fcl], "k--", label="|S|")
    support.set_ylabel("support points |S| (dashed)")
    right.legend(loc="lower left")

    fig.tight_layout()
    fig.savefig(out / "demo.png", dpi=110)


if __name__ == "__main__":
    main()
