#!/usr/bin/python3
"""Trajectory optimisation on a Fastron model: Baxter's arm among three boxes, from straight lines
that collide to paths that FCL verifies free, against RRT-Connect on FCL; a plot of the model's
score along one path before and after.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/trajectory_optimization.py -o opt.png
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import fastron  # noqa: E402


def colliding_queries(robot, fcl, count, seed, resolution):
    """Free starts and goals whose straight line collides under FCL."""
    rng = np.random.default_rng(seed)
    queries = []
    while len(queries) < count:
        ends = rng.uniform(robot.limits.lower, robot.limits.upper, size=(2, robot.dof))
        if not fcl.in_collision(ends).any() and not fastron.check_path(fcl, ends, resolution):
            queries.append(ends)
    return queries


def scores_along(model, path, resolution):
    states = fastron.states_along_path(path, resolution)
    travelled = np.r_[0, np.cumsum(np.linalg.norm(np.diff(states, axis=0), axis=1))]
    return travelled / travelled[-1], model.score(states)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="trajectory_optimization.png", help="PNG to write")
    parser.add_argument("--queries", type=int, default=10)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    resolution = 0.02

    robot = fastron.load_robot("baxter")
    scene = fastron.load_scene(fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml")
    fcl = fastron.FclChecker(robot, scene)
    detector = fastron.ProxyCollisionDetector(fcl, fastron.robot_features(robot), seed=args.seed)
    detector.initialize(3000)
    model = detector.model()
    print(f"model: |S| = {model.support_count}")

    solved, first = 0, None
    for k, (start, goal) in enumerate(colliding_queries(robot, fcl, args.queries, args.seed,
                                                        resolution)):
        before = detector.model()
        out = fastron.optimize_verified(detector, fcl, start, goal, resolution=resolution)
        rrt = fastron.plan(fcl, start, goal, resolution=resolution)
        seconds = out.optimize_seconds + out.verify_seconds + out.learn_seconds
        length = np.linalg.norm(np.diff(out.path, axis=0), axis=1).sum()
        rrt_length = np.linalg.norm(np.diff(rrt.path, axis=0), axis=1).sum() if rrt.solved else np.nan
        print(f"query {k}: {'free under FCL' if out.solved else out.failure}; {out.iterations} "
              f"iterations, {out.rounds} round(s), {1e3 * seconds:.1f} ms, length {length:.2f} rad; "
              f"RRT-Connect on FCL {1e3 * rrt.seconds:.1f} ms, length {rrt_length:.2f} rad")
        if out.solved:
            solved += 1
            assert fastron.check_path(fcl, out.path, resolution)  # never on the model's word
            if first is None:
                first = (k, before, np.array([start, goal]), detector.model(), out.path)
    print(f"{solved} of {args.queries} straight lines optimised to FCL-free paths")

    if first is not None:
        k, before, line, after, path = first
        fig, ax = plt.subplots(figsize=(8, 4))
        ax.plot(*scores_along(before, line, resolution), ":", label="straight line")
        ax.plot(*scores_along(after, path, resolution), "-", label="optimised (FCL-free)")
        ax.axhline(0, color="black", lw=0.8)
        ax.set_xlabel("share of the path's length")
        ax.set_ylabel("model score f (> 0: collision)")
        ax.set_title(f"Baxter, three boxes, query {k}: the score along the path")
        ax.legend()
        fig.tight_layout()
        fig.savefig(args.output, dpi=100)
        print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
