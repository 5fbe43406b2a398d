#!/usr/bin/env python3
"""How the automatic control-point rule shapes the default method's scene models.

For the first problems of a MotionBenchMaker-format family, trains each scene's model as the
default method does (fastron.train_scene_model: 2000 FCL-labelled samples, one active-learning
update) on the control points of each rule, and measures accuracy and TPR against FCL without
self-collision (the model's own labels) on fresh uniform configurations. Prints one line per
rule and kernel width: mean accuracy and TPR over the scenes, median |S| and training time.

    PYTHONPATH=build/release/python python3 scripts/scene_control_points.py mobile-arm DIR

docs/log/2026-11-29-control-points-of-scene-models.md has what it measured.
"""

import argparse
import pathlib
import time

import numpy as np

import fastron

CANDIDATES = {
    "spread4": {},
    "cover4": {"rule": "cover"},
    "spread6": {"max_points": 6},
}


def measure(robot_name, family, problems, samples, gammas, seed=3):
    base = fastron.load_robot(robot_name)
    rng = np.random.default_rng(seed)
    results = {}
    for i in range(1, problems + 1):
        scene_file = family / f"scene{i:04d}.yaml"
        scene = fastron.load_scene(scene_file)
        robot, _, _, _ = fastron.robot_for_request(base, family / f"request{i:04d}.yaml", scene)
        fcl = fastron.FclChecker(robot, scene)
        lower, upper = robot.limits.lower, robot.limits.upper
        x = lower + (upper - lower) * rng.random((samples, len(lower)))
        colliding = fcl.in_collision(x)
        for name, options in CANDIDATES.items():
            features = fastron.robot_features(robot, "fk", **options)
            for gamma in gammas:
                began = time.perf_counter()
                model = fastron.train_scene_model(robot, scene, features, gamma=gamma).model()
                seconds = time.perf_counter() - began
                said = model.in_collision(x)
                tpr = float(np.mean(said[colliding])) if colliding.any() else 1.0
                results.setdefault((name, gamma), []).append(
                    (float(np.mean(said == colliding)), tpr, model.support_count, seconds))
    return results


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("robot", help="a shipped robot or a URDF file")
    parser.add_argument("family", type=pathlib.Path, help="folder of sceneNNNN/requestNNNN.yaml")
    parser.add_argument("--problems", type=int, default=4, help="the first this many problems")
    parser.add_argument("--samples", type=int, default=20000, help="test configurations per scene")
    parser.add_argument("--gamma", type=float, action="append",
                        help="kernel widths to try (repeatable; default: the features' own)")
    args = parser.parse_args()
    gammas = args.gamma or [None]
    for (name, gamma), rows in measure(args.robot, args.family, args.problems, args.samples,
                                       gammas).items():
        rows = np.array(rows)
        width = "default" if gamma is None else f"{gamma:g}"
        print(f"{name:8s} gamma {width:8s} accuracy {rows[:, 0].mean():.3f} "
              f"TPR {rows[:, 1].mean():.3f} |S| {np.median(rows[:, 2]):.0f} "
              f"train {np.median(rows[:, 3]) * 1000:.1f} ms")


if __name__ == "__main__":
    main()
