# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The tables of solved load cases, their columns the quantity registry's (doc/quantities.md).

    corners   a row per case and corner: travel, camber and toe under load, the tyre's wrench
    pickups   a row per case, corner, pickup and end: where, the force and a bushing's couple
              on the body (end body), on the carrier (end carrier), on an anti-roll bar (bar)
    members   a row per case, corner and member: a link's or drop link's axial force, a
              spring's or stop's force, a bushing's force and deflection, a bar's torque
    summary   a row per corner, pickup and end: the largest force over the cases, and its case

Text columns (case, corner, status, pickup, end, member, kind) and numbers in mm, deg, N, N m.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .bar import DROP_LINK
from .corner import bushing_deflections
from .transfer import ground_moment
from ..solve.mechanism import compile_scene

if TYPE_CHECKING:
    from .answer import CaseAnswer, CornerAnswer

CORNER_COLUMNS = ('case', 'corner', 'status', 'travel_mm', 'camber_deg', 'toe_deg',
                  'wheel_center_x_mm', 'wheel_center_y_mm', 'wheel_center_z_mm', 'tyre_fx_N',
                  'tyre_fy_N', 'tyre_fz_N', 'tyre_mx_Nm', 'tyre_my_Nm', 'tyre_mz_Nm',
                  'holding_force_N')
PICKUP_COLUMNS = ('case', 'corner', 'pickup', 'end', 'x_mm', 'y_mm', 'z_mm', 'fx_N', 'fy_N',
                  'fz_N', 'force_magnitude_N', 'mx_Nm', 'my_Nm', 'mz_Nm')
MEMBER_COLUMNS = ('case', 'corner', 'member', 'kind', 'force_N', 'deflection_mm',
                  'deflection_x_mm', 'deflection_y_mm', 'deflection_z_mm', 'torque_Nm',
                  'twist_deg')
SUMMARY_COLUMNS = ('corner', 'pickup', 'end', 'force_magnitude_N', 'case', 'fx_N', 'fy_N',
                   'fz_N', 'x_mm', 'y_mm', 'z_mm')
TABLES = {'corners': CORNER_COLUMNS, 'pickups': PICKUP_COLUMNS, 'members': MEMBER_COLUMNS,
          'summary': SUMMARY_COLUMNS}
NAN3 = (math.nan,) * 3


def corner_rows(answer: CaseAnswer) -> list[list]:
    """Return the corners table's rows of a solved case."""
    rows = []
    for name, c in answer.corners.items():
        tyre = c.tyre
        moment = NAN3 if c.pose is None else ground_moment(tyre, c.pose.centre, c.pose.patch)
        loaded = c.loaded
        pose = ((loaded.camber_deg, loaded.toe_deg, *loaded.wheel_center_mm)
                if loaded is not None else (math.nan,) * 5)
        rows.append([answer.case.name, name, c.status.name, c.travel_mm, *pose, *tyre.force_n,
                     *moment, loaded.holding_force_n if loaded is not None else math.nan])
    return rows


def corner_pickups(c: CornerAnswer) -> list[tuple]:
    """
    Return (pickup, end, point (3,), force (3,), couple (3,)) of a solved corner.

    The body's pickups as the statics names them (<link>_base, <arm>_axis0, _axis1 or
    _centre, <strut>_top, <spring>_body), the force on the body; an anti-roll bar's drop link
    top (arb_drop_link, end bar), the force on the bar; each constraint's carrier point
    (<constraint>_carrier, in the loaded pose), the force on the carrier.
    """
    loaded, out = c.loaded, []
    for key, force in loaded.body_forces_n.items():
        couple = loaded.body_moments_nm.get(key, np.zeros(3))
        pickup, end = key, 'body'
        if key == f'{DROP_LINK}_body':
            pickup, end = DROP_LINK, 'bar'
        out.append((pickup, end, loaded.body_points_mm[key], force, couple))
    centre = compile_scene(c.scene).design_center
    for con in c.scene.constraints:
        force = loaded.ball_joint_forces_n.get(con.name)
        if force is None:
            continue
        point = loaded.wheel_center_mm + loaded.rotation @ (con.carrier - centre)
        out.append((f'{con.name}_carrier', 'carrier', point, force, np.zeros(3)))
    return out


def pickup_rows(answer: CaseAnswer) -> list[list]:
    """Return the pickups table's rows of a solved case (corners that are OK, and bars)."""
    rows = []
    for name, c in answer.corners.items():
        if c.loaded is None:
            continue
        for pickup, end, point, force, couple in corner_pickups(c):
            rows.append([answer.case.name, name, pickup, end, *point, *force,
                         float(np.linalg.norm(force)), *couple])
    for axle, bar in answer.bars.items():
        for k, (point, force) in enumerate(zip(bar.points_mm, bar.forces_n)):
            rows.append([answer.case.name, axle, f'arb_axis{k}', 'body', *point, *force,
                         float(np.linalg.norm(force)), 0.0, 0.0, 0.0])
    return rows


def member_rows(answer: CaseAnswer) -> list[list]:
    """Return the members table's rows of a solved case."""
    rows, blank = [], [math.nan] * 6
    for name, c in answer.corners.items():
        loaded = c.loaded
        if loaded is None:
            continue
        for link, force in loaded.link_forces_n.items():
            rows.append([answer.case.name, name, link, 'link', force, *blank])
        stops = {e.name for e in c.scene.elements if e.is_stop}
        for spring, force in loaded.spring_forces_n.items():
            if spring == DROP_LINK:
                rows.append([answer.case.name, name, spring, 'drop_link', -force, *blank])
                continue
            kind = 'stop' if spring in stops else 'spring'
            rows.append([answer.case.name, name, spring, kind, force, *blank])
        for key, d in bushing_deflections(c.scene, loaded).items():
            force = float(np.linalg.norm(loaded.body_forces_n[key]))
            rows.append([answer.case.name, name, key, 'bushing', force,
                         float(np.linalg.norm(d)), *d, math.nan, math.nan])
    for axle, bar in answer.bars.items():
        rows.append([answer.case.name, axle, 'anti_roll_bar', 'bar', math.nan, *blank[:4],
                     bar.torque_nm, math.degrees(bar.twist_rad)])
    return rows


def summary_rows(answers: list[CaseAnswer]) -> list[list]:
    """
    Return the summary's rows: per corner, pickup and end, the largest force over the cases.

    In the order first met; ties keep the earlier case.
    """
    best = {}
    for answer in answers:
        for row in pickup_rows(answer):
            case, corner, pickup, end, x, y, z, fx, fy, fz, size = row[:11]
            key = (corner, pickup, end)
            if key not in best or size > best[key][3]:
                best[key] = [corner, pickup, end, size, case, fx, fy, fz, x, y, z]
    return list(best.values())


def case_notes(answer: CaseAnswer) -> list[str]:
    """Say, per corner, which stops carry a force and how much (the springs' beside them)."""
    notes = []
    for name, c in answer.corners.items():
        if c.loaded is None:
            continue
        stops = [e.name for e in c.scene.elements if e.is_stop]
        springs = {k: v for k, v in c.loaded.spring_forces_n.items()
                   if k not in stops and k != DROP_LINK}
        for stop in stops:
            force = c.loaded.spring_forces_n[stop]
            if force != 0.0:
                said = ', '.join(f'{k} {v:.0f} N' for k, v in springs.items())
                notes.append(f'{answer.case.name}: {name}: {stop} closed at travel '
                             f'{c.travel_mm:.1f} mm, carrying {force:.0f} N ({said})')
    return notes
