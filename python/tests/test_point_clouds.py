"""Sensed obstacles from Python: clouds from numpy arrays, replaced frame by frame."""
import numpy as np
import pytest

import fastron
from conftest import uniform


def box_surface(centre, half, spacing):
    axes = [np.arange(-h, h + 1e-9, spacing) for h in half]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    on_surface = (np.asarray(half) - np.abs(grid)).min(axis=1) < spacing / 2
    return grid[on_surface] + np.asarray(centre)


def test_a_cloud_answers_as_the_box_it_samples(baxter):
    centre, half = [0.7, -0.5, 0.1], [0.15, 0.2, 0.12]
    box = fastron.Scene()
    box.add_box("box", [2 * h for h in half], centre)
    cloud = fastron.Scene()
    cloud.add_point_cloud("camera", box_surface(centre, half, 0.01), 0.01, voxel=0)
    x = uniform(baxter.limits, 400, seed=2)
    on_box = fastron.FclChecker(baxter, box).in_collision(x)
    on_cloud = fastron.FclChecker(baxter, cloud).in_collision(x)
    on_grown = fastron.FclChecker(baxter, box.grown(0.0101)).in_collision(x)
    # The cloud is the box's surface with a centimetre's balls: it touches what the box touches
    # (the arm cannot reach inside the box without crossing its surface), and nothing that the
    # box grown by the balls' radius does not touch.
    assert on_box.sum() > 10
    assert np.all(on_cloud[on_box])
    assert not np.any(on_cloud & ~on_grown)


def test_clouds_are_down_sampled_replaced_and_checked(baxter):
    scene = fastron.Scene()
    points = box_surface([0.7, -0.5, 0.1], [0.15, 0.2, 0.12], 0.005).astype(np.float32)
    scene.add_point_cloud("camera", points, 0.02)  # float32: converted; voxel = radius
    checker = fastron.FclChecker(baxter, scene)
    x = uniform(baxter.limits, 300, seed=3)
    before = checker.in_collision(x)
    assert 0 < before.sum() < len(x)
    scene.set_point_cloud("camera", np.zeros((0, 3)), 0.02)  # an empty frame: nothing to touch
    checker.set_scene(scene)
    assert not checker.in_collision(x).any()
    with pytest.raises(fastron.InvalidArgument, match=r"points.*3"):
        scene.add_point_cloud("bad", np.zeros((4, 2)), 0.01)
    with pytest.raises(fastron.InvalidArgument, match=r"points\[1, 2\]"):
        scene.add_point_cloud("bad", np.array([[0, 0, 0], [1, 1, np.nan]]), 0.01)
    with pytest.raises(fastron.InvalidArgument, match="radius"):
        scene.add_point_cloud("bad", np.zeros((1, 3)), -1.0)
    with pytest.raises(fastron.Unsupported, match="point cloud"):
        fastron.GjkChecker(baxter, scene)
