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


def test_non_finite_rows_raise_in_every_function():
    points = np.random.default_rng(1).random((20, 3))
    points[4, 2] = np.nan
    with pytest.raises(ValueError, match=r"NaN or infinite coordinate \(row 4\)"):
        dtlab.validate(points, [[0, 1, 2, 3]], oriented=False)
    rows = [np.random.default_rng(2).random((5, 3)) for _ in range(4)]
    rows[3][1, 0] = np.inf
    for kernel in ["fast", "adaptive", "filtered", "exact"]:
        with pytest.raises(ValueError, match="NaN or infinite"):
            dtlab.predicates.orient3d(*rows, kernel=kernel)


def test_thread_counts_and_seeds_out_of_range_raise():
    points = np.random.default_rng(2).random((10, 3))
    with pytest.raises(ValueError, match=r"threads must be in \[0, 1024\]"):
        dtlab.validate(points, [[0, 1, 2, 3]], threads=100000)
    with pytest.raises(ValueError, match=r"threads must be in \[0, 1024\]"):
        dtlab.repair(points, [[0, 1, 2, 3]], threads=-1)
    with pytest.raises(ValueError, match=r"seed must be in \[0, "):
        dtlab.generate("uniform", 10, seed=-1)


def test_an_empty_list_of_tetrahedra_is_validated_not_refused():
    points = np.random.default_rng(2).random((10, 3))
    report = dtlab.validate(points, [])
    assert report["tetrahedra"] == 0 and not report["valid"]
    assert report["missing_points"] == 10


def test_ragged_lists_raise():
    with pytest.raises(ValueError):
        dtlab.triangulate([[0, 0, 0], [1, 0], [0, 1, 0], [0, 0, 1]])


@pytest.mark.parametrize("options, message", [
    ({"predicates": "exactish"}, "predicates must be one of fast, adaptive, filtered, exact"),
    ({"method": "magic"}, "method must be one of sequential"),
    ({"location": "octree"}, "location must be one of dag, walk"),
    ({"insertion": "bulk"}, "insertion must be one of flips, cavity"),
    ({"repair": "glue"}, "repair must be None, True or one of"),
    ({"repair": []}, "repair must be None, True or one of"),  # unhashable: was a TypeError
    ({"repair": 2.5}, "repair must be None, True or one of"),
    ({"threads": 2}, "runs on one thread"),
    ({"threads": 0, "method": "pessimistic"}, r"threads must be in \[1, 1024\]"),
    ({"threads": "2"}, "threads must be an integer"),
    ({"threads": 10**12, "method": "pessimistic"}, r"threads must be in \[1, 1024\]"),
    ({"seed": -1}, r"seed must be in \[0, "),
    ({"seed": 2**64}, r"seed must be in \[0, "),
    ({"method": "partitioned", "threads": 2, "location": "dag"}, "walk"),
    ({"repair": "flips"}, "burglary"),
])
def test_bad_options_raise(options, message):
    points = np.random.default_rng(2).random((50, 3))
    with pytest.raises(ValueError, match=message):
        dtlab.triangulate(points, **options)


def test_more_threads_than_the_cpus_serve_raise():
    # A method whose waiting threads spin runs at most 32 threads a CPU available (docs/design.md,
    # "Threads a CPU"); the partitioned method, which never waits, takes the same count.
    cpus = len(os.sched_getaffinity(0))
    if 32 * cpus + 1 > 1024:
        pytest.skip("more than 31 CPUs: the count would pass the 1024-thread limit")
    points = np.random.default_rng(2).random((50, 3))
    with pytest.raises(ValueError, match=rf"at most {32 * cpus} here"):
        dtlab.triangulate(points, method="burglary", threads=32 * cpus + 1)
    result = dtlab.triangulate(points, method="partitioned", threads=32 * cpus + 1)
    assert len(result.simplices) > 0


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
