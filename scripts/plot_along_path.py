#!/usr/bin/python3
"""Plot of `fastron eval --path ... --out DIR` (along_path.png): along the path, the model's score
against its decision threshold, and each state's clearance from the nearest obstacle, with the
free states the model calls colliding marked. It shows where a model closes a passage a planner
needs.

Usage: /usr/bin/python3 scripts/plot_along_path.py OUTPUT_DIR   (reads DIR/along_path.csv)
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    with open(out / "along_path.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{out / 'along_path.csv'}: no states")
    arc = np.array([float(r["arc_length"]) for r in rows])
    score = np.array([float(r["score"]) for r in rows])
    fcl = np.array([r["fcl_collides"] == "1" for r in rows])
    model = np.array([r["model_collides"] == "1" for r in rows])
    clearance_cm = np.array([float(r["clearance_m"]) * 100 for r in rows])
    wrong_free = model & ~fcl  # free under FCL, colliding for the model
    missed = fcl & ~model

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(11, 6.5), sharex=True)
    top.plot(arc, score, color="tab:blue", lw=1.2, label="model score")
    top.axhline(0, color="black", lw=0.8, label="threshold: above it the model says collides")
    top.scatter(arc[wrong_free], score[wrong_free], s=10, color="tab:red", zorder=3,
                label=f"free, called colliding ({wrong_free.sum()})")
    if missed.any():
        top.scatter(arc[missed], score[missed], s=14, marker="x", color="black", zorder=3,
                    label=f"colliding, called free ({missed.sum()})")
    top.set_ylabel("model score")
    top.set_title(f"{len(rows)} states along the path: FCL says {fcl.sum()} collide, "
                  f"the model {model.sum()}")
    top.grid(alpha=0.3)
    top.legend(loc="best", fontsize=8)

    bottom.plot(arc, clearance_cm, color="tab:green", lw=1.2, label="clearance (FCL)")
    bottom.scatter(arc[wrong_free], clearance_cm[wrong_free], s=10, color="tab:red", zorder=3,
                   label="free, called colliding")
    for level in (1, 2, 5):
        bottom.axhline(level, color="grey", lw=0.6, ls="--")
    bottom.set_ylim(bottom=0)
    bottom.set_xlabel("joint-space distance along the path (rad)")
    bottom.set_ylabel("distance to the nearest obstacle (cm)")
    bottom.grid(alpha=0.3)
    bottom.legend(loc="best", fontsize=8)

    fig.tight_layout()
    fig.savefig(out / "along_path.png", dpi=110)


if __name__ == "__main__":
    main()
