"""dtlab.validate, dtlab.repair and dtlab.generate: round trips and their agreement with the CLI."""
import os
import subprocess
import sys

import numpy as np
from scipy.spatial import Delaunay

import dtlab
from conftest import tetrahedra_set


def test_validate_reports_a_valid_mesh_and_an_inverted_tetrahedron(uniform_points):
    tri = dtlab.triangulate(uniform_points)
    report = dtlab.validate(uniform_points, tri.simplices)
    assert report["valid"] and report["tetrahedra"] == len(tri.simplices)
    assert report["turned_tetrahedra"] == 0
    inverted = tri.simplices.copy()
    inverted[5, [2, 3]] = inverted[5, [3, 2]]
    report = dtlab.validate(uniform_points, inverted)
    assert not report["valid"] and report["non_positive_orientation"] == 1
    report = dtlab.validate(uniform_points, inverted, oriented=False)
    assert report["valid"] and report["turned_tetrahedra"] == 1


def test_validate_counts_a_non_delaunay_face_and_repair_flips_it():
    # Segment de crosses triangle abc, and e lies inside the sphere through a, b, c, d: the two
    # tetrahedra on abc tile the hull but are not Delaunay; the three around de are.
    points = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [1, 1, 1], [1, 1, -1]], float)
    two = [[0, 1, 2, 3], [0, 1, 2, 4]]
    report = dtlab.validate(points, two, oriented=False)
    assert report["consistent"] and not report["valid"]
    assert report["non_delaunay_faces"] == 1 and report["turned_tetrahedra"] == 1
    repaired, _ = dtlab.repair(points, two)
    assert len(repaired) == 3
    assert tetrahedra_set(repaired) == tetrahedra_set(dtlab.triangulate(points).simplices)


def test_qhulls_simplices_pass_unoriented_validation_on_general_position(uniform_points):
    report = dtlab.validate(uniform_points, Delaunay(uniform_points).simplices, oriented=False)
    assert report["valid"]


def test_repair_turns_scipys_overlapping_grid_mesh_into_the_delaunay_one(scipy_grid):
    theirs = Delaunay(scipy_grid).simplices
    repaired, stats = dtlab.repair(scipy_grid, theirs)
    assert dtlab.validate(scipy_grid, repaired)["valid"]
    assert tetrahedra_set(repaired) == tetrahedra_set(dtlab.triangulate(scipy_grid).simplices)
    assert stats["tetrahedra_in"] == 28 and stats["tetrahedra_out"] == 24


def test_repair_of_a_damaged_mesh_gives_the_delaunay_one(uniform_points):
    tri = dtlab.triangulate(uniform_points)
    damaged = tri.simplices[np.random.default_rng(9).permutation(len(tri.simplices))[:-40]]
    repaired, stats = dtlab.repair(uniform_points, damaged)
    assert tetrahedra_set(repaired) == tetrahedra_set(tri.simplices)
    assert stats["points"] == len(uniform_points)


def test_generate_writes_what_the_cli_writes(tmp_path):
    points = dtlab.generate("sphere", 1000, seed=3)
    assert points.shape == (1000, 3) and points.dtype == np.float64
    assert "sphere" in dtlab.families()
    if "DTLAB_CLI" in os.environ:
        path = tmp_path / "sphere.xyz"
        subprocess.run([os.environ["DTLAB_CLI"], "generate", "sphere", "1000", "--seed", "3",
                        "-o", str(path)], check=True, capture_output=True)
        assert np.array_equal(np.loadtxt(path), points)


def test_cmake_install_puts_an_importable_package_where_debians_python_looks(tmp_path):
    build = os.environ.get("DTLAB_BUILD_DIR")
    if build is None:
        import pytest
        pytest.skip("DTLAB_BUILD_DIR names the build tree (ctest sets it)")
    subprocess.run(["cmake", "--install", build, "--prefix", str(tmp_path)], check=True,
                   capture_output=True)
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    site = tmp_path / "lib" / version / "dist-packages"
    run = subprocess.run([sys.executable, "-c", "import dtlab; print(dtlab.__file__); "
                          "print(len(dtlab.triangulate(dtlab.generate('uniform', 100)).simplices))"],
                         env={**os.environ, "PYTHONPATH": str(site)}, cwd=tmp_path,
                         capture_output=True, text=True, check=True)
    where, count = run.stdout.split()
    assert where.startswith(str(site)) and int(count) > 0
    # the prefix's dist-packages of this python is on Debian's default path for /usr/local
    if sys.executable == "/usr/bin/python3":
        assert f"/usr/local/lib/{version}/dist-packages" in sys.path
