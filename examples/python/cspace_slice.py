#!/usr/bin/python3
"""Learn Baxter's C-space among three boxes, query it in batch, compare with FCL, and plot a 2-D
slice of the C-space (two joints varied, the others held) as FCL and as the model see it.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/cspace_slice.py -o slice.png
"""
import argparse
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import fastron  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="cspace_slice.png", help="PNG to write")
    parser.add_argument("--samples", type=int, default=8000, help="FCL-labelled training samples")
    args = parser.parse_args()

    robot = fastron.load_robot("baxter")
    scene = fastron.load_scene(fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml")
    fcl = fastron.FclChecker(robot, scene)

    # Train on task-space features (control points on the arm), labels from FCL on every core.
    detector = fastron.ProxyCollisionDetector(fcl, fastron.robot_features(robot), seed=1)
    report = detector.initialize(args.samples)
    model = detector.model()

    # Batch queries against the exact checker on fresh configurations.
    limits = robot.limits
    q = np.random.default_rng(7).uniform(limits.lower, limits.upper, size=(20000, robot.dof))
    t0 = time.perf_counter()
    exact = fcl.in_collision(q)
    t1 = time.perf_counter()
    predicted = model.in_collision(q)
    t2 = time.perf_counter()
    counts = fastron.evaluate(model, q, exact)
    print(f"model: |S| = {model.support_count}, trained on {report.labelled} FCL labels")
    print(f"accuracy {counts.accuracy:.3f}, TPR {counts.tpr:.3f}, TNR {counts.tnr:.3f} "
          f"on {counts.total} fresh configurations")
    print(f"FCL {1e6 * (t1 - t0) / len(q):.2f} us per configuration, "
          f"Fastron {1e6 * (t2 - t1) / len(q):.3f} us ({(t1 - t0) / (t2 - t1):.1f}x)")
    assert np.array_equal(predicted, model.score(q) > 0)

    # A slice through the C-space: joints 0 and 1 over their range, the others at a collision.
    held = q[np.argmax(exact)]
    n = 120
    a = np.linspace(limits.lower[0], limits.upper[0], n)
    b = np.linspace(limits.lower[1], limits.upper[1], n)
    grid = np.repeat(held[None, :], n * n, axis=0)
    grid[:, 0] = np.repeat(a, n)
    grid[:, 1] = np.tile(b, n)
    truth = fcl.in_collision(grid).reshape(n, n)
    score = model.score(grid).reshape(n, n)

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.5), sharey=True)
    extent = (b[0], b[-1], a[0], a[-1])
    axes[0].imshow(truth, origin="lower", extent=extent, aspect="auto", cmap="Greys")
    axes[0].set_title("FCL: in collision (black)")
    axes[1].imshow(score > 0, origin="lower", extent=extent, aspect="auto", cmap="Greys")
    axes[1].contour(b, a, truth.astype(float), levels=[0.5], colors="tab:red", linewidths=1)
    axes[1].set_title(f"Fastron (|S| = {model.support_count}); red: FCL's boundary")
    for ax in axes:
        ax.set_xlabel(f"{robot.joint_names[1]} (rad)")
    axes[0].set_ylabel(f"{robot.joint_names[0]} (rad)")
    fig.suptitle(f"Baxter among three boxes, slice through joints 0 and 1; "
                 f"accuracy {np.mean((score > 0) == truth):.3f} on the slice")
    fig.tight_layout()
    fig.savefig(args.output, dpi=100)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
