"""Every wrong argument raises a fastron.Error that names it; never a crash or garbage."""
import numpy as np
import pytest

import fastron


@pytest.fixture(scope="module")
def model():
    x = np.random.default_rng(1).uniform(-1, 1, size=(300, 3))
    return fastron.train(x, np.where(x[:, 0] > 0, 1, -1), gamma=10)[0]


@pytest.mark.parametrize("q, message", [
    (np.zeros(2), r"q: expected shape \(3,\) or \(n, 3\), got shape \(2,\)"),
    (np.zeros((4, 2)), r"got shape \(4, 2\)"),
    (np.zeros((2, 2, 3)), r"got shape \(2, 2, 3\)"),
    (np.float64(1.0), r"got shape \(\)"),
    (np.zeros((0, 0)), r"got shape \(0, 0\)"),
    (np.array([0, np.nan, 0]), r"q\[1\] is nan"),
    (np.array([[0, 0, 0], [0, 0, np.inf]]), r"q\[1, 2\] is inf"),
    (np.array(["a", "b", "c"]), r"dtype <U1"),
    (np.array([1 + 2j, 0, 0]), r"dtype complex128"),
    (np.array([None, 1, 2], dtype=object), r"dtype object"),
    ("abc", r"dtype <U3"),
])
def test_bad_configurations(model, q, message):
    for query in (model.score, model.in_collision):
        with pytest.raises(fastron.InvalidArgument, match=message):
            query(q)


def test_other_dtypes_and_layouts_are_converted(model):
    q = np.asfortranarray(np.random.default_rng(2).uniform(-1, 1, size=(5, 3)))
    expected = model.score(np.ascontiguousarray(q))
    assert np.array_equal(model.score(q), expected)
    assert np.array_equal(model.score(q.astype(np.float32)), model.score(q.astype(np.float32).astype(float)))
    assert model.score(np.zeros(3, dtype=np.int32)) == model.score(np.zeros(3))
    assert np.array_equal(model.score(q.tolist()), expected)
    assert np.array_equal(model.score(np.repeat(q, 2, axis=1)[:, ::2]), expected)  # strided view


def test_exceptions_derive_from_builtins(tmp_path):
    assert issubclass(fastron.InvalidArgument, ValueError)
    assert issubclass(fastron.FileError, OSError)
    assert issubclass(fastron.FileNotFound, FileNotFoundError)
    assert issubclass(fastron.FileNotFound, fastron.Error)
    with pytest.raises(FileNotFoundError, match="missing.csv: cannot open"):
        fastron.read_dataset(tmp_path / "missing.csv")
    bad = tmp_path / "bad.csv"
    bad.write_text("0.1,0.2,1\n0.3,oops,-1\n")
    with pytest.raises(fastron.FileError, match=r"bad.csv:2"):
        fastron.read_dataset(bad)
    with pytest.raises(fastron.FileError, match="bad.csv: not a Fastron model file"):
        fastron.load_model(bad)
    with pytest.raises(fastron.FileNotFound):
        fastron.load_robot("no_such_robot.urdf")
    with pytest.raises(fastron.FileError, match="baxter"):
        fastron.load_robot("no_such_robot")  # names the shipped robots


def test_bad_labels_and_training_arguments():
    x = np.zeros((3, 2))
    with pytest.raises(fastron.InvalidArgument, match=r"y\[1\] is 0"):
        fastron.train(x + [[0, 0], [1, 1], [2, 2]], [1, 0, -1])
    with pytest.raises(fastron.InvalidArgument, match=r"y: expected shape \(3,\)"):
        fastron.train(x, [1, -1])
    with pytest.raises(fastron.InvalidArgument, match=r"X: expected shape \(n, d\), got shape \(2,\)"):
        fastron.train(np.zeros(2), [1])
    with pytest.raises(fastron.InvalidArgument, match="no configurations"):
        fastron.train(np.zeros((0, 2)), [])
    with pytest.raises(fastron.InvalidArgument, match="data's range"):
        fastron.train(x, [1, -1, 1])  # constant columns give no joint limits
    with pytest.raises(fastron.InvalidArgument, match="gamma"):
        fastron.train(np.eye(3), [1, -1, 1], gamma=-1)
    with pytest.raises(fastron.InvalidArgument, match="beta"):
        fastron.train(np.eye(3), [1, -1, 1], beta=0.5)
    with pytest.raises(fastron.InvalidArgument, match="bogus"):
        fastron.train(np.eye(3), [1, -1, 1], kernel="bogus")
    with pytest.raises(TypeError):
        fastron.train(np.eye(3), [1, -1, 1], 5.0)  # settings are keyword-only


def test_bad_robot_and_planning_arguments(baxter, baxter_fcl):
    with pytest.raises(fastron.InvalidArgument, match=r"q: expected one configuration of shape \(7,\)"):
        baxter_fcl.first_contact(np.zeros((2, 7)))
    with pytest.raises(fastron.InvalidArgument, match="start"):
        fastron.plan(baxter_fcl, np.zeros(6), np.zeros(7))
    with pytest.raises(fastron.InvalidArgument, match="planner"):
        fastron.plan(baxter_fcl, np.zeros(7), np.zeros(7), planner="nope")
    with pytest.raises(fastron.InvalidArgument, match="source"):
        fastron.plan("fcl", np.zeros(7), np.zeros(7), limits=baxter.limits)
    with pytest.raises(fastron.InvalidArgument, match=r"'smooth' \(choose full or shortcuts\)"):
        fastron.plan(baxter_fcl, np.zeros(7), np.zeros(7), simplification="smooth")
    # Settings the chosen plan would not read are refused, naming them.
    for setting in ({"model_share": 0.1}, {"hybrid_range": 0.5}, {"oracle_relaxes_exact": True}):
        name = next(iter(setting))
        with pytest.raises(fastron.InvalidArgument, match=name + ": only a ProxyCollisionDetector"):
            fastron.plan_verified(baxter_fcl, baxter_fcl, np.zeros(7), np.zeros(7), **setting)
    with pytest.raises(fastron.InvalidArgument, match="static_scene: only a ProxyCollisionDetector"):
        fastron.plan_verified(baxter_fcl, baxter_fcl, np.zeros(7), np.zeros(7), static_scene=True)
    for setting, message in (({"stretch_share": 0}, "stretchShare must be in"),
                             ({"bridge_margin": -1}, "bridgeMargin must be finite and >= 0"),
                             ({"approximate_share": 1.5}, "approximateShare must be in"),
                             ({"substitute_share": -1}, "substituteShare must be in")):
        with pytest.raises(fastron.InvalidArgument, match=message):
            fastron.plan_verified(baxter_fcl, baxter_fcl, np.zeros(7), np.zeros(7), **setting)
    with pytest.raises(fastron.InvalidArgument, match="oracle"):
        fastron.ProxyCollisionDetector(42, fastron.robot_features(baxter))
    with pytest.raises(fastron.InvalidArgument, match="nope"):
        fastron.robot_features(baxter, "fk", ["nope"])
    with pytest.raises(fastron.InvalidArgument, match="'spread' or 'cover', got 'near'"):
        fastron.robot_features(baxter, rule="near")
    with pytest.raises(fastron.Error, match="initialize"):
        fastron.ProxyCollisionDetector(baxter_fcl, fastron.robot_features(baxter)).model()
