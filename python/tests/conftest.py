"""Shared inputs for the binding's tests (run by ctest as python_tests, or by hand:
PYTHONPATH=build/release/python python3 -m pytest python/tests)."""
import numpy as np
import pytest


def tetrahedra_set(simplices):
    """The tetrahedra as vertex sets: equal meshes up to order and orientation."""
    return {frozenset(int(v) for v in t) for t in simplices}


@pytest.fixture
def uniform_points():
    return np.random.default_rng(7).random((3000, 3))


@pytest.fixture
def scipy_grid():
    """scipy issue #16094's 3 x 3 x 2 grid."""
    return np.array([[x, y, z] for x in range(3) for y in range(3) for z in range(2)], float)
