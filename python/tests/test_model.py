"""Models, training and datasets from Python agree with the C++ library and its command."""
import subprocess

import numpy as np
import pytest

import fastron
from conftest import uniform


def disc_data(n=1500, seed=2):
    x = np.random.default_rng(seed).uniform(-2, 2, size=(n, 2))
    return x, np.where(np.hypot(x[:, 0] - 0.3, x[:, 1]) < 0.8, 1, -1)


def test_train_learns_a_disc():
    x, y = disc_data()
    model, report = fastron.train(x, y, gamma=30, beta=5)
    assert report.stop_reason == "converged"
    assert model.support_count == report.support_count > 0
    xt, yt = disc_data(2000, seed=9)
    counts = fastron.evaluate(model, xt, yt)
    assert counts.total == 2000 and counts.accuracy > 0.95 and counts.tpr > 0.9
    # Claim 1 of the paper: every training point is classified correctly after convergence.
    assert np.all(np.sign(model.score(x)) == y)


def test_training_on_two_cores_gives_the_model_of_one():
    x, y = disc_data(6000, seed=4)  # more rows than Trainer::rowsToShareUpdate() (4096 on AVX-512)
    one, report_one = fastron.train(x, y, gamma=30, beta=5, threads=1)
    two, report_two = fastron.train(x, y, gamma=30, beta=5)  # threads=0: every core
    assert report_one.shared_iterations == 0
    assert report_two.iterations == report_one.iterations
    assert np.array_equal(two.weights, one.weights)
    assert np.array_equal(two.score(x), one.score(x))


def test_batch_and_single_queries_agree():
    x, y = disc_data()
    model, _ = fastron.train(x, y, gamma=30, beta=5)
    batch = model.score(x[:50])
    single = np.array([model.score(q) for q in x[:50]])
    assert batch.shape == (50,) and np.array_equal(batch, single)
    assert np.array_equal(model.in_collision(x[:50]), batch > 0)
    assert isinstance(model.in_collision(x[0]), bool)
    hits = np.flatnonzero(batch > 0)
    assert model.first_in_collision(x[:50]) == (hits[0] if hits.size else None)


def test_score_gradients_point_out_of_collision(baxter, baxter_fcl):
    x, y = disc_data()
    model, _ = fastron.train(x, y, gamma=30, beta=5)
    score, gradient = model.score_gradient(x[0])
    assert isinstance(score, float) and gradient.shape == (2,)
    scores, gradients = model.score_gradient(x[:20])
    assert scores.shape == (20,) and gradients.shape == (20, 2)
    assert np.allclose(gradients[0], gradient) and np.isclose(scores[0], score)
    # The scores are summed in float: differences over a step of 1e-3 (the C++ tests compare the
    # double sum's gradient with differences at 1e-4).
    h = 1e-3
    for q, g in zip(x[:20], gradients):
        numeric = [(model.score_gradient(q + h * e)[0] - model.score_gradient(q - h * e)[0]) / (2 * h)
                   for e in np.eye(2)]
        assert np.allclose(g, numeric, rtol=1e-2, atol=1e-2 * max(1e-2, np.abs(numeric).max()))
    # On a task-space model, a step along minus the gradient lowers the score.
    detector = fastron.ProxyCollisionDetector(baxter_fcl, fastron.robot_features(baxter),
                                              calibration_samples=0)
    detector.initialize(1500)
    task = detector.model()
    q = uniform(baxter.limits, 200, seed=3)
    f, g = task.score_gradient(q)
    stepped, _ = task.score_gradient(q - 1e-4 * g)
    assert np.all(stepped <= f + 1e-12)
    with pytest.raises(fastron.InvalidArgument, match="q"):
        model.score_gradient(np.zeros(3))


def test_pruned_and_merged_models_keep_their_answers():
    x, y = disc_data()
    model, _ = fastron.train(x, y, gamma=30, beta=5)
    held_out, _ = disc_data(3000, seed=11)
    pruned = fastron.prune_support(model, held_out)
    assert pruned.support_count <= model.support_count
    assert np.array_equal(pruned.in_collision(held_out), model.in_collision(held_out))
    assert fastron.merge_support(model, 0.0).support_count == model.support_count
    merged = fastron.merge_support(model, 0.5)
    assert merged.support_count < model.support_count
    assert np.isclose(merged.weights.sum(), model.weights.sum())
    with pytest.raises(fastron.InvalidArgument, match="merge radius"):
        fastron.merge_support(model, -1.0)
    with pytest.raises(fastron.InvalidArgument):
        fastron.prune_support(model, held_out[:, :1])


def test_every_simd_path_gives_the_same_answers():
    x, y = disc_data()
    model, _ = fastron.train(x, y, gamma=30, beta=5)
    paths = fastron.simd_paths()
    assert paths[0] == "portable" and fastron.active_simd_path() in paths
    saved = fastron.active_simd_path()
    try:
        scores = {}
        for path in paths:
            fastron.use_simd_path(path)
            assert fastron.active_simd_path() == path
            scores[path] = model.score(x[:200])
        # Float sums with and without fused multiply-adds: apart by float rounding of each term.
        tolerance = 1e-6 * np.abs(model.weights).sum()
        for path in paths:
            assert np.abs(scores[path] - scores["portable"]).max() <= tolerance, path
    finally:
        fastron.use_simd_path(saved)
    with pytest.raises(fastron.InvalidArgument, match="unknown SIMD path 'sse9'"):
        fastron.use_simd_path("sse9")


