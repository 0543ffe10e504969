"""The predicates over arrays: one sign per row, and with audit=True the stage that decided it.

    signs = dtlab.predicates.orient3d(a, b, c, d)                 # int8 in {-1, 0, 1}
    signs, stages = dtlab.predicates.insphere(a, b, c, d, e, audit=True)

Each argument is an (n, 3) array (row i of each is one call). Conventions (docs/predicates.md):
orient3d > 0 iff d lies on the side of plane abc into which (b - a) x (c - a) points;
insphere > 0 iff e lies inside the sphere through a, b, c, d when abcd is positively oriented.
Kernels: "adaptive" (exact; stages A, B, C, D, gmp), "filtered" (exact; A, D, gmp), "exact"
(GMP for every call: "gmp"), "fast" (the float determinant's sign, unchecked: "float").
"""
import numpy as np

from . import _dtlab

STAGES = tuple(_dtlab.stage_names())


def _rows(arrays):
    from . import _points
    out = [_points(a, name="every argument") for a in arrays]
    if len({len(a) for a in out}) != 1:
        raise ValueError("every argument must have the same number of rows")
    return out


def _result(signs, stages, audit):
    return (signs, np.array(STAGES)[stages]) if audit else signs


def orient3d(a, b, c, d, kernel="adaptive", audit=False):
    """Sign of orient3d for each row of the (n, 3) arrays a, b, c, d."""
    signs, stages = _dtlab.orient3d(*_rows([a, b, c, d]), str(kernel))
    return _result(signs, stages, audit)


def insphere(a, b, c, d, e, kernel="adaptive", audit=False):
    """Sign of insphere for each row of the (n, 3) arrays a, b, c, d, e."""
    signs, stages = _dtlab.insphere(*_rows([a, b, c, d, e]), str(kernel))
    return _result(signs, stages, audit)
