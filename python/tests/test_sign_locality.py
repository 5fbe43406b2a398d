"""scripts/sign_locality.py: its per-term sums are the model's score, its oracle counts right."""
import importlib.util
import pathlib

import numpy as np

import fastron

_SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "sign_locality.py"
_spec = importlib.util.spec_from_file_location("sign_locality", _SCRIPT)
sign_locality = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(sign_locality)


def test_terms_sum_to_the_models_score():
    rng = np.random.default_rng(3)
    x = rng.uniform(-1, 1, size=(300, 6))
    y = np.where(np.linalg.norm(x[:, :3], axis=1) < 0.6, 1, -1)
    for kind, block in (("rq", 0), ("gaussian", 0), ("rq", 3), ("gaussian", 3)):
        model, _ = fastron.train(x, y, gamma=4, beta=5, kernel=kind, kernel_block=block,
                                 kernel_whole_share=0.3 if block else None)
        for q in rng.uniform(-1, 1, size=(5, 6)):
            features = model.features.map(q)
            terms = sign_locality.terms(model, features)
            assert np.isclose(terms.sum(), model.score(q), rtol=1e-4, atol=1e-4)


def test_oracle_share_stops_when_the_rest_cannot_change_the_sign():
    # One dominant term decides alone; terms that cancel to nothing need every one.
    assert sign_locality.oracle_share(np.array([10.0, 1.0, -1.0, 0.5])) == 0.25
    assert sign_locality.oracle_share(np.array([1.0, -1.0, 1.0, -1.0])) == 1.0
    assert sign_locality.oracle_share(np.array([3.0, -2.0, 1.5, 0.25])) == 0.75


def test_clusters_cover_every_point_once():
    points = np.random.default_rng(1).uniform(size=(100, 3))
    groups = sign_locality.clusters(points, 16)
    assert sorted(np.concatenate(groups).tolist()) == list(range(100))
    assert max(len(g) for g in groups) <= 16
