"""The model's collision cost, trajectory optimisation and gradient repair from Python."""
import numpy as np
import pytest

import fastron


def disc_model():
    """A model of a disc of radius 0.35 at the origin of [-1, 1]^2."""
    x = np.random.default_rng(4).uniform(-1, 1, size=(2500, 2))
    y = np.where(np.hypot(x[:, 0], x[:, 1]) < 0.35, 1, -1)
    model, _ = fastron.train(x, y, gamma=30, beta=10, limits=fastron.JointLimits([-1, -1], [1, 1]))
    return model


def misses_the_disc(path, step=0.002):
    for a, b in zip(path[:-1], path[1:]):
        n = max(1, int(np.ceil(np.linalg.norm(b - a) / step)))
        s = np.linspace(0, 1, n + 1)[:, None]
        if np.any(np.hypot(*((1 - s) * a + s * b).T) < 0.35):
            return False
    return True


def test_the_path_cost_and_its_gradient():
    model = disc_model()
    path = np.array([[-0.8, 0.05], [-0.2, 0.1], [0.3, 0.0], [0.8, 0.0]])
    cost, gradient, scores = fastron.path_collision_cost(model, path, margin=0.5)
    assert cost > 0 and gradient.shape == (4, 2) and scores.shape == (4,)
    assert np.allclose(scores, model.score(path), rtol=1e-5, atol=1e-5)
    h = 1e-3
    numeric = np.zeros_like(path)
    for i in range(4):
        for j in range(2):
            e = np.zeros_like(path)
            e[i, j] = h
            numeric[i, j] = (fastron.path_collision_cost(model, path + e, margin=0.5)[0] -
                             fastron.path_collision_cost(model, path - e, margin=0.5)[0]) / (2 * h)
    assert np.allclose(gradient, numeric, rtol=1e-2, atol=1e-2 * max(1.0, np.abs(numeric).max()))
    with pytest.raises(fastron.InvalidArgument, match="path"):
        fastron.path_collision_cost(model, np.zeros((3, 3)))
    with pytest.raises(fastron.InvalidArgument, match="margin"):
        fastron.path_collision_cost(model, path, margin=-1)


def test_the_optimiser_leaves_the_disc():
    model = disc_model()
    line = fastron.straight_path([-0.8, 0.02], [0.8, 0.0])
    assert line.shape[1] == 2 and len(line) >= 8 and not misses_the_disc(line)
    out = fastron.optimize_trajectory(model, line)
    assert out.free_on_model and out.iterations == len(out.costs) - 1
    assert np.array_equal(out.path[0], line[0]) and np.array_equal(out.path[-1], line[-1])
    assert misses_the_disc(out.path)
    with pytest.raises(fastron.InvalidArgument, match="max_step|maxStep"):
        fastron.optimize_trajectory(model, line, max_step=0)
    with pytest.raises(fastron.InvalidArgument, match="timeLimit"):
        fastron.optimize_trajectory(model, line, time_limit=-1)
    with pytest.raises(fastron.InvalidArgument, match="three waypoints"):
        fastron.optimize_trajectory(model, line[[0, -1]])


def test_verified_optimisation_on_baxter(baxter, baxter_fcl):
    detector = fastron.ProxyCollisionDetector(baxter_fcl, fastron.robot_features(baxter),
                                              calibration_samples=0)
    detector.initialize(3000)
    rng = np.random.default_rng(11)
    solved = 0
    for _ in range(3):
        while True:  # free ends whose straight line collides
            ends = rng.uniform(baxter.limits.lower, baxter.limits.upper, size=(2, 7))
            if not baxter_fcl.in_collision(ends).any() and \
                    not fastron.check_path(baxter_fcl, ends, 0.02):
                break
        out = fastron.optimize_verified(detector, baxter_fcl, ends[0], ends[1], resolution=0.02)
        if out.solved:
            solved += 1
            assert fastron.check_path(baxter_fcl, out.path, 0.01)  # never on the model's word
            assert out.costs[0] > 0 and out.rounds >= 1
    assert solved >= 2
    with pytest.raises(fastron.InvalidArgument, match="start"):
        fastron.optimize_verified(detector, baxter_fcl, np.zeros(3), np.zeros(7))


def test_gradient_repair_needs_a_static_scene(baxter, baxter_fcl):
    detector = fastron.ProxyCollisionDetector(baxter_fcl, fastron.robot_features(baxter))
    detector.initialize(500)
    with pytest.raises(fastron.InvalidArgument, match="gradient_repair"):
        fastron.plan_verified(detector, baxter_fcl, np.zeros(7), np.zeros(7), gradient_repair=True)
