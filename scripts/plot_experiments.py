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


def plot_cspace(out):
    """The paper's Fig. 7: one row per environment: the cubes seen from above, then the exact
    C-space and the ones Fastron, ISVM and SSVM learn, with their support points."""
    grid = read(out / "grid.csv")
    support = read(out / "support.csv")
    cubes = read(out / "cubes.csv")
    envs = list(dict.fromkeys(r["environment"] for r in grid))
    methods = ["truth", "Fastron", "ISVM", "SSVM"]
    titles = {"truth": "FK + FCL (exact)", "Fastron": "Fastron", "ISVM": "ISVM", "SSVM": "SSVM"}
    fig, axes = plt.subplots(len(envs), 5, figsize=(17, 3.5 * len(envs)), squeeze=False)
    for row, env in zip(axes, envs):
        cells = [r for r in grid if r["environment"] == env]
        n = int(round(len(cells) ** 0.5))
        x1 = np.array([float(r["x1"]) for r in cells]).reshape(n, n)
        x2 = np.array([float(r["x2"]) for r in cells]).reshape(n, n)
        ws = row[0]
        ws.add_patch(plt.Circle((0, 0), 0.53, fill=False, ls="--", color="0.5"))
        for c in (c for c in cubes if c["environment"] == env):
            side, yaw = float(c["side"]), float(c["yaw"])
            corner = np.array([float(c["x"]), float(c["y"])]) - side / 2 * np.array(
                [np.cos(yaw) - np.sin(yaw), np.sin(yaw) + np.cos(yaw)])
            ws.add_patch(plt.Rectangle(corner, side, side, angle=np.degrees(yaw), color="tab:orange", alpha=0.8))
        ws.set_xlim(-0.7, 0.7)
        ws.set_ylim(-0.7, 0.7)
        ws.set_aspect("equal")
        ws.set_title(f"Environment {int(env) + 1}: cubes from above")
        ws.set_xlabel("x (m)")
        ws.set_ylabel("y (m)")
        for ax, method in zip(row[1:], methods):
            values = np.array([float(r[method]) for r in cells]).reshape(n, n)
            ax.contourf(x1, x2, values, levels=[0.5 if method == "truth" else 0, np.inf], colors=["0.55"])
            ax.contour(x1, x2, values, levels=[0.5 if method == "truth" else 0], colors=["k"], linewidths=0.8)
            if method != "truth":
                pts = [r for r in support if r["environment"] == env and r["method"] == method]
                pos = [(float(p["x1"]), float(p["x2"])) for p in pts if float(p["weight"]) > 0]
                neg = [(float(p["x1"]), float(p["x2"])) for p in pts if float(p["weight"]) <= 0]
                if pos:
                    ax.scatter(*zip(*pos), s=9, c="tab:red", label="support, in collision")
                if neg:
                    ax.scatter(*zip(*neg), s=9, c="tab:blue", label="support, free")
                ax.set_title(f"{titles[method]} ({len(pts)} support points)")
            else:
                ax.set_title(titles[method])
            ax.set_xlim(-1, 1)
            ax.set_ylim(-1, 1)
            ax.set_aspect("equal")
            ax.set_xlabel("yaw (scaled to [-1, 1])")
            ax.set_ylabel("pitch (scaled)")
    handles, labels = axes[0][2].get_legend_handles_labels()
    fig.legend(handles + [plt.Rectangle((0, 0), 1, 1, color="0.55")], labels + ["C_obs"], loc="lower center", ncol=3)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(out / "cspace.png", dpi=100)


