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

import numpy as np

from ..base.compiled import bare, jitable

FAILED, GENERAL, SQUARE = 0, 1, 2


def dense_bounds(size):
    """Return the bounds of a system factorised densely: no clusters, all root, not square."""
    out = np.empty(3, dtype=np.int64)
    write_dense_bounds(out, size)
    return out


@jitable
def write_dense_bounds(out, size):
    """Write the bounds of a dense factorisation of size unknowns into out (3,)."""
    out[0], out[1], out[2] = 0, size, -1


@bare
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


@bare
def factor(a, piv, bounds):
    """
    Factorise a (K, K) in place along bounds; return GENERAL, SQUARE or FAILED.

    bounds: the clusters' starts, the root's start, K, the root's coordinate count (-1: never
    SQUARE). piv (2 K,): the row swaps (piv[:K]), a SQUARE root's own (piv[K:]). Written
    out in one function: a helper taking the arrays would cost more per column (reference
    counts, numba) than the arithmetic.
    """
    clusters = len(bounds) - 3
    root, size, coords = bounds[clusters], bounds[clusters + 1], bounds[clusters + 2]
    for k in range(size):
        piv[k] = k
    for c in range(clusters + 1):   # each cluster, then the root (as one more, to the end)
        lo, hi = (bounds[c], bounds[c + 1]) if c < clusters else (root, size)
        square = c == clusters and coords > 0 and 2 * coords == size - root
        if square:
            break
        tail = max(root, hi)   # the root's columns beyond the cluster's
        for k in range(lo, hi):
            p, big = k, abs(a[k, k])   # the pivot: the largest in the column, in the cluster
            for i in range(k + 1, hi):
                if abs(a[i, k]) > big:
                    p, big = i, abs(a[i, k])
            if not big > 0.0 or big == np.inf:   # zero, NaN or inf
                return FAILED
            if p != k:
                piv[k] = p
                first = 0 if c == clusters else lo   # a root row carries the clusters' L
                for j in range(first, hi):
                    a[k, j], a[p, j] = a[p, j], a[k, j]
                for j in range(tail, size):
                    a[k, j], a[p, j] = a[p, j], a[k, j]
            d = a[k, k]
            i = k + 1
            while i < size:   # the cluster's rows below, then the root's
                if i == hi and hi < root:
                    i = root
                    continue
                f = a[i, k]
                if f != 0.0:
                    f /= d
                    a[i, k] = f
                    for j in range(k + 1, hi):
                        a[i, j] -= f * a[k, j]
                    for j in range(tail, size):
                        a[i, j] -= f * a[k, j]
                i += 1
    else:
        return GENERAL
    first = root + coords   # a SQUARE root: J_root (coords, coords) at a[first:, root:first]
    for k in range(coords):
        p, big = k, abs(a[first + k, root + k])
        for i in range(k + 1, coords):
            if abs(a[first + i, root + k]) > big:
                p, big = i, abs(a[first + i, root + k])
        if not big > 0.0 or big == np.inf:
            return FAILED
        piv[size + k] = p
        if p != k:
            for j in range(root, first):
                a[first + k, j], a[first + p, j] = a[first + p, j], a[first + k, j]
        d = a[first + k, root + k]
        for i in range(k + 1, coords):
            f = a[first + i, root + k] / d
            a[first + i, root + k] = f
            for j in range(k + 1, coords):
                a[first + i, root + j] -= f * a[first + k, root + j]
    return SQUARE


@bare
def solve(a, piv, bounds, mode, b, spare):
    """Solve in place a x = b (K,) with factor's a, piv and mode; spare (K,): scratch."""
    clusters = len(bounds) - 3
    root, size, coords = bounds[clusters], bounds[clusters + 1], bounds[clusters + 2]
    for k in range(size):   # P b: the row swaps, in their order
        p = piv[k]
        if p != k:
            b[k], b[p] = b[p], b[k]
    for c in range(clusters + 1):   # L: the clusters', then the root's
        lo, hi = (bounds[c], bounds[c + 1]) if c < clusters else (root, size)
        if c == clusters and mode == SQUARE:
            break
        for k in range(lo, hi):
            bk = b[k]
            if bk == 0.0:
                continue
            for i in range(k + 1, hi):
                b[i] -= a[i, k] * bk
            for i in range(max(root, hi), size):
                b[i] -= a[i, k] * bk
    if mode == SQUARE:
        _solve_square(a, piv, root, coords, size, b, spare)
    for c in range(clusters, -1, -1):   # U: the root's, then the clusters'
        lo, hi = (bounds[c], bounds[c + 1]) if c < clusters else (root, size)
        if c == clusters and mode == SQUARE:
            continue
        tail = max(root, hi)
        for k in range(hi - 1, lo - 1, -1):
            total = b[k]
            for j in range(k + 1, hi):
                total -= a[k, j] * b[j]
            for j in range(tail, size):
                total -= a[k, j] * b[j]
            b[k] = total / a[k, k]


@bare
def _solve_square(a, piv, root, coords, size, b, spare):
    """
    Solve a SQUARE root: dq = J^-1 r_rows, then lambda = J^-T (r_coords - H dq).

    J = P^T L U (factor's LU of J_root, swaps piv[size:]); H: the root's coordinate block.
    A zero r_rows gives dq exactly zero. spare (2 coords,): scratch.
    """
    first = root + coords
    dq, rest = spare[:coords], spare[coords:2 * coords]
    for k in range(coords):
        dq[k] = b[first + k]
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
    for k in range(coords):
        rest[k] = b[root + k]
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
    for k in range(coords):
        b[root + k], b[first + k] = dq[k], rest[k]


@bare
def solve_full(w, perm, bounds, mode):
    """
    Solve the full KKT system [[H, J^T], [J, 0]] sol = rhs (n + m,) with the reduced factors.

    w (a newton.Work): its a, piv (factor's), column = H[:, 2] (n,), row = H[2, :] (n,), jcol
    = J[:, 2] (m,): what of the full system the reduction leaves out; rhs in, sol out, b
    scratch. The carrier's z (coordinate 2) moves by the travel row's right-hand side,
    rhs[n + m - 1]; the travel's multiplier (last) follows from the z row.
    """
    column, row, jcol, rhs, out, b = w.column, w.row, w.jcol, w.rhs, w.sol, w.b
    n, m = len(column), len(jcol)
    dz = rhs[n + m - 1]
    for i in range(len(perm)):
        p = perm[i]
        b[i] = rhs[p] - (column[p] if p < n else jcol[p - n]) * dz
    solve(w.a, w.piv, bounds, mode, b, w.spare)
    for i in range(len(perm)):
        out[perm[i]] = b[i]
    out[2] = dz
    total = rhs[2]
    for j in range(n):
        total -= row[j] * out[j]
    for k in range(m - 1):
        total -= jcol[k] * out[n + k]
    out[n + m - 1] = total / jcol[m - 1]
