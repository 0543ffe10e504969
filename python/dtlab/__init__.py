"""dtlab: Delaunay tetrahedralizations of 3D point sets with exact predicates, from Python.

    >>> import numpy as np, dtlab
    >>> points = np.random.default_rng(1).random((10000, 3))
    >>> tri = dtlab.triangulate(points)
    >>> tri.simplices.shape[1], tri.validate()["valid"]
    (4, True)

Beside scipy.spatial.Delaunay: `simplices` and `neighbors` follow scipy's conventions (neighbour
i is opposite vertex i, -1 on the hull); the simplices are positively oriented, which scipy's are
not; the answer is exact on every finite input (grids, cospherical sets) and the same for every
method and thread count. docs/python.md in the source tree has the whole API.
"""
import json

import numpy as np

from . import _dtlab
from . import predicates  # noqa: F401  (dtlab.predicates.orient3d, insphere)

def _version():
    """The version with the commit it was built from as PEP 440 local part: 0.1.0+8ae48d7e02fc,
    0.1.0+8ae48d7e02fc.uncommitted when the tree had changes, 0.1.0 outside a git checkout."""
    commit, _, dirty = _dtlab.commit.partition("+")
    if commit == "unknown":
        return _dtlab.version
    return f"{_dtlab.version}+{commit[:12]}" + (".uncommitted" if dirty else "")


__version__ = _version()
__commit__ = _dtlab.commit

__all__ = ["triangulate", "validate", "repair", "generate", "families", "Triangulation",
           "predicates", "__version__"]

_REPAIRS = {None: "none", False: "none", True: "splay", "none": "none", "splay": "splay",
            "flips-splay": "flips-splay", "flips": "flips", "rebuild": "rebuild"}


def _points(points, name="points"):
    """`points` as a C-contiguous float64 (n, 3) array: as given when it already is one."""
    try:
        array = np.asarray(points)
    except Exception as e:  # ragged lists and the like
        raise ValueError(f"{name} must be an (n, 3) array of numbers: {e}") from None
    if array.dtype.kind not in "iuf":
        raise ValueError(f"{name} must hold real numbers (got dtype {array.dtype})")
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"{name} must be an (n, 3) array (got shape {array.shape})")
    array = np.ascontiguousarray(array, dtype=np.float64)
    finite = np.isfinite(array).all(axis=1)
    if not finite.all():
        raise ValueError(f"{name} has a NaN or infinite coordinate (row {int(np.argmin(finite))})")
    return array


