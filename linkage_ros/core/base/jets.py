# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Forward-mode derivatives of array expressions: a value and its gradient, carried together.

A Jet holds a value v (any shape S) and its derivatives g = dv/dp (S + (P,)) with respect to
P parameters (here the hardpoint coordinates of a scene). Arithmetic on Jets applies the
chain rule exactly: a quantity computed from Jets carries its exact derivative, rounding
aside (no finite step). The functions below take Jets or plain numbers and arrays alike, so
one formula serves values (numpy arrays, e.g. batched over mechanism variants) and
derivatives.

>>> x = seed(np.array([3.0, 4.0]))
>>> r = sqrt(x[0] * x[0] + x[1] * x[1])
>>> float(r.v), r.g.tolist()
(5.0, [0.6, 0.8])
"""

from __future__ import annotations

import numpy as np


class Jet:
    """A value v (S) and its gradient g (S + (P,)) with respect to P parameters."""

    __slots__ = ('v', 'g')
    __array_ufunc__ = None   # ndarray (op) Jet defers to Jet's reflected operators

    def __init__(self, v, g) -> None:
        self.v = np.asarray(v, dtype=float)
        self.g = np.asarray(g, dtype=float)

    @property
    def shape(self) -> tuple[int, ...]:
        """Shape of the value."""
        return self.v.shape

    def __getitem__(self, index):
        index = index if isinstance(index, tuple) else (index,)
        if any(i is Ellipsis for i in index):   # keep the gradient's last axis out of it
            return Jet(self.v[index], self.g[index + (slice(None),)])
        return Jet(self.v[index], self.g[index])

    def __neg__(self):
        return Jet(-self.v, -self.g)

    def __add__(self, other):
        if isinstance(other, Jet):
            return Jet(self.v + other.v, self.g + other.g)
        other = np.asarray(other, dtype=float)
        return Jet(self.v + other, np.broadcast_to(
            self.g, np.broadcast_shapes(self.v.shape, other.shape) + self.g.shape[-1:]))

    __radd__ = __add__

    def __sub__(self, other):
        return self + (-other)

    def __rsub__(self, other):
        return (-self) + other

    def __mul__(self, other):
        if isinstance(other, Jet):
            return Jet(self.v * other.v,
                       self.g * other.v[..., None] + other.g * self.v[..., None])
        other = np.asarray(other, dtype=float)
        return Jet(self.v * other, self.g * other[..., None])

    __rmul__ = __mul__

    def __truediv__(self, other):
        if isinstance(other, Jet):
            return self * reciprocal(other)
        return self * (1.0 / np.asarray(other, dtype=float))

    def __rtruediv__(self, other):
        return reciprocal(self) * other


def seed(values: np.ndarray) -> Jet:
    """Return values (any shape) as a Jet of the parameters themselves: P = values.size."""
    values = np.asarray(values, dtype=float)
    return Jet(values, np.eye(values.size).reshape(values.shape + (values.size,)))


def value(x):
    """Return the value of a Jet, or x itself."""
    return x.v if isinstance(x, Jet) else x


def reciprocal(x):
    """Return 1 / x."""
    if isinstance(x, Jet):
        inverse = 1.0 / x.v
        return Jet(inverse, -x.g * (inverse * inverse)[..., None])
    return 1.0 / np.asarray(x, dtype=float)


def sqrt(x):
    """Return the square root."""
    if isinstance(x, Jet):
        root = np.sqrt(x.v)
        return Jet(root, x.g * (0.5 / root)[..., None])
    return np.sqrt(x)


def atan2(y, x):
    """Return the angle (rad) of the point (x, y) from the x axis, as np.arctan2."""
    if not isinstance(y, Jet) and not isinstance(x, Jet):
        return np.arctan2(y, x)
    yv, xv = value(y), value(x)
    angle = np.arctan2(yv, xv)
    r2 = xv * xv + yv * yv
    g = 0.0
    if isinstance(y, Jet):
        g = g + y.g * (xv / r2)[..., None]
    if isinstance(x, Jet):
        g = g - x.g * (yv / r2)[..., None]
    return Jet(angle, np.broadcast_to(g, angle.shape + np.shape(g)[-1:]))


def hypot(x, y):
    """Return sqrt(x^2 + y^2)."""
    return sqrt(x * x + y * y)


def _axis(axis: int, ndim: int) -> int:
    """Return a value axis as a non-negative number, for a value of ndim dimensions."""
    return axis + ndim if axis < 0 else axis


def total(x, axis: int = -1):
    """Return the sum along a value axis."""
    if isinstance(x, Jet):
        a = _axis(axis, x.v.ndim)
        return Jet(x.v.sum(axis=a), x.g.sum(axis=a))
    return np.sum(x, axis=axis)


def stack(items, axis: int = -1):
    """Stack values (Jets or arrays of one shape) along a new value axis."""
    if not any(isinstance(i, Jet) for i in items):
        return np.stack(items, axis=axis)
    jets = [i for i in items if isinstance(i, Jet)]
    shape = np.broadcast_shapes(*(np.shape(value(i)) for i in items))
    size = jets[0].g.shape[-1]
    values = [np.broadcast_to(value(i), shape) for i in items]
    grads = [np.broadcast_to(i.g, shape + (size,)) if isinstance(i, Jet)
             else np.zeros(shape + (size,)) for i in items]
    a = _axis(axis, len(shape) + 1)
    return Jet(np.stack(values, axis=a), np.stack(grads, axis=a))


def where(condition, a, b):
    """Return a where condition holds, else b (condition on values, broadcast)."""
    if not isinstance(a, Jet) and not isinstance(b, Jet):
        return np.where(condition, a, b)
    jet = a if isinstance(a, Jet) else b
    shape = np.broadcast_shapes(np.shape(condition), np.shape(value(a)), np.shape(value(b)))
    size = jet.g.shape[-1]

    def grad(x):
        return np.broadcast_to(x.g, shape + (size,)) if isinstance(x, Jet) else 0.0

    return Jet(np.where(condition, value(a), value(b)),
               np.where(np.asarray(condition)[..., None], grad(a), grad(b)))


def components(v):
    """Return the three components of vectors (..., 3)."""
    return v[..., 0], v[..., 1], v[..., 2]


def dot(a, b):
    """Return a . b along the last axis."""
    return total(a * b, -1)


def cross(a, b):
    """Return a x b along the last axis."""
    ax, ay, az = components(a)
    bx, by, bz = components(b)
    return stack([ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx], -1)


def norm(v):
    """Return |v| along the last axis."""
    return sqrt(dot(v, v))


def unit(v):
    """Return v / |v| along the last axis."""
    return v / norm(v)[..., None]


def expand(x):
    """Return x with a new last value axis of length 1 (x[..., None])."""
    if isinstance(x, Jet):
        return Jet(x.v[..., None], x.g[..., None, :])
    return np.asarray(x)[..., None]


def matvec(matrix, vector):
    """Return matrix (..., 3, 3) times vector (..., 3)."""
    if isinstance(vector, Jet):
        vector = Jet(vector.v[..., None, :], vector.g[..., None, :, :])
    else:
        vector = np.asarray(vector)[..., None, :]
    return total(matrix * vector, -1)


def solve(a, b):
    """
    Return x with a x = b: a (..., k, k), b (..., k).

    dx = a^-1 (db - da x): the derivative of a linear solve, exact. The caller checks that a
    is regular (NaN otherwise).
    """
    av, bv = value(a), value(b)
    x = np.linalg.solve(av, bv[..., None])[..., 0]
    if not isinstance(a, Jet) and not isinstance(b, Jet):
        return x
    rhs = 0.0
    if isinstance(b, Jet):
        rhs = rhs + b.g
    if isinstance(a, Jet):
        rhs = rhs - np.einsum('...ijp,...j->...ip', a.g, x)
    return Jet(x, np.linalg.solve(av, np.broadcast_to(rhs, x.shape + np.shape(rhs)[-1:])))
