# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The KKT system [[H, J^T], [J, 0]] of a corner, reduced and factorised along its structure.

Reduced: the travel row, M_z = z, holds the carrier's z coordinate. That coordinate and the
travel's multiplier leave the system: dq_z is the row's own residual, and the multiplier
follows from the z row after the solve (solve_full). So a vertical force at the wheel centre,
which enters the z row alone, moves nothing, exactly; and the wheel centre's dz per unit load
is exactly zero.

Order (pack.py's perm): clusters first, the root last. A cluster is a bushed body with the
rows that hold it to the carrier (an arm: its 6 coordinates and its ball joint's 3
multipliers; a link's bushed base: its 3 and the link's 1); the root holds the carrier's 5
other coordinates, the rigid arms' angles and the rigid parts' rows, its coordinates first.
Clusters couple with the root only (a star), so a block LU, each cluster's pivots chosen
within it, then the root's, costs about the sum of the clusters' cubes: for
double_wishbone_bushings (27 unknowns) 2 000 flops against 13 000 of a dense LU. A cluster
whose pivot is zero or not finite (a singular arm) fails the factorisation (factor returns
FAILED); the caller then factorises the whole system densely (bounds DENSE).

A root with as many coordinates as rows (no bushing between the carrier and the body: a
rigid scene) is solved as such (SQUARE): dq_root = J_root^-1 (-c_root), then its
multipliers from J_root^T. So a load moves a rigid scene's carrier by exactly zero, as the
model says, not by round-off.

Matrices in place: factor overwrites a with its factors and piv with the row swaps.
"""

from numba import njit
import numpy as np

FAILED, GENERAL, SQUARE = 0, 1, 2
jit = njit(cache=True, nogil=True, error_model='numpy')


@jit
def dense_bounds(size):
    """Return the bounds of a system factorised densely: no clusters, all root, not square."""
    out = np.empty(3, dtype=np.int64)
    out[0], out[1], out[2] = 0, size, -1
    return out


@jit
def gather(hess, rows, perm, n, a):
    """Write the reduced KKT matrix a (K, K) in perm's order from hess (n, n), rows (m, n)."""
    size = len(perm)
    for i in range(size):
        p = perm[i]
        for j in range(size):
            q = perm[j]
            if p < n:
                a[i, j] = hess[p, q] if q < n else rows[q - n, p]
            else:
                a[i, j] = rows[p - n, q] if q < n else 0.0


@jit
def _swap_rows(a, i, k, lo, hi):
    for j in range(lo, hi):
        a[i, j], a[k, j] = a[k, j], a[i, j]


@jit
def _eliminate(a, k, lo, hi, root, size):
    """Eliminate column k below its pivot from rows (k, hi) and [root, size)."""
    d = a[k, k]
    for part in range(2):
        first, last = (k + 1, hi) if part == 0 else (root, size)
        for i in range(first, last):
            f = a[i, k]
            if f == 0.0:
                continue
            f /= d
            a[i, k] = f
            for j in range(k + 1, hi):
                a[i, j] -= f * a[k, j]
            for j in range(max(root, hi), size):
                a[i, j] -= f * a[k, j]


@jit
def _pivot(a, k, hi):
    """Return the row in [k, hi) of the largest |a[., k]|, and that value."""
    p, big = k, abs(a[k, k])
    for i in range(k + 1, hi):
        if abs(a[i, k]) > big:
            p, big = i, abs(a[i, k])
    return p, big


@jit
def factor(a, piv, bounds):
    """
    Factorise a (K, K) in place along bounds; return GENERAL, SQUARE or FAILED.

    bounds: the clusters' starts, the root's start, K, the root's coordinate count (-1: never
    SQUARE). piv (2 K,): the row swaps (piv[:K]), a SQUARE root's own (piv[K:]).
    """
    clusters = len(bounds) - 3
    root, size, coords = bounds[clusters], bounds[clusters + 1], bounds[clusters + 2]
    for k in range(size):
        piv[k] = k
    for c in range(clusters):
        lo, hi = bounds[c], bounds[c + 1]
        for k in range(lo, hi):
            p, big = _pivot(a, k, hi)
            if not big > 0.0 or big == np.inf:   # zero, NaN or inf
                return FAILED
            if p != k:
                piv[k] = p
                _swap_rows(a, k, p, lo, hi)
                _swap_rows(a, k, p, root, size)
            _eliminate(a, k, lo, hi, root, size)
    if coords >= 0 and 2 * coords == size - root and coords > 0:
        first = root + coords   # the rows: J_root (coords, coords) at a[first:, root:first]
        for k in range(coords):
            p, big = _pivot(a[first:, root:first], k, coords)
            if not big > 0.0 or big == np.inf:
                return FAILED
            piv[size + k] = p
            if p != k:
                _swap_rows(a, first + k, first + p, root, first)
            d = a[first + k, root + k]
            for i in range(k + 1, coords):
                f = a[first + i, root + k] / d
                a[first + i, root + k] = f
                for j in range(k + 1, coords):
                    a[first + i, root + j] -= f * a[first + k, root + j]
        return SQUARE
    for k in range(root, size):
        p, big = _pivot(a, k, size)
        if not big > 0.0 or big == np.inf:
            return FAILED
        if p != k:
            piv[k] = p
            _swap_rows(a, k, p, 0, size)
        _eliminate(a, k, size, size, size, size)
    return GENERAL


@jit
def solve(a, piv, bounds, mode, b):
    """Solve in place a x = b (K,) with factor's a, piv and mode."""
    clusters = len(bounds) - 3
    root, size, coords = bounds[clusters], bounds[clusters + 1], bounds[clusters + 2]
    for k in range(size):   # P b: the row swaps, in their order
        p = piv[k]
        if p != k:
            b[k], b[p] = b[p], b[k]
    for c in range(clusters):   # L of the clusters
        lo, hi = bounds[c], bounds[c + 1]
        for k in range(lo, hi):
            bk = b[k]
            if bk == 0.0:
                continue
            for i in range(k + 1, hi):
                b[i] -= a[i, k] * bk
            for i in range(root, size):
                b[i] -= a[i, k] * bk
    if mode == SQUARE:
        _solve_square(a, piv, root, coords, size, b)
    else:
        for k in range(root, size):   # L, U of the root
            bk = b[k]
            for i in range(k + 1, size):
                b[i] -= a[i, k] * bk
        _back(a, b, root, size, root, size)
    for c in range(clusters - 1, -1, -1):   # U of the clusters
        _back(a, b, bounds[c], bounds[c + 1], root, size)


@jit
def _back(a, b, lo, hi, root, size):
    """Back-substitute rows [lo, hi) of U; the root's unknowns (from root on) are known."""
    for k in range(hi - 1, lo - 1, -1):
        total = b[k]
        for j in range(k + 1, hi):
            total -= a[k, j] * b[j]
        for j in range(max(root, hi), size):
            total -= a[k, j] * b[j]
        b[k] = total / a[k, k]


@jit
def _solve_square(a, piv, root, coords, size, b):
    """
    Solve a SQUARE root: dq = J^-1 r_rows, then lambda = J^-T (r_coords - H dq).

    J = P^T L U (factor's LU of J_root, swaps piv[size:]); H: the root's coordinate block.
    A zero r_rows gives dq exactly zero.
    """
    first = root + coords
    dq = b[first:size].copy()
    for k in range(coords):
        p = piv[size + k]
        if p != k:
            dq[k], dq[p] = dq[p], dq[k]
    for k in range(coords):
        for i in range(k + 1, coords):
            dq[i] -= a[first + i, root + k] * dq[k]
    for k in range(coords - 1, -1, -1):
        total = dq[k]
        for j in range(k + 1, coords):
            total -= a[first + k, root + j] * dq[j]
        dq[k] = total / a[first + k, root + k]
    rest = b[root:first].copy()
    for i in range(coords):
        for j in range(coords):
            rest[i] -= a[root + i, root + j] * dq[j]
    for k in range(coords):   # U^T w = rest
        total = rest[k]
        for j in range(k):
            total -= a[first + j, root + k] * rest[j]
        rest[k] = total / a[first + k, root + k]
    for k in range(coords - 1, -1, -1):   # L^T z = w
        for j in range(k + 1, coords):
            rest[k] -= a[first + j, root + k] * rest[j]
    for k in range(coords - 1, -1, -1):   # lambda = P^T z
        p = piv[size + k]
        if p != k:
            rest[k], rest[p] = rest[p], rest[k]
    b[root:first] = dq
    b[first:size] = rest


@jit
def solve_full(a, piv, bounds, mode, perm, hess, rows, rhs, out, b):
    """
    Solve the full KKT system [[H, J^T], [J, 0]] out = rhs (n + m,) with the reduced factors.

    The carrier's z (coordinate 2) moves by the travel row's right-hand side, rhs[n + m - 1];
    the travel's multiplier (last) follows from the z row. b (K,): scratch.
    """
    n, m = hess.shape[0], rows.shape[0]
    dz = rhs[n + m - 1]
    for i in range(len(perm)):
        p = perm[i]
        b[i] = rhs[p] - (hess[p, 2] if p < n else rows[p - n, 2]) * dz
    solve(a, piv, bounds, mode, b)
    for i in range(len(perm)):
        out[perm[i]] = b[i]
    out[2] = dz
    total = rhs[2]
    for j in range(n):
        total -= hess[2, j] * out[j]
    for k in range(m - 1):
        total -= rows[k, 2] * out[n + k]
    out[n + m - 1] = total / rows[m - 1, 2]
