import os
import pathlib

import numpy as np
import pytest

import fastron


@pytest.fixture(scope="session")
def fastron_command():
    """The fastron command built with this module (set by ctest)."""
    path = os.environ.get("FASTRON_COMMAND")
    if not path:
        pytest.skip("FASTRON_COMMAND is not set")
    return pathlib.Path(path)


@pytest.fixture(scope="session")
def baxter():
    return fastron.load_robot("baxter")


@pytest.fixture(scope="session")
def three_boxes():
    return fastron.load_scene(fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml")


@pytest.fixture(scope="session")
def baxter_fcl(baxter, three_boxes):
    return fastron.FclChecker(baxter, three_boxes)


def uniform(limits, n, seed):
    return np.random.default_rng(seed).uniform(limits.lower, limits.upper, size=(n, limits.dim))