def _integer(value, name, low, high):
    """`value` as an int in [low, high], or ValueError."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"{name} must be an integer (got {value!r})")
    if not low <= value <= high:
        raise ValueError(f"{name} must be in [{low}, {high}] (got {value})")
    return int(value)


def _simplices(simplices, point_count):
    try:
        array = np.asarray(simplices)
    except Exception as e:
        raise ValueError(f"simplices must be an (m, 4) integer array: {e}") from None
    if array.size == 0 and array.ndim <= 2:
        return np.zeros((0, 4), dtype=np.int64)  # an empty list of tetrahedra
    if array.dtype.kind not in "iu":
        raise ValueError(f"simplices must be an (m, 4) integer array (got dtype {array.dtype})")
    if array.ndim != 2 or array.shape[1] != 4:
        raise ValueError(f"simplices must be an (m, 4) array (got shape {array.shape})")
    if array.size and (array.min() < 0 or array.max() >= point_count):
        raise ValueError(f"simplices must hold vertex ids in [0, {point_count})")
    return np.ascontiguousarray(array, dtype=np.int64)


class Triangulation:
    """A Delaunay tetrahedralization returned by triangulate().

    points     the input as float64, (n, 3)
    simplices  (m, 4) int32 input point ids, each tetrahedron positively oriented
               (orient3d > 0: the fourth point lies on the side of the first three into which
               (b - a) x (c - a) points); an exact duplicate point is named by its lowest index
    neighbors  (m, 4) int32: the tetrahedron opposite vertex i, -1 on the hull (scipy's)
    convex_hull  (k, 3) int32 hull triangles, each turned outward ((b - a) x (c - a) points out)
    stats      the run's counters and times, the dict `dtlab triangulate --stats` writes
    """

    def __init__(self, points, simplices, stats):
        self.points = points
        self.simplices = simplices
        self.stats = stats
        self._neighbors = None
        self._hull = None

    def _adjacency(self):
        if self._neighbors is None:
            self._neighbors, self._hull = _dtlab.face_adjacency(
                np.ascontiguousarray(self.simplices, dtype=np.int64), len(self.points))

    @property
    def neighbors(self):
        self._adjacency()
        return self._neighbors

    @property
    def convex_hull(self):
        self._adjacency()
        return self._hull

    def validate(self, kernel="adaptive", threads=0):
        """The exact validator's report on this mesh (see dtlab.validate)."""
        return validate(self.points, self.simplices, kernel=kernel, threads=threads)

    def __repr__(self):
        return (f"<dtlab.Triangulation: {len(self.points)} points, {len(self.simplices)} "
                f"tetrahedra, {self.stats['predicates']} predicates, {self.stats['method']}>")


def triangulate(points, *, predicates="adaptive", method="sequential", threads=1,
                location="walk", insertion=None, seed=1, repair=None, progress=False):
    """The Delaunay tetrahedralization of `points`, an (n, 3) array.

    A float64 C-contiguous array is read as it is (the engine's one working copy, no
    conversion); anything else is converted first. The defaults are the fastest exact
    configuration (`dtlab triangulate`'s: walk location, cavity insertion); location="dag" is the
    paper's (its insertion, flips, is the default there, as with the CLI's --location dag).
    predicates  "adaptive" | "filtered" | "exact" (GMP) | "fast" (plain doubles: can fail)
    method      "sequential" or a parallel method (dtlab methods), with `threads` threads (1 to
                1024; the methods whose waits spin, at most 32 a CPU available: ValueError)
    repair      None, True ("splay": star splaying after the run, exact), "flips-splay", or
                burglary's post-check "flips" / "rebuild"
    progress    True draws a bar on stderr; a callable receives (done, total) ten times a second
    The GIL is released while the engine runs; Ctrl-C stops it within about a second and raises
    KeyboardInterrupt. Bad input (NaN, Inf, fewer than 4 points, all coplanar, wrong shape or
    dtype) raises ValueError with the CLI's message.
    """
    xyz = _points(points)
    try:
        known = repair in _REPAIRS
    except TypeError:  # unhashable (a list): the ValueError below, not a TypeError
        known = False
    if not known:
        raise ValueError(f"repair must be None, True or one of splay, flips-splay, flips, "
                         f"rebuild (got {repair!r})")
    threads = _integer(threads, "threads", 1, 1024)
    seed = _integer(seed, "seed", 0, 2**64 - 1)
    if insertion is None:
        insertion = "flips" if location == "dag" else "cavity"
    simplices, stats = _dtlab.triangulate(xyz, str(predicates), str(method), threads,
                                          str(location), str(insertion), seed,
                                          _REPAIRS[repair], progress)
    return Triangulation(xyz, simplices, json.loads(stats))


def validate(points, simplices, oriented=True, *, kernel="adaptive", threads=0):
    """The exact validator's report on `simplices` over `points`, as a dict (the JSON of
    `dtlab validate`): "valid", "consistent", and every counter (non_delaunay_faces,
    non_positive_orientation, volume_excess, ...). oriented=False accepts either orientation
    (Qhull's and others' output): negative tetrahedra are turned first, counted in
    "turned_tetrahedra". kernel "adaptive" (exact) or "exact" (GMP); threads 0: all.
    """
    xyz = _points(points)
    ids = _simplices(simplices, len(xyz))
    threads = _integer(threads, "threads", 0, 1024)
    report, turned = _dtlab.validate(xyz, ids, bool(oriented), str(kernel), threads)
    result = json.loads(report)
    result["turned_tetrahedra"] = turned
    return result


def repair(points, simplices, *, threads=0):
    """The Delaunay tetrahedralization of `points` from any tetrahedra on them, by star
    splaying with exact predicates. Returns (simplices, stats)."""
    xyz = _points(points)
    ids = _simplices(simplices, len(xyz))
    threads = _integer(threads, "threads", 0, 1024)
    repaired, stats = _dtlab.repair(xyz, ids, threads)
    return repaired, json.loads(stats)


def generate(family, n, seed=1):
    """`n` points of a generator family (dtlab.families()), as `dtlab generate` writes them."""
    return _dtlab.generate(str(family), _integer(n, "n", 1, 200_000_000),
                           _integer(seed, "seed", 0, 2**64 - 1))


def families():
    """The generator families' names."""
    return list(_dtlab.families())
