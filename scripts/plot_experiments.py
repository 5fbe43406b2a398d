#!/usr/bin/python3
"""Figures of `fastron bench NAME`, drawn from the results.csv it wrote.

Usage: /usr/bin/python3 scripts/plot_experiments.py NAME OUTPUT_DIR
"""
import csv
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    return float("nan") if text == "nan" else float(text)


def mean_std(values):
    values = np.array([v for v in values if not np.isnan(v)])
    if len(values) == 0:
        return float("nan"), float("nan")
    return values.mean(), values.std(ddof=1) if len(values) > 1 else 0.0


def plot_static(rows, out):
    """The paper's Fig. 5: accuracy, TPR and TNR of each method, one panel per robot."""
    dofs = sorted({r["dof"] for r in rows}, key=int)
    methods = list(dict.fromkeys(r["method"] for r in rows))
    fig, axes = plt.subplots(1, len(dofs), figsize=(6.5 * len(dofs), 4.8), squeeze=False)
    for ax, dof in zip(axes[0], dofs):
        width = 0.26
        x = np.arange(len(methods))
        for k, (key, label) in enumerate((("accuracy", "accuracy"), ("tpr", "TPR"), ("tnr", "TNR"))):
            stats = [mean_std([number(r[key]) for r in rows if r["dof"] == dof and r["method"] == m]) for m in methods]
            ax.bar(x + (k - 1) * width, [s[0] for s in stats], width, yerr=[s[1] for s in stats], capsize=3, label=label)
        ax.set_xticks(x, methods)
        ax.set_ylim(0.5, 1.02)
        ax.set_ylabel("rate on the test configurations (FCL ground truth)")
        ax.set_title(f"{dof} DOF, static environment")
        ax.grid(axis="y", alpha=0.3)
        ax.legend(loc="lower left")
    fig.tight_layout()
    fig.savefig(out / "static.png", dpi=110)


def plot_sweep(rows, out, parameter):
    """The paper's Fig. 4 (beta) and Fig. 6 (gamma): TPR, TNR (and |S|/N) against the parameter."""
    dofs = sorted({r["dof"] for r in rows}, key=int)
    fig, axes = plt.subplots(1, len(dofs), figsize=(6.5 * len(dofs), 4.5), squeeze=False)
    for ax, dof in zip(axes[0], dofs):
        groups = defaultdict(list)
        for r in rows:
            if r["dof"] == dof:
                groups[float(r[parameter])].append(r)
        xs = sorted(groups)
        keys = [("tpr", "TPR"), ("tnr", "TNR")] + ([("support_ratio", "|S| / N")] if parameter == "gamma" else [])
        for key, label in keys:
            stats = [mean_std([number(r[key]) for r in groups[x]]) for x in xs]
            ax.errorbar(xs, [s[0] for s in stats], yerr=[s[1] for s in stats], marker="o", capsize=3, label=label)
        ax.set_xscale("log")
        ax.set_xlabel("β (conditional bias)" if parameter == "beta" else "γ (kernel width parameter)")
        ax.set_ylabel("rate" if parameter == "beta" else "rate, or support points per training point")
        ax.set_ylim(0, 1.02)
        ax.set_title(f"{dof} DOF")
        ax.grid(alpha=0.3)
        ax.legend(loc="lower right" if parameter == "beta" else "center right")
    fig.tight_layout()
    fig.savefig(out / f"static-{parameter}.png", dpi=110)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    name, out = sys.argv[1], Path(sys.argv[2])
    rows = read(out / "results.csv")
    if name == "static":
        plot_static(rows, out)
    elif name in ("static-beta", "static-gamma"):
        plot_sweep(rows, out, name.split("-")[1])
    else:
        sys.exit(f"no plot for '{name}'")


if __name__ == "__main__":
    main()
