"""dtlab.predicates over arrays, checked against the exact (GMP) kernel."""
import numpy as np
import pytest

import dtlab
from dtlab import predicates


def hard_rows(n, arity, seed):
    """Rows of nearly or exactly degenerate calls: points of a small integer grid (many exact
    zeros), and the same grid moved by 2^-40 steps and 0.1 (signs that rounding gets wrong: the
    fast kernel misses some 50 of 2000)."""
    rng = np.random.default_rng(seed)
    grid = rng.integers(0, 3, size=(arity, n, 3)).astype(float)
    shifted = grid + rng.integers(-1, 2, size=grid.shape) * 2.0 ** -40
    return [np.concatenate([grid[i], shifted[i] + 0.1]) for i in range(arity)]


@pytest.mark.parametrize("kernel", ["adaptive", "filtered"])
def test_exact_kernels_agree_with_gmp(kernel):
    for arity, function in [(4, predicates.orient3d), (5, predicates.insphere)]:
        rows = hard_rows(2000, arity, seed=arity)
        exact = function(*rows, kernel="exact")
        assert np.array_equal(function(*rows, kernel=kernel), exact)
        assert (exact == 0).sum() > 100 and (exact != 0).sum() > 100


def test_fast_kernel_differs_from_gmp_somewhere():
    rows = hard_rows(2000, 5, seed=11)
    wrong = predicates.insphere(*rows, kernel="fast") != predicates.insphere(*rows, kernel="exact")
    assert wrong.sum() >= 10


def test_audit_names_the_deciding_stage():
    rows = hard_rows(2000, 4, seed=4)
    signs, stages = predicates.orient3d(*rows, audit=True)
    assert set(stages) <= set(predicates.STAGES)
    assert "A" in set(stages) and len(set(stages)) >= 2  # easy calls end in A, hard ones later
    _, exact_stages = predicates.orient3d(*rows, kernel="exact", audit=True)
    assert set(exact_stages) == {"gmp"}
    _, fast_stages = predicates.orient3d(*rows, kernel="fast", audit=True)
    assert set(fast_stages) == {"float"}
    assert np.array_equal(signs, predicates.orient3d(*rows, kernel="exact"))


def test_sign_conventions():
    a, b, c = np.array([[0., 0, 0]]), np.array([[1., 0, 0]]), np.array([[0., 1, 0]])
    above = np.array([[0., 0, 1]])
    assert predicates.orient3d(a, b, c, above)[0] == 1  # (b - a) x (c - a) points to +z
    d = np.array([[0., 0, 1]]) if predicates.orient3d(a, b, c, above)[0] > 0 else None
    centre, outside = np.array([[0.2, 0.2, 0.2]]), np.array([[5., 5, 5]])
    assert predicates.insphere(a, b, c, d, centre)[0] == 1
    assert predicates.insphere(a, b, c, d, outside)[0] == -1


def test_mismatched_rows_raise():
    with pytest.raises(ValueError, match="same number of rows"):
        predicates.orient3d(np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((2, 3)))
    with pytest.raises(ValueError, match="kernel must be one of"):
        predicates.orient3d(*([np.zeros((1, 3))] * 4), kernel="quad")
