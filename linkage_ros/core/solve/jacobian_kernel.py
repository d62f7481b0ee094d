# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Compiled linear algebra on the Jacobian's free columns: solve, determinant, condition, LU.

Compiled (base/compiled.py's jit); kernel.py, element_kernel.py and core/vary/pose_kernel.py
compile these in. solve_free solves once and gives the determinant;
factor and solve share one LU among many right-hand sides. A
Jacobian is (5, 6), d(guidance equations)/d(M, omega) as kernel.py writes it; FREE are the
columns of the unknowns (x, y of the wheel centre M and the small rotation omega), column 2
(dZ_M) is the travel direction.
"""

import math

import numpy as np

from ..base.compiled import jit

FREE = (0, 1, 3, 4, 5)   # Jacobian columns of the unknowns: x, y of M and omega


@jit
def determinant(jac):
    """
    Return the determinant of J_free (the FREE columns of jac (5, 6)); 0.0 if singular.

    Its sign is constant along a branch between two turning points and changes at each.
    """
    x = np.empty(5)
    return solve_free(jac, np.zeros(5), x)


@jit
def condition(jac):
    """
    Return the 2-norm condition number of J_free (the FREE columns of jac (5, 6)).

    By one-sided Jacobi (Hestenes) SVD: accurate to rounding for the small singular values
    too. inf if singular.
    """
    a = np.empty((5, 5))
    for i in range(5):
        for j in range(5):
            a[i, j] = jac[i, FREE[j]]
    for _ in range(60):
        worst = 0.0   # largest cosine between two columns before this sweep
        for p in range(4):
            for q in range(p + 1, 5):
                alpha = beta = gamma = 0.0
                for i in range(5):
                    alpha += a[i, p] * a[i, p]
                    beta += a[i, q] * a[i, q]
                    gamma += a[i, p] * a[i, q]
                cosine = abs(gamma) / math.sqrt(alpha * beta)
                if not cosine > 1e-15:
                    continue
                worst = max(worst, cosine)
                zeta = (beta - alpha) / (2.0 * gamma)
                t = math.copysign(1.0, zeta) / (abs(zeta) + math.sqrt(1.0 + zeta * zeta))
                c = 1.0 / math.sqrt(1.0 + t * t)
                s = c * t
                for i in range(5):
                    ap, aq = a[i, p], a[i, q]
                    a[i, p], a[i, q] = c * ap - s * aq, s * ap + c * aq
        if worst < 1e-8:   # the column norms are the singular values to O(cosine^2)
            break
    largest, smallest = 0.0, np.inf
    for j in range(5):
        norm = math.sqrt(a[0, j] ** 2 + a[1, j] ** 2 + a[2, j] ** 2 + a[3, j] ** 2 + a[4, j] ** 2)
        largest, smallest = max(largest, norm), min(smallest, norm)
    if not np.isfinite(largest):
        return np.nan
    return largest / smallest if smallest > 0.0 else np.inf


@jit
def factor(jac, lu, pivots):
    """
    LU-factor J_free (the FREE columns of jac (5, 6)) into lu (5, 5), pivots (5,) int.

    By partial pivoting. Returns the sign of the row permutation (1.0 or -1.0), or 0.0 if
    J_free is singular (a zero or NaN pivot).
    """
    for i in range(5):
        for j in range(5):
            lu[i, j] = jac[i, FREE[j]]
        pivots[i] = i
    sign = 1.0
    for col in range(5):
        best = col
        for row in range(col + 1, 5):
            if abs(lu[row, col]) > abs(lu[best, col]):
                best = row
        if not abs(lu[best, col]) > 0.0:   # zero or NaN
            return 0.0
        if best != col:
            sign = -sign
            for j in range(5):
                lu[col, j], lu[best, j] = lu[best, j], lu[col, j]
            pivots[col], pivots[best] = pivots[best], pivots[col]
        for row in range(col + 1, 5):
            lu[row, col] /= lu[col, col]
            for j in range(col + 1, 5):
                lu[row, j] -= lu[row, col] * lu[col, j]
    return sign


@jit
def solve(lu, pivots, rhs, x):
    """Solve J_free x = rhs (5,) into x (5,) from factor()'s lu and pivots."""
    for i in range(5):
        total = rhs[pivots[i]]
        for j in range(i):
            total -= lu[i, j] * x[j]
        x[i] = total
    for i in range(4, -1, -1):
        total = x[i]
        for j in range(i + 1, 5):
            total -= lu[i, j] * x[j]
        x[i] = total / lu[i, i]


@jit
def solve_free(jac, rhs, x):
    """
    Solve J_free x = rhs into x (5,), J_free the FREE columns of jac (5, 6).

    By LU with partial pivoting (factor, solve). Returns the determinant of J_free (its
    pivots' product, signed), or 0.0 if J_free is singular or anything is not finite.
    """
    lu, pivots = np.empty((5, 5)), np.empty(5, np.int64)
    determinant = factor(jac, lu, pivots)   # the permutation's sign; 0.0: singular
    if determinant == 0.0:
        return 0.0
    solve(lu, pivots, rhs, x)
    for i in range(5):
        determinant *= lu[i, i]
    return determinant if np.isfinite(x).all() and np.isfinite(determinant) else 0.0


@jit
def slope_many(jac, out):
    """
    Write d(free unknowns)/d(travel) of n solved poses into out (n, 5): J_free x = -J_travel.

    jac (n, 5, 6): the Jacobians there (the implicit function theorem; NaN where singular).
    """
    rhs = np.empty(5)
    for n in range(jac.shape[0]):
        for i in range(5):
            rhs[i] = -jac[n, i, 2]
        if not solve_free(jac[n], rhs, out[n]):
            out[n, :] = np.nan
