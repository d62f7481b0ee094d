# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The statics of a corner as bodies, points, constraints and energies (doc/kc.md, The model).

Bodies and their coordinates (a pose: position c (3,) mm and rotation R from design; a body
point at design x0 is at c + R (x0 - ref0)): the carrier (6: dM, w), an arm with a bushing (6:
its pivot midpoint's move and w), an arm without one (1: its angle about its body-fixed axis,
ref0 = axis[0]), a link's bushed base (3: its move). Rotations are updated on the left,
R <- exp(w) R, w rad in the vehicle frame, so a point x on a body moves by dx = dc + w x v
(v = x - c) and its second derivative along w is the symmetric w x (w x v) / 2 (exact).

Constraints (L = V + lambda . c): distance |x1 - x2| = l of a link (as (|d|^2 - l^2) / 2l);
the ball joint x_arm = x_carrier of an arm (3 rows); a strut line (T - C) . n = 0 (2 rows);
the held travel M_z = z, last. Energies: springs, bushings (translation and rotation), and the
load as minus its work. Lengths mm, forces N, energies N mm.

The System is the scene's, whatever the travel and rack: the held height z, the rack and the
load are inputs of each solve. A point fixed to the body that a steering rack moves (a rack
link's base, a bushing on the rack) is an Item with rack True: it sits rack mm along y from
its design place. The numbers are packed for the compiled kernels by pack.py; the numpy
formulation of the same equations is the tests' reference (test/core/statics_reference.py).
"""

from __future__ import annotations

from dataclasses import dataclass
import math
from typing import NamedTuple

import numpy as np

from ..base.geometry import cross, exp_so3, N_MM_PER_NM_DEG, unit
from ..solve.mechanism import compile_scene

CARRIER, ARM, HINGE, BASE = 'carrier', 'arm', 'hinge', 'base'   # body kinds
SIZES = {CARRIER: 6, ARM: 6, HINGE: 1, BASE: 3}
EYE = np.eye(3)


class Item(NamedTuple):
    """
    A point (or, translates False, a direction) on body (-1: the fixed body), design x0.

    rack: a fixed point that the steering rack moves along y (by the rack, mm).
    """

    body: int
    x0: np.ndarray
    translates: bool = True
    rack: bool = False


class Bush(NamedTuple):
    """
    One bushing of an arm or a link base.

    key, constraint index, body, design point x0 on the body, where it holds B (3,) mm at
    rack 0 (rack True: B moves with the rack), translational stiffness (3, 3) N/mm,
    rotational (3, 3) N mm/rad or None, design axis.
    """

    key: str
    constraint: int
    body: int
    x0: np.ndarray
    at: np.ndarray
    stiff: np.ndarray
    turn: np.ndarray | None
    axis: np.ndarray
    rack: bool = False


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


@dataclass
class System:
    """A scene's statics: bodies, constraint rows, energies, and the load's point."""

    bodies: list
    size: int
    constraints: list        # (name, kind, items, data) rows; the travel row last
    springs: list            # (element, body point, moving point: weighted items)
    bushings: list           # Bush
    rotations: list          # (body, K_rot total (3, 3) N mm/rad) of bushed arms
    load_item: Item          # the wheel centre; each solve gives its own load point x0
    body_of: dict            # constraint index -> body index (arms, bushed link bases)


def build(scene) -> System:
    """Return the System of a scene (the rack, the held height and the load are inputs)."""
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
            for top, normal in line_rows[j]:
                cons.append((c.name, 'line', (ball, Item(0, normal, False)), top))
            continue
        on_rack = c.steer == 'rack'
        b = c.bushing
        if c.type == 'sphere':
            length = float(np.linalg.norm(c.carrier - c.base[0]))
            if b is None:
                cons.append((c.name, 'link', (ball, Item(-1, c.base[0], True, on_rack)),
                             length))
                continue
            body_of[j] = len(bodies)
            bodies.append(Body(BASE, start, c.base[0].copy()))
            start += 3
            cons.append((c.name, 'link', (ball, Item(body_of[j], c.base[0])), length))
            u = unit(c.carrier - c.base[0])
            stiff = b.axial * np.outer(u, u) + b.radial * (EYE - np.outer(u, u))
            bushings.append(Bush(f'{c.name}_base', j, body_of[j], c.base[0], c.base[0].copy(),
                                 stiff, None, u, on_rack))
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
    cons.append(('travel', 'travel', (Item(0, mech.design_center),), 0.0))
    springs = [(e, Item(-1, e.body), _moving(e, scene, body_of))
               for e in scene.elements if e.type == 'spring' and e.has_rate]
    return System(bodies, start, cons, springs, bushings, rotations,
                  Item(0, mech.design_center.copy()), body_of)


def _moving(element, scene, body_of):
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
        base = Item(-1, c.base[0], True, c.steer == 'rack')
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
