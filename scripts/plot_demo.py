#!/usr/bin/python3
"""Plots of `fastron demo`: the final C-space (cspace.png) and the per-step metrics (steps.png).

Usage: /usr/bin/python3 scripts/plot_demo.py OUTPUT_DIR   (reads the CSV files the demo wrote there)
"""
import csv
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Circle, Patch  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows")
    return rows


def plot_cspace(out):
    grid = read_csv(out / "cspace_grid.csv")
    n = int(round(math.sqrt(len(grid))))
    t1 = np.array([float(r["theta1"]) for r in grid]).reshape(n, n)
    t2 = np.array([float(r["theta2"]) for r in grid]).reshape(n, n)
    truth = np.array([int(r["in_collision"]) for r in grid]).reshape(n, n)
    score = np.array([float(r["score"]) for r in grid]).reshape(n, n)
    support = read_csv(out / "support_points.csv")
    discs = read_csv(out / "discs.csv")

    fig, (ws, cs) = plt.subplots(1, 2, figsize=(13, 6), gridspec_kw={"width_ratios": [1, 1.15]})

    # Workspace: the discs and the arm's reach.
    ws.add_patch(Circle((0, 0), 1.8, fill=False, ls="--", color="0.6"))
    for d in discs:
        ws.add_patch(Circle((float(d["x"]), float(d["y"])), float(d["radius"]), color="tab:orange", alpha=0.8))
    ws.plot([0], [0], "ko")
    ws.set_xlim(-2.2, 2.2)
    ws.set_ylim(-2.2, 2.2)
    ws.set_aspect("equal")
    ws.set_xlabel("x (m)")
    ws.set_ylabel("y (m)")
    ws.set_title("Workspace at the last step")
    ws.legend(handles=[Patch(color="tab:orange", label="obstacle discs"),
                       Line2D([], [], ls="--", color="0.6", label="reach of the arm (1.8 m)")],
              loc="upper right", fontsize=9)

    # C-space: exact obstacle region, learned boundary, support points.
    cs.contourf(t1, t2, truth, levels=[0.5, 1.5], colors=["0.75"])
    cs.contour(t1, t2, score, levels=[0], colors=["tab:red"], linewidths=1.6)
    wrong = (score > 0) != (truth > 0)
    cs.contourf(t1, t2, wrong.astype(float), levels=[0.5, 1.5], colors=["none"], hatches=["////"])
    pos = [(float(r["theta1"]), float(r["theta2"])) for r in support if float(r["weight"]) > 0]
    neg = [(float(r["theta1"]), float(r["theta2"])) for r in support if float(r["weight"]) < 0]
    if pos:
        cs.scatter(*zip(*pos), s=30, c="tab:red", marker="+", linewidths=1.2)
    if neg:
        cs.scatter(*zip(*neg), s=8, c="tab:blue", marker="o", linewidths=0)
    cs.set_xlim(-math.pi, math.pi)
    cs.set_ylim(-math.pi, math.pi)
    cs.set_aspect("equal")
    cs.set_xlabel("θ1 (rad)")
    cs.set_ylabel("θ2 (rad)")
    accuracy = 1 - wrong.mean()
    cs.set_title(f"C-space: {len(support)} support points, grid accuracy {accuracy:.3f}")
    cs.legend(handles=[Patch(color="0.75", label="C_obs (exact)"),
                       Line2D([], [], color="tab:red", label="Fastron boundary f(q) = 0"),
                       Patch(facecolor="none", hatch="////", edgecolor="k", label="misclassified"),
                       Line2D([], [], ls="", marker="+", color="tab:red", label="support point, in collision"),
                       Line2D([], [], ls="", marker="o", color="tab:blue", label="support point, free")],
              loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=3, fontsize=9)
    fig.tight_layout()
    fig.savefig(out / "cspace.png", dpi=110)
    plt.close(fig)


def plot_steps(out):
    rows = read_csv(out / "steps.csv")
    step = [int(r["step"]) for r in rows]
    fig, (rates, size) = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    for key, label in (("accuracy", "accuracy"), ("tpr", "TPR"), ("tnr", "TNR")):
        rates.plot(step, [float(r[key]) for r in rows], marker=".", label=label)
    rates.set_ylabel("rate on fresh configurations")
    rates.set_ylim(0.5, 1.01)
    rates.grid(alpha=0.3)
    rates.legend(loc="lower left")
    rates.set_title("Fastron tracking moving obstacles")
    size.plot(step, [int(r["support"]) for r in rows], color="tab:purple", marker=".", label="|S|")
    size.set_ylabel("support points |S|")
    size.set_xlabel("step (obstacles moved, model updated)")
    size.grid(alpha=0.3)
    twin = size.twinx()
    twin.plot(step, [float(r["update_ms"]) for r in rows], color="tab:gray", marker=".", label="update time")
    twin.set_ylabel("update time (ms)")
    size.legend(handles=size.get_lines() + twin.get_lines(), loc="upper left")
    fig.tight_layout()
    fig.savefig(out / "steps.png", dpi=110)
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    plot_cspace(out)
    plot_steps(out)


if __name__ == "__main__":
    main()
