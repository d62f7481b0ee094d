# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The quantities of a solved position as functions of pose and hardpoints, named as tables are.

Each is written once on arrays or jets.Jet values (equations.py says why): the sweep's
camber_deg, toe_deg, wheel_center_{x,y,z}_mm; the alignment set of linkage-sweep
--alignment (alignment.py's and kingpin.py's definitions, the same names); and per element
of the scene <name>_length_mm, <name>_ratio (d length / d travel) and, for a spring with a
rate or a force table (a stop), <name>_force_N. The wheel rate needs the carrier's
second-order motion and is left out. Poses: center (n, 3) mm, rotation (n, 3, 3); hardpoints
(k, 3) mm.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .equations import jacobian, rack_column
from .hardpoints import link_fractions
from ..base import jets as jt
from ..measure.kingpin import kingpin_points
from ..measure.quantities import columns, columns_of_element
from ..solve.mechanism import geometry_of

if TYPE_CHECKING:
    from ..model.scene import Scene

# Names from the registry (core/measure/quantities.py), as linkage-sweep's columns
SWEEP_COLUMNS = tuple(columns('wheel'))
ALIGNMENT_COLUMNS = tuple(columns('alignment', 'kingpin'))
KINGPIN_COLUMNS = tuple(columns('kingpin'))
DEG = 180.0 / math.pi
E_Z = np.array([0.0, 0.0, 1.0])


def element_names(scene: Scene) -> list[str]:
    """Return the element quantities a scene has (length, ratio, force of a spring)."""
    return [c for e in scene.elements
            for c in columns_of_element(e.name, e.has_rate, wheel_rate=False)]


def quantities(scene: Scene, points, center, rotation, rack: float = 0.0,
               wanted: tuple[str, ...] | None = None) -> dict:
    """
    Return {name: (n,) values or Jets} at n poses of the design with hardpoints points.

    wanted: the names to compute (None: all); groups not asked for are skipped.
    """
    layout = scene.layout
    geom = geometry_of(layout, points)
    axis = jt.matvec(rotation, geom.spin_axis)
    camber, toe = camber_toe(axis, scene.side_sign)
    out = {'camber_deg': camber * DEG, 'toe_deg': toe * DEG, 'wheel_center_x_mm': center[..., 0],
           'wheel_center_y_mm': center[..., 1], 'wheel_center_z_mm': center[..., 2]}
    want = set(out) | set(ALIGNMENT_COLUMNS) | set(element_names(scene)) \
        if wanted is None else set(wanted)
    if not want - set(out):
        return out
    jac = jacobian(layout, geom, center, rotation, rack)
    motion = _slopes(jac, -jac[..., 2], 1.0)
    if want & set(ALIGNMENT_COLUMNS):
        out.update(alignment(scene, layout, geom, points, center, rotation, rack, jac, motion,
                             axis))
    if want & set(element_names(scene)):
        out.update(elements(scene, points, center, rotation, rack, motion))
    return out


def camber_toe(axis, side: float):
    """Return camber and toe (rad) of outboard spin axes (..., 3) (so3.camber_toe)."""
    ax, ay, az = jt.components(axis)
    return -jt.atan2(az, jt.hypot(ax, ay)), jt.atan2(ax, side * ay)


def _slopes(jac, rhs, travel_rate):
    """Return (v (..., 3), w (..., 3)) with J_free [v_xy, w] = rhs, v_z = travel_rate."""
    x = jt.solve(jac[..., [0, 1, 3, 4, 5]], rhs)
    v = jt.stack([x[..., 0], x[..., 1], np.full(jt.value(x).shape[:-1], travel_rate)], -1)
    return v, x[..., 2:]


def angle_rates(axis, axis_rate, side: float):
    """Return the rates of camber and toe (rad per unit input) of spin axes at axis_rate."""
    ax, ay, az = jt.components(axis)
    dx, dy, dz = jt.components(axis_rate)
    h = jt.hypot(ax, ay)
    dh = (ax * dx + ay * dy) / h
    camber_rate = -(h * dz - az * dh) / (h * h + az * az)
    return camber_rate, side * (ay * dx - ax * dy) / (ax * ax + ay * ay)


def screw(center, velocity, omega):
    """Return the unit direction, the point nearest the centre and the pitch of a twist."""
    w2 = jt.dot(omega, omega)
    return (omega / jt.expand(jt.sqrt(w2)), center + jt.cross(omega, velocity) / jt.expand(w2),
            jt.dot(omega, velocity) / w2)


def contact_patch(center, axis, radius: float):
    """Return the lowest point of wheels of radius (mm) at centres (..., 3), spin axes."""
    up = E_Z - jt.expand(axis[..., 2]) * axis
    return center - radius * up / jt.expand(jt.norm(up))


