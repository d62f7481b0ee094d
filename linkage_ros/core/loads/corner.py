# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The one place where the load cases call the statics (core/statics): a corner under a load.

    solve_corner(scene, travel_mm, load) -> Loaded       one loaded equilibrium, travel held
    corner_load(tyre, pose, ...) -> Load                 a tyre load as the statics takes it
    bushing_deflections(scene, loaded) -> {key: (3,)}    each bushing's deflection, mm
    pivot_forces(points, loads) -> (2, 3)                a rigid revolute's two pivot forces

Switching to a Statics object (one solve per command, continued from the last) changes
solve_corner only. N, mm, N m, vehicle frame.
"""

from __future__ import annotations

from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from ..measure.alignment import patch_offset
from ..solve.mechanism import compile_scene
from ..statics import Load, solve_loaded
from ..statics.forces import _rigid_arm

if TYPE_CHECKING:
    from .transfer import CornerTyre
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
    """Return the loaded equilibrium of a corner at a held travel (mm) under a Load."""
    return solve_loaded(scene, travel_mm=float(travel_mm), load=load)


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
    _rigid_arm(points, total, out[0], out[1])
    return out
