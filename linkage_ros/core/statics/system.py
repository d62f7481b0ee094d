# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The statics of a corner as bodies, points, constraints and energies (STATICS_SPEC.md).

Bodies and their coordinates (a pose: position c (3,) mm and rotation R from design; a body
point at design x0 is at c + R (x0 - ref0)): the carrier (6: dM, w), an arm with a bushing (6:
its pivot midpoint's move and w), an arm without one (1: its angle about its body-fixed axis,
ref0 = axis[0]), a link's bushed base (3: its move). Rotations are updated on the left,
R <- exp(w) R, w rad in the vehicle frame, so a point x on a body moves by dx = dc + w x v
(v = x - c) and its second derivative along w is the symmetric w x (w x v) / 2 (exact).

Constraints (L = V + lambda . c): distance |x1 - x2| = l of a link (as (|d|^2 - l^2) / 2l);
the ball joint x_arm = x_carrier of an arm (3 rows); a strut line (T - C) . n = 0 (2 rows);
the held travel M_z = z. Energies: springs, bushings (translation and rotation), and the
load as minus its work. Lengths mm, forces N, energies N mm.
"""

from __future__ import annotations

from dataclasses import dataclass
import math
from typing import NamedTuple

import numpy as np

from .rotation import energy_terms, log_so3, skew
from ..base.geometry import cross, exp_so3, N_MM_PER_NM_DEG, unit
from ..solve.mechanism import compile_scene

CARRIER, ARM, HINGE, BASE = 'carrier', 'arm', 'hinge', 'base'   # body kinds
SIZES = {CARRIER: 6, ARM: 6, HINGE: 1, BASE: 3}
EYE = np.eye(3)


class Item(NamedTuple):
    """A point (or, translates False, a direction) on body (-1: the fixed body), design x0."""

    body: int
    x0: np.ndarray
    translates: bool = True


class Bush(NamedTuple):
    """
    One bushing of an arm or a link base.

    key, constraint index, body, design point x0 on the body, where it holds B (3,) mm,
    translational stiffness (3, 3) N/mm, rotational (3, 3) N mm/rad or None, design axis.
    """

    key: str
    constraint: int
    body: int
    x0: np.ndarray
    at: np.ndarray
    stiff: np.ndarray
    turn: np.ndarray | None
    axis: np.ndarray


@dataclass
class Body:
    """One movable body: kind, its slice of the coordinates, ref0 and (hinge) axis."""

    kind: str
    start: int
    ref0: np.ndarray
    axis: np.ndarray | None = None

    @property
    def size(self) -> int:
        """How many coordinates the body has."""
        return SIZES[self.kind]

    def blocks(self) -> tuple[np.ndarray, np.ndarray]:
        """Return T (3, n) and W (3, n): dc = T dq, w = W dq."""
        n = self.size
        t, w = np.zeros((3, n)), np.zeros((3, n))
        if self.kind in (CARRIER, ARM):
            t[:, :3], w[:, 3:] = EYE, EYE
        elif self.kind == BASE:
            t[:] = EYE
        else:
            w[:, 0] = self.axis
        return t, w


@dataclass
class System:
    """A scene's statics at one travel and rack: bodies, terms, and the loaded point."""

    bodies: list
    size: int
    constraints: list        # (name, kind, points, data) rows, see residuals()
    springs: list            # (element, body point, moving point)
    bushings: list           # Bush
    rotations: list          # (body, K_rot total (3, 3) N mm/rad) of bushed arms
    load_item: Item
    z: float                 # the held wheel-centre height, mm
    body_of: dict            # constraint index -> body index (arms, bushed link bases)