def ground_point(point, direction, height):
    """Return where lines (point, direction) meet the horizontal planes z = height."""
    return point + jt.expand((height - point[..., 2]) / direction[..., 2]) * direction


def alignment(scene, layout, geom, points, center, rotation, rack, jac, motion, axis) -> dict:
    """Return the ALIGNMENT_COLUMNS (alignment.py and kingpin.py's definitions)."""
    side, n = scene.side_sign, jt.value(center).shape[0]
    v, w = motion
    gain, steer = angle_rates(axis, jt.cross(w, axis), side)
    screw_axis, _, pitch = screw(center, v, w)
    nan3 = np.full((n, 3), np.nan)
    steer_axis, steer_point = nan3, nan3
    if layout.steer.any():
        rack_v, rack_w = _slopes(jac, -rack_column(layout, geom, center, rotation, rack), 0.0)
        steer_axis, steer_point, _ = screw(center, rack_v, rack_w)
        steer_axis = steer_axis * np.sign(jt.value(steer_axis)[..., 2:3])
    radius = scene.wheel_radius
    patch = contact_patch(center, axis, radius) if radius else nan3
    design = contact_patch(geom.center0, geom.spin_axis, radius) if radius else nan3[0]
    ground = ground_point(steer_point, steer_axis, patch[..., 2])
    king = geometric_kingpin(scene, points, geom, center, rotation, rack, patch)
    out = {
        'camber_gain_deg_per_mm': gain * DEG, 'bump_steer_deg_per_mm': steer * DEG,
        'wheel_center_vx_per_travel': v[..., 0], 'wheel_center_vy_per_travel': v[..., 1],
        'caster_deg': jt.atan2(-steer_axis[..., 0], steer_axis[..., 2]) * DEG,
        'kingpin_inclination_deg': jt.atan2(-side * steer_axis[..., 1], steer_axis[..., 2]) * DEG,
        'scrub_radius_mm': side * (patch[..., 1] - ground[..., 1]),
        'mechanical_trail_mm': ground[..., 0] - patch[..., 0],
        'track_change_mm': 2 * side * (patch[..., 1] - design[..., 1]),
        'wheelbase_change_mm': patch[..., 0] - design[..., 0],
        'wheel_center_lateral_shift_mm': side * (center[..., 1] - geom.center0[..., 1]),
        'wheel_center_longitudinal_shift_mm': center[..., 0] - geom.center0[..., 0],
        'svic_x_mm': center[..., 0] + v[..., 2] / w[..., 1],
        'svic_z_mm': center[..., 2] - v[..., 0] / w[..., 1],
        'fvic_y_mm': center[..., 1] - v[..., 2] / w[..., 0],
        'fvic_z_mm': center[..., 2] + v[..., 1] / w[..., 0],
        'screw_axis_x': screw_axis[..., 0], 'screw_axis_y': screw_axis[..., 1],
        'screw_axis_z': screw_axis[..., 2], 'screw_pitch_mm_per_rad': pitch}
    out.update(king)
    return {name: _full(out[name], n) for name in ALIGNMENT_COLUMNS}


def _full(x, n):
    """Return x broadcast to (n,) (a NaN column of a scene without the quantity)."""
    return x if isinstance(x, jt.Jet) else np.broadcast_to(np.asarray(x, dtype=float), (n,))


def joint(points, index, center, rotation, center0):
    """Return where the carrier point of hardpoint index is at the poses, (n, 3)."""
    return center + jt.matvec(rotation, points[index] - center0)


def geometric_kingpin(scene, points, geom, center, rotation, rack, patch) -> dict:
    """Return the geometric kingpin's columns (kingpin.geometric_kingpin's definitions)."""
    ends = kingpin_points(scene)
    if ends is None:
        return dict.fromkeys(KINGPIN_COLUMNS, np.nan)
    index = {name: i for i, name in enumerate(scene.point_names)}

    def body(c):
        shift = np.array([0.0, float(rack), 0.0]) if c.steer == 'rack' else 0.0
        return points[index[f'{c.name}.base']] + shift

    def place(end):
        cs = [scene.constraints[i] for i in end.constraints]
        joints = [joint(points, index[f'{c.name}.carrier'], center, rotation, geom.center0)
                  for c in cs]
        if end.kind == 'carrier':
            return joints[0]
        if end.kind == 'base':
            return body(cs[0]) + 0.0 * center
        return closest_approach(body(cs[0]), joints[0], body(cs[1]), joints[1])

    upper, lower = place(ends[0]), place(ends[1])
    axis = upper - lower
    axis = axis * jt.expand(np.sign(jt.value(axis)[..., 2]) / jt.norm(axis))
    side = scene.side_sign
    at_ground = ground_point(lower, axis, patch[..., 2])
    at_centre = ground_point(lower, axis, center[..., 2])
    return dict(zip(KINGPIN_COLUMNS, (
        jt.atan2(-axis[..., 0], axis[..., 2]) * DEG,
        jt.atan2(-side * axis[..., 1], axis[..., 2]) * DEG,
        side * (patch[..., 1] - at_ground[..., 1]), at_ground[..., 0] - patch[..., 0],
        side * (center[..., 1] - at_centre[..., 1]))))