def test_arrays_are_read_only_views_of_the_model():
    x, y = disc_data()
    model, _ = fastron.train(x, y, gamma=30, beta=5)
    w = model.weights
    assert w.shape == (model.support_count,) and not w.flags.writeable
    assert model.support_points.shape == (model.support_count, 2)
    assert model.support_features.shape == (model.support_count, 2)
    assert np.shares_memory(w, model.weights)  # the model's own memory, not a copy
    with pytest.raises(ValueError):
        w[0] = 1


def test_same_data_same_model_as_the_command(tmp_path, fastron_command):
    """Python's train and `fastron train --data` give the same support set and weights."""
    x, y = disc_data()
    data = tmp_path / "disc.csv"
    fastron.write_dataset(data, x, y)
    model_file = tmp_path / "disc.fastron"
    subprocess.run([fastron_command, "train", "--data", data, "-o", model_file, "--gamma", "30",
                    "--beta", "5"], check=True, capture_output=True)
    from_command = fastron.load_model(model_file)
    x_read, y_read = fastron.read_dataset(data)
    from_python, _ = fastron.train(x_read, y_read, gamma=30, beta=5)
    assert np.array_equal(from_command.support_points, from_python.support_points)
    assert np.array_equal(from_command.weights, from_python.weights)


def test_task_space_model_equals_the_command(tmp_path, fastron_command, baxter, baxter_fcl):
    x = uniform(baxter.limits, 3000, seed=5)
    y = baxter_fcl.in_collision(x)
    data = tmp_path / "baxter.npy"
    fastron.write_dataset(data, x, y)
    model_file = tmp_path / "baxter.fastron"
    subprocess.run([fastron_command, "train", "--data", data, "--robot", "baxter", "-o",
                    model_file, "--max-support", "3000"], check=True, capture_output=True)
    from_command = fastron.load_model(model_file, baxter)
    from_python, _ = fastron.train(x, y, features=fastron.robot_features(baxter))
    assert from_python.features.kind == "fk"
    assert np.array_equal(from_command.weights, from_python.weights)
    q = uniform(baxter.limits, 100, seed=6)
    assert np.array_equal(from_command.score(q), from_python.score(q))


def test_a_point_field_answers_as_the_full_sum(baxter, baxter_fcl):
    x = uniform(baxter.limits, 3000, seed=11)
    model, _ = fastron.train(x, baxter_fcl.in_collision(x), features=fastron.robot_features(baxter),
                             kernel_whole_share=0)
    assert model.has_only_point_terms and model.point_field is None
    tabulated = model.with_point_field(spacing=0.05)
    field = tabulated.point_field
    assert field["grids"] == model.feature_dim // 3 and field["spacing"] == 0.05
    # A node's value (4 bytes) and, per cell, its bound and curvature correction (8 bytes).
    assert field["nodes"] > 0 and 4 * field["nodes"] < field["memory_bytes"] < 16 * field["nodes"]
    q = uniform(baxter.limits, 2000, seed=12)
    assert np.array_equal(tabulated.in_collision(q), model.score(q) > 0)
    assert np.array_equal(tabulated.score(q), model.score(q))
    assert tabulated.first_in_collision(q) == model.first_in_collision(q)
    refined = model.with_point_field(spacing=0.05, refinement=4, fine_from=0)
    assert refined.point_field["fine_blocks"] > 0
    assert refined.point_field["memory_bytes"] > field["memory_bytes"]
    assert np.array_equal(refined.in_collision(q), model.score(q) > 0)
    assert field["answers"] == "exact"
    # The estimate alone: the full sum's answers but on the model's boundary, no fine blocks.
    estimated = model.with_point_field(spacing=0.05, answers="estimate", fine_from=0)
    assert estimated.point_field["answers"] == "estimate"
    assert estimated.point_field["fine_blocks"] == 0
    assert np.count_nonzero(estimated.in_collision(q) != (model.score(q) > 0)) < len(q) // 100
    with pytest.raises(fastron.InvalidArgument, match="'roughly'"):
        model.with_point_field(answers="roughly")
    with pytest.raises(fastron.InvalidArgument, match="spacing"):
        model.with_point_field(spacing=0)
    with pytest.raises(fastron.InvalidArgument, match="refinement"):
        model.with_point_field(refinement=0)
    default, _ = fastron.train(x[:500], baxter_fcl.in_collision(x[:500]),
                               features=fastron.robot_features(baxter))
    assert not default.has_only_point_terms
    with pytest.raises(fastron.InvalidArgument, match="whole vector's, share 0.5"):
        default.with_point_field()


def test_save_and_load(tmp_path, baxter, baxter_fcl):
    x = uniform(baxter.limits, 1000, seed=7)
    model, _ = fastron.train(x, baxter_fcl.in_collision(x), features=fastron.robot_features(baxter))
    path = tmp_path / "m.fastron"
    model.save(path)
    with pytest.raises(fastron.FileError, match="robot"):
        fastron.load_model(path)  # a task-space model needs its robot
    loaded = fastron.load_model(path, baxter)
    assert np.array_equal(loaded.score(x[:20]), model.score(x[:20]))


def test_dataset_round_trip(tmp_path):
    x, y = disc_data(50)
    for name in ("d.csv", "d.npy"):
        fastron.write_dataset(tmp_path / name, x, y)
        x2, y2 = fastron.read_dataset(tmp_path / name)
        assert np.allclose(x2, x) and np.array_equal(y2, y) and y2.dtype == np.int8