def build(scene, rack: float, z: float, load_x0: np.ndarray) -> System:
    """Return the System of a scene at rack (mm), wheel-centre height z (mm), load point x0."""
    mech = compile_scene(scene)
    bodies = [Body(CARRIER, 0, mech.design_center.copy())]
    start, body_of = 6, {}
    cons, bushings, rotations = [], [], []
    line_rows = {}
    for point, top, normal in mech.line_rows():
        line_rows.setdefault(point, []).append((top.copy(), normal.copy()))
    for j, c in enumerate(scene.constraints):
        ball = Item(0, c.carrier)
        if c.type == 'line':
            for k, (top, normal) in enumerate(line_rows[j]):
                cons.append((f'{c.name}', 'line', (ball, Item(0, normal, False)), top))
            continue
        shift = np.array([0.0, rack if c.steer == 'rack' else 0.0, 0.0])
        b = c.bushing
        if c.type == 'sphere':
            base = c.base[0] + shift
            length = float(np.linalg.norm(c.carrier - c.base[0]))
            if b is None:
                cons.append((c.name, 'link', (ball, Item(-1, base)), length))
                continue
            body_of[j] = len(bodies)
            bodies.append(Body(BASE, start, c.base[0].copy()))
            start += 3
            cons.append((c.name, 'link', (ball, Item(body_of[j], c.base[0])), length))
            u = unit(c.carrier - c.base[0])
            stiff = b.axial * np.outer(u, u) + b.radial * (EYE - np.outer(u, u))
            bushings.append(Bush(f'{c.name}_base', j, body_of[j], c.base[0], base, stiff, None, u))
            continue
        a0, a1 = c.base
        axis = unit(a1 - a0)
        body_of[j] = len(bodies)
        if b is None:
            bodies.append(Body(HINGE, start, a0.copy(), axis))
            start += 1
        else:
            middle = 0.5 * (a0 + a1)
            bodies.append(Body(ARM, start, middle))
            start += 6
            along = np.outer(axis, axis)
            stiff = b.axial * along + b.radial * (EYE - along)
            turn = N_MM_PER_NM_DEG * (b.torsion * along + b.conical * (EYE - along))
            places = ([('axis0', a0), ('axis1', a1)] if b.at == 'pivots'
                      else [('centre', middle)])
            for key, at in places:
                bushings.append(Bush(f'{c.name}_{key}', j, body_of[j], at, at, stiff, turn, axis))
            if turn.any():
                rotations.append((body_of[j], len(places) * turn))
        for m in range(3):
            cons.append((c.name, 'ball', (Item(body_of[j], c.carrier), ball), m))
    cons.append(('travel', 'travel', (Item(0, mech.design_center),), z))
    springs = [(e, Item(-1, e.body), _moving(e, scene, bodies, body_of, rack))
               for e in scene.elements if e.type == 'spring' and e.has_rate]
    return System(bodies, start, cons, springs, bushings, rotations, Item(0, load_x0), z,
                  body_of)


def _moving(element, scene, bodies, body_of, rack):
    """Return the moving end of a spring as weighted items ((w, Item), ...)."""
    mount = element.mount
    if mount.kind in ('carrier', 'along'):
        return ((1.0, Item(0, mount.point)),)
    c = scene.constraints[mount.constraint]
    if mount.kind == 'arm':
        return ((1.0, Item(body_of[mount.constraint], mount.point)),)
    span = c.carrier - c.base[0]
    s = float((mount.point - c.base[0]) @ span / (span @ span))
    if mount.constraint in body_of:
        base = Item(body_of[mount.constraint], c.base[0])
    else:
        base = Item(-1, c.base[0] + np.array([0.0, rack if c.steer == 'rack' else 0.0, 0.0]))
    return ((1.0 - s, base), (s, Item(0, c.carrier)))


class Pose(NamedTuple):
    """Every body's position c (b, 3) mm and rotation R (b, 3, 3) from design."""

    c: np.ndarray
    r: np.ndarray


def initial_pose(system: System, scene, center, rotation) -> Pose:
    """Return the pose of every body at a kinematic carrier pose (M (3,), R (3, 3))."""
    mech = compile_scene(scene)
    c = np.array([b.ref0 for b in system.bodies])
    r = np.repeat(EYE[None], len(system.bodies), axis=0)
    c[0], r[0] = center, rotation
    for j, k in system.body_of.items():
        con = scene.constraints[j]
        if con.type != 'circle':
            continue
        a0, a1 = con.base
        axis = unit(a1 - a0)
        ball = center + rotation @ (con.carrier - mech.design_center)
        u0, u1 = (p - a0 - ((p - a0) @ axis) * axis for p in (con.carrier, ball))
        angle = math.atan2(axis @ cross(u0, u1), u0 @ u1)
        r[k] = exp_so3(angle * axis)
    return Pose(c, r)


def position(system: System, pose: Pose, item: Item) -> tuple[np.ndarray, np.ndarray]:
    """Return where an item is, x (a point or a direction), and v = R (x0 - ref0), (3,) mm."""
    if item.body < 0:
        return item.x0, np.zeros(3)
    body = system.bodies[item.body]
    if not item.translates:
        v = pose.r[item.body] @ item.x0
        return v, v
    v = pose.r[item.body] @ (item.x0 - body.ref0)
    return pose.c[item.body] + v, v


def point_of(system: System, pose: Pose, weighted) -> np.ndarray:
    """Return the position (3,) of weighted items ((w, Item), ...)."""
    return sum(w * position(system, pose, it)[0] for w, it in weighted)


