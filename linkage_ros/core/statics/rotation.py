"""
A bushing's rotational energy on SO(3): the rotation vector of an arm and its derivatives.

The arm's rotation R from design is updated on the left, R <- exp(w) R (w a small rotation,
rad, vehicle frame), as the carrier's is. Its rotation vector phi = log(R) then moves as
d phi = A(phi) w, A the inverse of SO(3)'s left Jacobian (Barfoot, State Estimation for
Robotics, 2017, eq. 7.77b):

    A(phi) = I - [phi]x / 2 + c(theta) [phi]x^2,
    c = 1/theta^2 - (1 + cos theta) / (2 theta sin theta)

so the energy E = phi.K phi / 2 has the gradient A^T K phi, and its Hessian in w (at w = 0)
adds to A^T K A the term from A's own change (dA/dphi, exact, below).
"""

from __future__ import annotations

import math

import numpy as np

# Below this angle (rad) c and c'/theta come from their Taylor series (sympy, to theta^10):
# the closed forms lose digits to cancellation there (c' as eps / theta^3).
SERIES_BELOW = 0.1
EYE = np.eye(3)


def skew(v: np.ndarray) -> np.ndarray:
    """Return [v]x (3, 3), the matrix of v x ."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def log_so3(rotation: np.ndarray) -> np.ndarray:
    """Return the rotation vector (3,) rad of a rotation matrix (angle below pi)."""
    cos = min(1.0, max(-1.0, 0.5 * (np.trace(rotation) - 1.0)))
    axis = np.array([rotation[2, 1] - rotation[1, 2], rotation[0, 2] - rotation[2, 0],
                     rotation[1, 0] - rotation[0, 1]])   # 2 sin(theta) * unit axis
    sin = 0.5 * np.linalg.norm(axis)
    theta = math.atan2(sin, cos)
    scale = 0.5 / (1.0 - theta * theta / 6.0) if sin < 1e-8 else 0.5 * theta / sin
    return scale * axis


def coefficients(theta: float) -> tuple[float, float]:
    """Return c(theta) and c'(theta) / theta of A (module docstring)."""
    t2 = theta * theta
    if theta < SERIES_BELOW:
        c = 1 / 12 + t2 * (1 / 720 + t2 * (1 / 30240 + t2 * (1 / 1209600 + t2 / 47900160)))
        dc = 1 / 360 + t2 * (1 / 7560 + t2 * (1 / 201600 + t2 * (1 / 5987520
                                                                 + t2 * 691 / 130767436800)))
        return c, dc
    sin, cos = math.sin(theta), math.cos(theta)
    c = 1.0 / t2 - (1.0 + cos) / (2.0 * theta * sin)
    dc = (-2.0 / (t2 * theta) + (1.0 + cos) / (2.0 * t2 * sin)
          + (1.0 + cos) / (2.0 * theta * sin * sin))
    return c, dc / theta


def energy_terms(phi: np.ndarray, stiffness: np.ndarray) -> tuple[float, np.ndarray,
                                                                  np.ndarray]:
    """
    Return E, its gradient (3,) and Hessian (3, 3) in w of E = phi.K phi / 2 (N mm, rad).

    stiffness K (3, 3) N mm/rad, symmetric. Gradient A^T K phi; Hessian A^T K A plus the
    symmetrised (K phi) . (dA/dphi_k w2) (A w1)_k, exact (module docstring).
    """
    theta = float(np.linalg.norm(phi))
    c, dc = coefficients(theta)
    big = skew(phi)
    big2 = big @ big
    a = EYE - 0.5 * big + c * big2
    k_phi = stiffness @ phi
    z = np.empty((3, 3))
    for k in range(3):
        e = skew(EYE[k])
        d_a = -0.5 * e + dc * phi[k] * big2 + c * (e @ big + big @ e)
        z[k] = k_phi @ d_a
    hess = a.T @ stiffness @ a + 0.5 * (a.T @ z + z.T @ a)
    return 0.5 * float(phi @ k_phi), a.T @ k_phi, hess