def closest_approach(a0, a1, b0, b1):
    """Return the midpoint of the common perpendicular of lines a0-a1 and b0-b1, (n, 3)."""
    u, v, w = a1 - a0, b1 - b0, a0 - b0
    uu, uv, vv = jt.dot(u, u), jt.dot(u, v), jt.dot(v, v)
    uw, vw = jt.dot(u, w), jt.dot(v, w)
    det = uu * vv - uv * uv
    parallel = ~(jt.value(det) > 1e-12 * jt.value(uu) * jt.value(vv))
    s = jt.where(parallel, np.nan, (uv * vw - vv * uw) / det)
    t = jt.where(parallel, np.nan, (uu * vw - uv * uw) / det)
    return 0.5 * (a0 + jt.expand(s) * u + b0 + jt.expand(t) * v)


def elements(scene, points, center, rotation, rack, motion) -> dict:
    """Return each element's length (mm), ratio (d length / d travel) and spring force (N)."""
    v, w = motion
    index = {name: i for i, name in enumerate(scene.point_names)}
    center0 = points[index['wheel_center']]
    out = {}
    for e, fraction in zip(scene.elements, link_fractions(scene)):
        body = e.body
        if e.mount.kind == 'carrier':
            r = jt.matvec(rotation, e.mount.point - center0)
            point, rate = center + r, v + jt.cross(w, r)
        else:
            c = scene.constraints[e.mount.constraint]
            r = jt.matvec(rotation, points[index[f'{c.name}.carrier']] - center0)
            joint_at, joint_rate = center + r, v + jt.cross(w, r)
            if e.mount.kind == 'along':
                point, rate, body = joint_at, joint_rate, points[index[f'{c.name}.base']]
            elif e.mount.kind == 'link':
                end = points[index[f'{c.name}.base']]
                if c.steer == 'rack':
                    end = end + np.array([0.0, float(rack), 0.0])
                point, rate = end + fraction * (joint_at - end), fraction * joint_rate
            else:
                point, rate = _arm_point(points, index, c, e.mount.point, joint_at, joint_rate)
        d = point - body
        length = jt.norm(d)
        out[f'{e.name}_length_mm'] = length
        out[f'{e.name}_ratio'] = jt.dot(d, rate) / length
        if e.force_table is not None:
            out[f'{e.name}_force_N'] = _table_force(e, length)
        elif e.has_rate:
            out[f'{e.name}_force_N'] = e.rate * (e.free_length - length)
    return out


def _table_force(element, length):
    """
    Return a force-table spring's force (N, + = compressed) at lengths (mm; arrays or Jets).

    The table's force and slope at each length's value (Element.spring_at, as linkage-sweep
    reads it); a Jet's derivative is the slope times its deflection's: the table is linear
    on each segment (at a row, the slope of the segment below it, as spring_at gives it).
    """
    deflection = element.free_length - length
    at = np.asarray(jt.value(deflection), dtype=float)
    force, slope = np.empty(at.shape), np.empty(at.shape)
    for i, x in np.ndenumerate(at):
        force[i], slope[i], _ = element.spring_at(element.free_length - float(x))
    return force + slope * (deflection - at)


def _arm_point(points, index, c, given, joint_at, joint_rate):
    """Return a point on an arm and its rate: it keeps its design coordinates in the arm."""
    a0, a1 = points[index[f'{c.name}.axis0']], points[index[f'{c.name}.axis1']]
    u = jt.unit(a1 - a0)
    rho = points[index[f'{c.name}.carrier']] - a0
    e1 = jt.unit(rho - jt.dot(rho, u) * u)
    q = given - a0
    cu, c1, c2 = jt.dot(q, u), jt.dot(q, e1), jt.dot(q, jt.cross(u, e1))
    h = joint_at - a0
    f1 = jt.unit(h - jt.expand(jt.dot(h, u)) * u)
    f2 = jt.cross(u, f1)
    offset = cu * u + jt.expand(c1) * f1 + jt.expand(c2) * f2
    lever = jt.cross(u, h)
    turn = jt.dot(lever, joint_rate) / jt.dot(lever, lever)
    return a0 + offset, jt.expand(turn) * jt.cross(u, offset)
