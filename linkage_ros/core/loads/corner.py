# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The one place where the load cases call the statics (core/statics): a corner under a load.

    CornerStatics(scene, side).solve(travel_mm, load, end, tension) -> Loaded
                                                         a corner's Statics, made once
    solve_corner(scene, travel_mm, load) -> Loaded       one loaded equilibrium, travel held
    corner_load(tyre, pose, ...) -> Load                 a tyre load as the statics takes it
    bushing_deflections(scene, loaded) -> {key: (3,)}    each bushing's deflection, mm
    pivot_forces(points, loads) -> (2, 3)                a rigid revolute's two pivot forces

A corner's CornerStatics is one statics.Statics, made once and reused over the ride-height
iterations and the cases: each solve goes on from the last equilibrium (one compiled call).
N, mm, N m, vehicle frame.
"""

from __future__ import annotations

from dataclasses import replace
import math
from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from .bar import drop_element, DROP_LINK
from ..measure.alignment import patch_offset
from ..solve.mechanism import compile_scene
from ..statics.forces import rigid_arm
from ..statics.loaded import Load
from ..statics.statics import solve_loaded, Statics

if TYPE_CHECKING:
    from .transfer import CornerTyre
    from ..model.anti_roll_bar import BarSide
    from ..model.scene import Scene
    from ..statics.loaded import Loaded


class KinematicPose(NamedTuple):
    """A corner's kinematic pose at a travel: what the tyre load's points are taken from."""

    travel_mm: float
    centre: np.ndarray     # (3,) wheel centre, mm
    rotation: np.ndarray   # (3, 3) from design
    patch: np.ndarray      # (3,) contact patch, mm


def kinematic_pose(scene: Scene, solution) -> KinematicPose:
    """Return the KinematicPose of a solved kinematic position (solve.Solution)."""
    centre = np.array(solution.wheel_center, dtype=float)
    rotation = np.array(solution.rotation, dtype=float)
    axis = rotation @ compile_scene(scene).spin_axis
    patch = centre + np.array(patch_offset(axis[0], axis[1], axis[2], scene.wheel_radius))
    return KinematicPose(float(solution.travel), centre, rotation, patch)


def solve_corner(scene: Scene, travel_mm: float, load: Load) -> Loaded:
    """Return the loaded equilibrium of a corner at a held travel (mm) under a Load, alone."""
    return solve_loaded(scene, travel_mm=float(travel_mm), load=load)


class CornerStatics:
    """
    A corner's statics.Statics, made once and reused: each solve from the last equilibrium.

    side: the corner's anti-roll bar side (model.anti_roll_bar.BarSide), or None. With a bar,
    the corner carries its drop link as a constant-force spring from the arm's end E (a body
    point) to its lower end (bar.drop_element), whose E and force change with the travels:
    solve() writes them into the Statics in place (Statics.spring_in_place), as pack() would
    for the scene with_drop(end, tension) (its body end's point and pickup, its table's
    forces), so that one Statics serves every E and force.
    """

    def __init__(self, scene: Scene, side: BarSide | None = None) -> None:
        self.scene, self.side = scene, side
        if side is not None:   # at design, 1 N until the first solve says
            scene = self.with_drop(side.arm_end, 1.0)
        self.statics = Statics(scene)
        self._drop = None
        if side is not None:
            self._drop = self.statics.spring_in_place(DROP_LINK)

    def with_drop(self, end: np.ndarray, tension: float) -> Scene:
        """Return the corner's scene with its drop link from end (mm) at tension (N)."""
        element = drop_element(self.side, end, tension)
        return replace(self.scene, elements=self.scene.elements + (element,))

    def solve(self, travel_mm: float, load: Load, end: np.ndarray | None = None,
              tension: float = math.nan) -> Loaded:
        """
        Return the loaded equilibrium at a held travel (mm) under a Load.

        With a bar: its drop link from end (3,) mm at tension N (+ = tension), as
        solve_corner(with_drop(end, tension), travel_mm, load) but from the last equilibrium.
        """
        if self._drop is not None:
            x0, point, forces = self._drop
            x0[:] = end
            point[:] = end
            forces[:] = -tension   # drop_element's table: -tension at every deflection
        return self.statics.solve(float(travel_mm), load)


def corner_load(tyre: CornerTyre, pose: KinematicPose, unsprung_drop_mm: float) -> Load:
    """
    Return a corner's tyre load and unsprung mass's load as one statics Load.

    The force (tyre and unsprung) at the contact patch, with the couple that moves centre_n
    to the wheel centre and the unsprung force to the unsprung centre, unsprung_drop_mm
    below the wheel centre (doc/loads.md): all in the corner's kinematic pose at the travel.
    """
    unsprung_at = pose.centre - np.array([0.0, 0.0, unsprung_drop_mm])
    couple = (np.asarray(tyre.couple_nm, dtype=float)
              + np.cross(pose.centre - pose.patch, tyre.centre_n) / 1000.0
              + np.cross(unsprung_at - pose.patch, tyre.unsprung_n) / 1000.0)
    force = np.asarray(tyre.force_n, dtype=float) + tyre.unsprung_n
    return Load(force_n=tuple(float(f) for f in force), at='cp',
                moment_nm=tuple(float(m) for m in couple))


def bushing_deflections(scene: Scene, loaded: Loaded) -> dict[str, np.ndarray]:
    """
    Return each bushing's deflection (3,) mm: the arm's or link's point from its body point.

    From the bushing's force on the body f = K d (loaded.body_forces_n), K = axial u u^T +
    radial (I - u u^T) with u its design axis (doc/kc.md, 'The model'): d = K^-1 f.
    """
    out = {}
    for c in scene.constraints:
        b = c.bushing
        if b is None:
            continue
        if c.type == 'circle':
            u = c.base[1] - c.base[0]
            keys = ('axis0', 'axis1') if b.at == 'pivots' else ('centre',)
        else:
            u = c.carrier - c.base[0]
            keys = ('base',)
        u = u / np.linalg.norm(u)
        for key in keys:
            f = loaded.body_forces_n[f'{c.name}_{key}']
            along = (f @ u) * u
            out[f'{c.name}_{key}'] = along / b.axial + (f - along) / b.radial
    return out


def pivot_forces(points: np.ndarray, loads: list) -> np.ndarray:
    """
    Return the forces (2, 3) N that a rigid revolute's two pivots exert on the body.

    points (2, 3) mm: the pivots; loads [(point (3,), force on the revolving part (3,)), ...].
    The statics' rule (core/statics/forces.py): the forces and the moments across the axis
    balanced, the share along the axis equal.
    """
    points = np.ascontiguousarray(points, dtype=float)
    total = np.zeros(6)   # the force (3,) N and its moment about points[0] (3,) N mm
    for point, force in loads:
        total[:3] += force
        total[3:] += np.cross(np.asarray(point, dtype=float) - points[0], force)
    out = np.zeros((2, 3))
    rigid_arm(points, total, out[0], out[1])
    return out