def plot_changing(rows, out):
    """The paper's Figs. 9 and 11: accuracy, TPR and TNR against FCL after every update, per case."""
    cases = list(dict.fromkeys(r["case"] for r in rows))
    methods = ["Fastron (FCL)", "Fastron (GJK)", "FK+GJK"]
    fig, axes = plt.subplots(3, len(cases), figsize=(5 * len(cases), 9), squeeze=False, sharex=True)
    for col, case in enumerate(cases):
        for row_index, (key, label) in enumerate((("accuracy", "accuracy"), ("tpr", "TPR"), ("tnr", "TNR"))):
            ax = axes[row_index][col]
            for method, style in zip(methods, ("-", "--", ":")):
                by_step = defaultdict(list)
                for r in rows:
                    if r["case"] == case and r["method"] == method:
                        by_step[int(r["step"])].append(number(r[key]))
                steps = sorted(by_step)
                ax.plot(steps, [mean_std(by_step[s])[0] for s in steps], style, marker=".", label=method)
            ax.set_ylim(0.5, 1.01)
            ax.grid(alpha=0.3)
            if col == 0:
                ax.set_ylabel(f"{label} against FCL")
            if row_index == 0:
                ax.set_title(case)
            if row_index == 2:
                ax.set_xlabel("update (the boxes moved)")
    axes[0][0].legend(loc="lower left")
    fig.tight_layout()
    fig.savefig(out / "changing.png", dpi=100)


def plot_sweep_obstacles(rows, out):
    """The paper's Fig. 12: query time against the number of obstacles and the share of C_obs."""
    counts = sorted({int(r["obstacles"]) for r in rows})
    fig, (by_count, by_cobs) = plt.subplots(1, 2, figsize=(13, 4.8))
    for method, marker in (("Fastron", "o"), ("FK+GJK", "s"), ("FK+FCL", "^")):
        stats = [mean_std([number(r["query_s"]) * 1e6 for r in rows if r["method"] == method and int(r["obstacles"]) == c])
                 for c in counts]
        cobs = [mean_std([number(r["cobs_fraction"]) for r in rows if r["method"] == method and int(r["obstacles"]) == c])[0]
                for c in counts]
        by_count.errorbar(counts, [s[0] for s in stats], yerr=[s[1] for s in stats], marker=marker, capsize=3, label=method)
        order = np.argsort(cobs)
        by_cobs.plot(np.array(cobs)[order], np.array([s[0] for s in stats])[order], marker=marker, label=method)
    for ax in (by_count, by_cobs):
        ax.set_yscale("log")
        ax.set_ylabel("query time (µs)")
        ax.grid(alpha=0.3, which="both")
        ax.legend()
    by_count.set_xscale("log")
    by_count.set_xlabel("obstacles in the workspace")
    by_cobs.set_xlabel("share of C-space in collision")
    by_count.set_title("Query time against the number of obstacles")
    by_cobs.set_title("... and against the share of C-space in collision")
    fig.tight_layout()
    fig.savefig(out / "sweep.png", dpi=110)


PARTS = (("plan_s", "plan"), ("verify_s", "verify"), ("repair_s", "repair"))
METHOD_COLOURS = {"Fastron": "tab:blue", "GJK": "tab:orange", "FCL": "tab:green"}


def stacked_times(ax, rows, groups, group_key, title):
    """Stacked bars of mean plan / verify / repair time over solved queries, one group per value
    of group_key (a planner or a problem), one bar per method: the paper's Figs. 13 and 14."""
    methods = list(dict.fromkeys(r["method"] for r in rows))
    width = 0.8 / len(methods)
    x = np.arange(len(groups))
    hatches = {"plan_s": "", "verify_s": "//", "repair_s": ".."}
    for k, method in enumerate(methods):
        bottom = np.zeros(len(groups))
        for key, part in PARTS:
            heights = []
            for g in groups:
                values = [number(r[key]) * 1e3 for r in rows
                          if r[group_key] == g and r["method"] == method and r["solved"] == "1"]
                heights.append(mean_std(values)[0] if values else 0.0)
            heights = np.nan_to_num(np.array(heights))
            ax.bar(x + (k - (len(methods) - 1) / 2) * width, heights, width, bottom=bottom,
                   color=METHOD_COLOURS.get(method, "grey"), hatch=hatches[key], edgecolor="black",
                   linewidth=0.4, label=f"{method}: {part}" if heights.any() or key == "plan_s" else None)
            bottom += heights
    ax.set_xticks(x, groups)
    ax.set_ylabel("mean time per query (ms)")
    ax.set_title(title)
    ax.grid(axis="y", alpha=0.3)