class Assembly:
    """Accumulates gradient (n,), Hessian (n, n), constraint values and rows at one pose."""

    def __init__(self, system: System, pose: Pose) -> None:
        self.system, self.pose = system, pose
        n = system.size
        self.grad, self.hess = np.zeros(n), np.zeros((n, n))
        self.blocks = [b.blocks() for b in system.bodies]

    def jac(self, weighted) -> np.ndarray:
        """Return d x / d q (3, n) of weighted items."""
        out = np.zeros((3, self.system.size))
        for w, it in weighted:
            if it.body < 0:
                continue
            body = self.system.bodies[it.body]
            t, wb = self.blocks[it.body]
            _, v = position(self.system, self.pose, it)
            block = -skew(v) @ wb + (t if it.translates else 0.0)
            out[:, body.start:body.start + body.size] += w * block
        return out

    def term(self, points, grads, hess, factor: float = 1.0) -> np.ndarray:
        """
        Add factor times a term of points; return the term's row d/dq (n,), unscaled.

        points: weighted items each; grads (p, 3) its d/dx; hess (p, p, 3, 3) its d2/dx2
        (blocks may be None), or None.
        """
        jacs = [self.jac(p) for p in points]
        row = sum(g @ j for g, j in zip(grads, jacs))
        self.grad += factor * row
        if hess is not None:
            for i, ji in enumerate(jacs):
                for k, jk in enumerate(jacs):
                    if hess[i][k] is not None:
                        self.hess += factor * (ji.T @ hess[i][k] @ jk)
        for p, g in zip(points, grads):
            for w, it in p:
                if it.body < 0:
                    continue
                body = self.system.bodies[it.body]
                _, v = position(self.system, self.pose, it)
                wb = self.blocks[it.body][1]
                second = 0.5 * (np.outer(v, g) + np.outer(g, v)) - (g @ v) * EYE
                s = slice(body.start, body.start + body.size)
                self.hess[s, s] += factor * w * (wb.T @ second @ wb)
        return row

    def body_term(self, body: int, grad: np.ndarray, hess: np.ndarray | None) -> None:
        """Add an energy's gradient (3,) and Hessian (3, 3) in a body's rotation w."""
        b = self.system.bodies[body]
        wb = self.blocks[body][1]
        s = slice(b.start, b.start + b.size)
        self.grad[s] += wb.T @ grad
        if hess is not None:
            self.hess[s, s] += wb.T @ hess @ wb


def constraint_terms(kind, points, data, xs):
    """Return c, d/dx (p, 3), d2/dx2 (p, p, 3, 3) or None of a constraint row at xs."""
    if kind == 'link':
        d = xs[0] - xs[1]
        h = EYE / data
        return (d @ d - data * data) / (2.0 * data), np.array([d / data, -d / data]), \
            [[h, -h], [-h, h]]
    if kind == 'ball':
        e = EYE[data]
        return xs[0][data] - xs[1][data], np.array([e, -e]), None
    if kind == 'line':
        gap = data - xs[0]
        return gap @ xs[1], np.array([-xs[1], gap]), [[None, -EYE], [-EYE, None]]
    return xs[0][2] - data, np.array([EYE[2]]), None


def spring_terms(element, x_body, x_move):
    """Return E, d/dx (2, 3), d2/dx2 of a spring between x_body and x_move (N mm)."""
    d = x_move - x_body
    length = float(np.linalg.norm(d))
    u = d / length
    pushed, stiffness, energy = element.spring_at(length)   # a rate or a force table
    f = -pushed   # the tension, N
    h = stiffness * np.outer(u, u) + f / length * (EYE - np.outer(u, u))
    return energy, np.array([-f * u, f * u]), [[h, -h], [-h, h]]


def assemble(system: System, pose: Pose, multipliers: np.ndarray, force: np.ndarray,
             moment: np.ndarray):
    """
    Return (gradient of L (n,), Hessian of L (n, n), c (m,), dc/dq (m, n), energy) at a pose.

    force (3,) N at the load point, moment (3,) N mm; L = V - work + multipliers . c.
    """
    asm = Assembly(system, pose)
    m = len(system.constraints)
    values, rows = np.empty(m), np.empty((m, system.size))
    energy = 0.0
    for i, (_, kind, items, data) in enumerate(system.constraints):
        xs = [position(system, pose, it)[0] for it in items]
        c, g, h = constraint_terms(kind, items, data, xs)
        values[i] = c
        # term() adds multiplier * row to the gradient and returns the row unscaled
        rows[i] = asm.term([((1.0, it),) for it in items], g, h, multipliers[i])
    for element, body, moving in system.springs:
        e, g, h = spring_terms(element, body.x0, point_of(system, pose, moving))
        energy += e
        asm.term([((1.0, body),), moving], g, h)
    for b in system.bushings:
        d = position(system, pose, Item(b.body, b.x0))[0] - b.at
        energy += 0.5 * d @ b.stiff @ d
        asm.term([((1.0, Item(b.body, b.x0)),)], np.array([b.stiff @ d]), [[b.stiff]])
    for k, turn in system.rotations:
        e, g, h = energy_terms(log_so3(pose.r[k]), turn)
        energy += e
        asm.body_term(k, g, h)
    x_load = position(system, pose, system.load_item)[0]
    energy -= force @ x_load
    asm.term([((1.0, system.load_item),)], np.array([-force]), None)
    asm.body_term(0, -moment, None)
    hess = 0.5 * (asm.hess + asm.hess.T)
    return asm.grad, hess, values, rows, energy


def moved(system: System, pose: Pose, step: np.ndarray) -> Pose:
    """Return the pose moved by a coordinate step (n,): c += T dq, R <- exp(W dq) R."""
    c, r = pose.c.copy(), pose.r.copy()
    for k, body in enumerate(system.bodies):
        t, w = body.blocks()
        dq = step[body.start:body.start + body.size]
        c[k] = c[k] + t @ dq
        omega = w @ dq
        if omega.any():
            r[k] = exp_so3(omega) @ r[k]
    return Pose(c, r)
