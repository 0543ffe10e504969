"""dtlab.triangulate beside scipy.spatial.Delaunay, and the Triangulation it returns."""
import numpy as np
import pytest
from scipy.spatial import Delaunay

import dtlab
from conftest import tetrahedra_set


def test_same_tetrahedra_as_scipy_on_points_in_general_position(uniform_points):
    tri = dtlab.triangulate(uniform_points)
    reference = Delaunay(uniform_points)
    assert tri.simplices.dtype == np.int32 and tri.simplices.shape[1] == 4
    assert tetrahedra_set(tri.simplices) == tetrahedra_set(reference.simplices)


def test_simplices_are_positively_oriented(uniform_points):
    tri = dtlab.triangulate(uniform_points)
    p = tri.points[tri.simplices]
    signs = dtlab.predicates.orient3d(p[:, 0], p[:, 1], p[:, 2], p[:, 3], kernel="exact")
    assert (signs == 1).all()


def test_neighbors_match_scipys_up_to_numbering(uniform_points):
    tri = dtlab.triangulate(uniform_points)
    reference = Delaunay(uniform_points)

    def across(simplices, neighbors):
        # (tetrahedron, the vertex it is opposite to) -> the tetrahedron across, as vertex sets
        out = {}
        for t, row in enumerate(neighbors):
            for i, n in enumerate(row):
                key = (frozenset(simplices[t]), int(simplices[t][i]))
                out[key] = None if n < 0 else frozenset(simplices[n])
        return out

    assert across(tri.simplices, tri.neighbors) == across(reference.simplices, reference.neighbors)
    assert tri.neighbors.dtype == np.int32


def test_convex_hull_is_scipys_and_faces_outward(uniform_points):
    tri = dtlab.triangulate(uniform_points)
    hull = tri.convex_hull
    assert {frozenset(f) for f in hull} == {frozenset(f) for f in Delaunay(uniform_points).convex_hull}
    p = tri.points
    inside = np.repeat(p.mean(axis=0)[None, :], len(hull), axis=0)
    # outward: the inside lies where (b - a) x (c - a) does not point, orient3d < 0
    signs = dtlab.predicates.orient3d(p[hull[:, 0]], p[hull[:, 1]], p[hull[:, 2]], inside,
                                      kernel="exact")
    assert (signs == -1).all()


def test_every_method_gives_the_same_tetrahedra(uniform_points):
    expected = tetrahedra_set(dtlab.triangulate(uniform_points).simplices)
    for method in ["pessimistic", "optimistic-detect", "optimistic-prevent", "burglary",
                   "batch", "partitioned", "lock-grid"]:
        repair = True if method == "burglary" else None
        tri = dtlab.triangulate(uniform_points, method=method, threads=2, repair=repair)
        assert tetrahedra_set(tri.simplices) == expected, method
        assert tri.stats["method"] == method and tri.stats["threads"] == 2


def test_location_dag_alone_means_the_papers_flips(uniform_points):
    tri = dtlab.triangulate(uniform_points, location="dag")
    assert tri.stats["location"] == "dag" and tri.stats["insertion"] == "flips"
    assert dtlab.triangulate(uniform_points).stats["insertion"] == "cavity"


def test_paper_configuration_and_kernels_agree(uniform_points):
    expected = tetrahedra_set(dtlab.triangulate(uniform_points).simplices)
    for predicates in ["adaptive", "filtered", "exact"]:
        tri = dtlab.triangulate(uniform_points, predicates=predicates, location="dag",
                                insertion="flips")
        assert tetrahedra_set(tri.simplices) == expected, predicates
        assert tri.stats["location"] == "dag" and tri.stats["predicates"] == predicates


def test_grid_gives_a_valid_mesh_where_scipys_has_flat_tetrahedra(scipy_grid):
    tri = dtlab.triangulate(scipy_grid)
    assert len(tri.simplices) == 24
    assert tri.validate()["valid"]
    theirs = Delaunay(scipy_grid).simplices
    report = dtlab.validate(scipy_grid, theirs, oriented=False)
    assert len(theirs) == 28
    assert not report["valid"]
    # Four of scipy's tetrahedra are flat: no orientation turns them positive, and the faces
    # they share with the others are left inconsistent. Their volume is 0, so the other 24 cover
    # the hull once (no volume counted twice): the four are extra, degenerate simplices.
    assert report["non_positive_orientation"] == 4
    assert report["inconsistent_faces"] > 0
    assert not report["consistent"]
    assert report["volume_excess"] == 0 and report["probes_covered_twice"] == 0


def test_duplicates_are_named_by_their_lowest_index():
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 0, 0], [1, 1, 1]], float)
    tri = dtlab.triangulate(points)
    assert 4 not in tri.simplices
    assert tri.stats["duplicates"] == 1
    assert tri.validate()["valid"]


def test_input_arrays_of_other_layouts_are_converted():
    rng = np.random.default_rng(3)
    points = rng.random((500, 3))
    expected = tetrahedra_set(dtlab.triangulate(points).simplices)
    as_float32_exact = points.astype(np.float32).astype(np.float64)
    assert tetrahedra_set(dtlab.triangulate(np.asfortranarray(points)).simplices) == expected
    assert tetrahedra_set(dtlab.triangulate(points.tolist()).simplices) == expected
    assert (tetrahedra_set(dtlab.triangulate(as_float32_exact.astype(np.float32)).simplices)
            == tetrahedra_set(dtlab.triangulate(as_float32_exact).simplices))
    wide = np.zeros((500, 6))
    wide[:, ::2] = points
    assert tetrahedra_set(dtlab.triangulate(wide[:, ::2]).simplices) == expected
    integers = rng.integers(0, 1000, size=(300, 3))
    assert dtlab.triangulate(integers).validate()["valid"]


def test_a_c_contiguous_float64_input_is_not_copied_by_the_binding():
    points = np.random.default_rng(4).random((100, 3))
    assert dtlab.triangulate(points).points is points


def test_stats_are_the_clis_keys(uniform_points):
    stats = dtlab.triangulate(uniform_points, seed=5).stats
    for key in ["points", "tetrahedra", "seconds", "flips", "predicates", "method", "seed"]:
        assert key in stats
    assert stats["seed"] == 5 and stats["points"] == len(uniform_points)


def test_version_names_the_commit():
    assert dtlab.__version__.startswith("0.")
    assert len(dtlab.__commit__) >= 40 or dtlab.__commit__ == "unknown"
