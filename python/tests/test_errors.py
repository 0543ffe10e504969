"""Bad input raises ValueError with a message that says what is wrong (the CLI's where the
engine is the one that refuses), never a crash."""
import os
import subprocess

import numpy as np
import pytest

import dtlab


def cli_error(points, tmp_path):
    """What `dtlab triangulate` says about the same points."""
    path = tmp_path / "points.xyz"
    np.savetxt(path, points, fmt="%.17g")
    run = subprocess.run([os.environ["DTLAB_CLI"], "triangulate", str(path)],
                         capture_output=True, text=True)
    assert run.returncode == 2
    return run.stderr.strip().removeprefix("dtlab: error: ")


@pytest.mark.parametrize("points", [
    np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float),                       # three points
    np.array([[x, y, 0] for x in range(4) for y in range(4)], float),         # coplanar
    np.array([[t, 2 * t, 3 * t] for t in range(10)], float),                  # collinear
    np.array([[1, 2, 3]] * 8, float),                                         # one point, repeated
])
def test_no_tetrahedralization_raises_the_clis_message(points, tmp_path):
    with pytest.raises(ValueError) as error:
        dtlab.triangulate(points)
    assert "no tetrahedralization exists" in str(error.value)
    if "DTLAB_CLI" in os.environ:
        assert str(error.value) == cli_error(points, tmp_path)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_coordinates_raise(bad):
    points = np.random.default_rng(1).random((20, 3))
    points[7, 1] = bad
    with pytest.raises(ValueError, match="NaN or infinite"):
        dtlab.triangulate(points)
    with pytest.raises(ValueError, match="NaN or infinite"):
        dtlab.repair(points, [[0, 1, 2, 3]])


@pytest.mark.parametrize("points, message", [
    (np.zeros((10, 2)), r"\(n, 3\) array \(got shape \(10, 2\)\)"),
    (np.zeros((10, 3, 1)), r"got shape \(10, 3, 1\)"),
    (np.zeros(30), r"got shape \(30,\)"),
    (np.zeros((10, 3), dtype=complex), "real numbers"),
    (np.array([["a", "b", "c"]] * 5), "real numbers"),
    (np.array([[0, 0, 0], [1, 0]], dtype=object), "real numbers"),
    (np.zeros((0, 3)), "no tetrahedralization"),
])
def test_wrong_shapes_and_dtypes_raise(points, message):
    with pytest.raises(ValueError, match=message):
        dtlab.triangulate(points)


def test_ragged_lists_raise():
    with pytest.raises(ValueError):
        dtlab.triangulate([[0, 0, 0], [1, 0], [0, 1, 0], [0, 0, 1]])


@pytest.mark.parametrize("options, message", [
    ({"predicates": "exactish"}, "predicates must be one of fast, adaptive, filtered, exact"),
    ({"method": "magic"}, "method must be one of sequential"),
    ({"location": "octree"}, "location must be one of dag, walk"),
    ({"insertion": "bulk"}, "insertion must be one of flips, cavity"),
    ({"repair": "glue"}, "repair must be None, True or one of"),
    ({"threads": 2}, "runs on one thread"),
    ({"threads": 0, "method": "pessimistic"}, r"threads must be in \[1, 1024\]"),
    ({"threads": "2"}, "threads must be an integer"),
    ({"seed": -1}, "seed must be a non-negative integer"),
    ({"method": "partitioned", "threads": 2, "location": "dag"}, "walk"),
    ({"repair": "flips"}, "burglary"),
])
def test_bad_options_raise(options, message):
    points = np.random.default_rng(2).random((50, 3))
    with pytest.raises(ValueError, match=message):
        dtlab.triangulate(points, **options)


def test_bad_simplices_raise():
    points = np.random.default_rng(2).random((10, 3))
    for simplices, message in [([[0, 1, 2, 10]], r"vertex ids in \[0, 10\)"),
                               ([[0, 1, 2, -1]], r"vertex ids in \[0, 10\)"),
                               ([[0, 1, 2]], r"\(m, 4\) array"),
                               ([[0.0, 1.0, 2.0, 3.0]], "integer array")]:
        with pytest.raises(ValueError, match=message):
            dtlab.validate(points, simplices)
        with pytest.raises(ValueError, match=message):
            dtlab.repair(points, simplices)


def test_huge_and_tiny_magnitudes_are_triangulated_exactly():
    points = np.random.default_rng(5).random((400, 3))
    expected = {frozenset(t) for t in dtlab.triangulate(points).simplices.tolist()}
    for factor in [2.0 ** 600, 2.0 ** -600, 2.0 ** -1060]:
        tri = dtlab.triangulate(points * factor)
        assert tri.validate()["valid"]
        if factor != 2.0 ** -1060:  # subnormal scaling rounds the coordinates: another set
            assert {frozenset(t) for t in tri.simplices.tolist()} == expected


def test_unknown_generator_family_raises():
    with pytest.raises(ValueError, match="unknown"):
        dtlab.generate("nonsense", 10)