def plot_plan(rows, out):
    """Figs. 13 and 14: planning time split into plan / verify / repair, per planner and case."""
    cases = list(dict.fromkeys(r["case"] for r in rows))
    planners = list(dict.fromkeys(r["planner"] for r in rows))
    fig, axes = plt.subplots(1, len(cases), figsize=(5.5 * len(cases), 4.6), squeeze=False)
    for ax, case in zip(axes[0], cases):
        stacked_times(ax, [r for r in rows if r["case"] == case], planners, "planner",
                      f"Baxter, {case}")
    axes[0][-1].legend(fontsize=7, loc="upper right")
    fig.suptitle("Time to a valid plan (solved queries): plan / verify / repair")
    fig.tight_layout()
    fig.savefig(out / "plan.png", dpi=110)


def plot_single_planner(rows, out, name, title, group_key):
    groups = list(dict.fromkeys(r[group_key] for r in rows))
    fig, ax = plt.subplots(figsize=(max(5.5, 0.9 * len(groups) + 3), 4.6))
    stacked_times(ax, rows, groups, group_key, title)
    ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(out / f"{name}.png", dpi=110)


def plot_surgical(rows, out):
    """Replanning rate of each method, and each tick's time to a valid plan."""
    methods = list(dict.fromkeys(r["method"] for r in rows))
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.6))
    rates = []
    for m in methods:
        times = [number(r["total_s"]) for r in rows if r["method"] == m and r["solved"] == "1"]
        rates.append(1.0 / mean_std(times)[0] if times else 0.0)
    left.bar(methods, rates, color=[METHOD_COLOURS.get(m, "grey") for m in methods])
    for i, rate in enumerate(rates):
        left.text(i, rate, f"{rate:.0f} Hz", ha="center", va="bottom")
    left.set_ylabel("replanning rate (Hz, 1 / mean time to a valid plan)")
    left.set_title("PSM3 replanning an RRT every tick")
    left.grid(axis="y", alpha=0.3)
    for m in methods:
        ticks = [int(r["tick"]) for r in rows if r["method"] == m and r["solved"] == "1"]
        times = [number(r["total_s"]) * 1e3 for r in rows if r["method"] == m and r["solved"] == "1"]
        right.plot(ticks, times, ".", color=METHOD_COLOURS.get(m, "grey"), label=m)
    right.set_yscale("log")
    right.set_xlabel("tick")
    right.set_ylabel("plan + verify + repair (ms)")
    right.set_title("time to a valid plan at each tick")
    right.grid(alpha=0.3)
    right.legend()
    fig.tight_layout()
    fig.savefig(out / "surgical.png", dpi=110)


def plot_sensed(rows, out):
    """The sensed scene with a plan on it, and per frame the model's update rate and accuracy."""
    fig = plt.figure(figsize=(13, 5.2))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    if (out / "scene.csv").exists():
        cloud = np.array([[number(r[k]) for k in "xyz"] for r in read(out / "scene.csv")])
        if len(cloud):
            ax.scatter(cloud[:, 0], cloud[:, 1], cloud[:, 2], s=0.3, c=cloud[:, 2], cmap="viridis", alpha=0.5)
            ax.set_box_aspect(np.ptp(cloud, axis=0))  # metres alike on every axis
    if (out / "path.csv").exists():
        path = read(out / "path.csv")
        for kind, colour, label in (("path", "red", "Fastron's path (the arm's tip)"),
                                    ("start", "black", "arm at the start"), ("goal", "blue", "arm at the goal")):
            p = np.array([[number(r[k]) for k in "xyz"] for r in path if r["kind"] == kind])
            if len(p):
                ax.plot(p[:, 0], p[:, 1], p[:, 2], color=colour, lw=2 if kind == "path" else 3,
                        marker=None if kind == "path" else "o", ms=3, label=label)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.view_init(elev=28, azim=-140)
    ax.set_title("What the camera saw (the last frame), and a plan verified on it")
    ax.legend(loc="upper left", fontsize=8)
    right = fig.add_subplot(1, 2, 2)
    frames = sorted({int(r["frame"]) for r in rows})
    def per_frame(key):
        return [np.nanmean([number(r[key]) for r in rows if int(r["frame"]) == f]) for f in frames]
    right.plot(frames, per_frame("updates_per_s"), color="tab:blue", label="model updates per second")
    right.axhline(30, color="tab:blue", ls=":", label="a 30 Hz camera")
    right.set_xlabel("frame")
    right.set_ylabel("updates per second (ingest + update)")
    twin = right.twinx()
    twin.plot(frames, per_frame("accuracy_cloud"), color="tab:green", label="accuracy (FCL on the cloud)")
    twin.plot(frames, per_frame("tpr_cloud"), color="tab:orange", label="TPR (FCL on the cloud)")
    twin.set_ylim(0.8, 1.0)
    twin.set_ylabel("rate on fresh configurations")
    lines = right.get_legend_handles_labels()
    more = twin.get_legend_handles_labels()
    right.legend(lines[0] + more[0], lines[1] + more[1], loc="lower right", fontsize=8)
    right.set_title("Keeping up with the camera (mean over trials)")
    fig.tight_layout()
    fig.savefig(out / "sensed.png", dpi=110)


def plot_optimize(rows, out):
    """The model's score along each path before (the straight line) and after optimising, and the
    times and lengths of the optimiser against RRT-Connect."""
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 4.8))
    scores = read(out / "scores.csv") if (out / "scores.csv").exists() else []
    trials = sorted({int(r["trial"]) for r in scores})[:4]
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, trial in enumerate(trials):
        for which, style in (("before", ":"), ("after", "-")):
            path = [r for r in scores if int(r["trial"]) == trial and r["path"] == which]
            left.plot([number(r["s"]) for r in path], [number(r["score"]) for r in path],
                      ls=style, color=colours[k % len(colours)],
                      label=f"query {trial}, {'straight line' if which == 'before' else 'optimised'}")
    left.axhline(0, color="black", lw=0.8)
    left.set_xlabel("share of the path's length")
    left.set_ylabel("model score f (> 0: collision)")
    left.set_title("The score along the path, before and after optimising\n(on the model after the query)")
    left.legend(fontsize=7, ncol=2)
    methods = list(dict.fromkeys(r["method"] for r in rows))
    solved = [[r for r in rows if r["method"] == m and r["solved"] == "1"] for m in methods]
    times = [[number(r["time_ms"]) for r in group] for group in solved]
    right.boxplot(times, labels=[f"{m}\n{len(g)} solved" for m, g in zip(methods, solved)])
    right.set_yscale("log")
    right.set_ylabel("time to an FCL-valid path (ms)")
    twin = right.twinx()
    twin.plot(range(1, len(methods) + 1), [np.median([number(r["length"]) for r in g]) if g else np.nan
                                          for g in solved], "o", color="tab:red")
    twin.set_ylabel("median path length (rad)", color="tab:red")
    right.set_title("Baxter, three boxes: optimiser against RRT-Connect")
    fig.tight_layout()
    fig.savefig(out / "optimize.png", dpi=110)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    name, out = sys.argv[1], Path(sys.argv[2])
    # A batch run's problems it could not run are rows of their own, with no plan to draw.
    rows = [r for r in read(out / "results.csv") if not r.get("status", "").startswith("skipped: ")]
    if name == "static":
        plot_static(rows, out)
    elif name in ("static-beta", "static-gamma"):
        plot_sweep(rows, out, name.split("-")[1])
    elif name == "cspace":
        plot_cspace(out)
    elif name == "changing":
        plot_changing(rows, out)
    elif name == "sweep":
        plot_sweep_obstacles(rows, out)
    elif name == "plan":
        plot_plan(rows, out)
    elif name == "shelf":
        plot_single_planner(rows, out, "shelf", "UR3 shelf, RRT: time to a valid plan", "planner")
    elif name == "surgical":
        plot_surgical(rows, out)
    elif name == "sensed":
        plot_sensed(rows, out)
    elif name == "optimize":
        plot_optimize(rows, out)
    elif name == "motion-bench":
        plot_single_planner(rows, out, "motion-bench", "MoveIt problems, RRT-Connect: time to a valid plan", "problem")
    else:
        sys.exit(f"no plot for '{name}'")


if __name__ == "__main__":
    main()
