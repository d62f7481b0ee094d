# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Kinematic maps: every quantity of the tables, solved on a regular grid, for lookup tables.

A corner's map is over (travel, rack), mm: at every grid point the pose, camber and toe, the
alignment set and the scene's elements, in the units of linkage-sweep's columns (mm, deg).
Each rack's column is solved by continuation from the design position outwards, bump and
rebound apart (kinematics.sweep), so a travel limit ends one side only; points beyond a limit
are NaN and listed with the reason, never extrapolated.

An axle's map is over (left travel, right travel) at rack 0: the corners move independently,
so it combines the two wheels' columns; only the roll centre couples them, through a
function of both wheels' contact patches and their velocities (axle_map; the axle table's and
the node's, core/axle/roll_centre.py).
"""

from __future__ import annotations

from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from .sweep import header, table
from ..core.axle import height_above_ground, patch_motion, roll_centre
from ..core.measure import columns
from ..core.solve import compile_scene, sweep, tangent, travel_count, travel_range

if TYPE_CHECKING:
    from ..core.axle import Axle
    from ..core.model import Scene

AXES = ('travel_mm', 'rack_mm')
SKIPPED = ('iterations',)   # how the solver got there, not a quantity of the position
# the registry's roll centre and track, then both wheels' camber and toe
# (core/measure/quantities.py)
AXLE_QUANTITIES = tuple(columns('roll_centre', 'axle_wheel'))


class Grid(NamedTuple):
    """A regular grid axis FROM:TO:STEP (mm), counted before anything is allocated."""

    start: float
    stop: float
    step: float

    @property
    def count(self) -> float:
        """Return how many values travel_range gives (the stop always in); inf: uncountable."""
        return travel_count(self.start, self.stop, self.step)

    def values(self) -> np.ndarray:
        """Return the grid's points as an array of count floats, mm, ascending."""
        return np.sort(travel_range(self.start, self.stop, self.step))


class GridMap(NamedTuple):
    """Quantities on a 2-D grid; values (n0, n1, q), NaN where out of reach."""

    kind: str                # 'corner' or 'axle'
    name: str                # the corner's or the axle's
    axis_names: tuple[str, str]          # ('travel_mm', 'rack_mm') or the wheels' travels
    axes: tuple[np.ndarray, np.ndarray]  # (n0,), (n1,) mm, ascending
    quantities: list[str]    # (q,) names with units, as linkage-sweep's columns
    values: np.ndarray       # (n0, n1, q)
    unreached: list[tuple[str, float, float, str]]   # (corner, travel mm, rack mm, why)
    undefined: list[str] = []   # quantities it does not have (NaN wherever solved)


def quantities(scene: Scene) -> list[str]:
    """Return the names of what a corner map holds: the table columns but the grid axes."""
    return [c for c in header(scene, True, scene if scene.elements else None)
            if c not in AXES + SKIPPED]


def outwards(travels: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the indices of travels >= 0 ascending and < 0 descending: continuation's order."""
    return np.flatnonzero(travels >= 0), np.flatnonzero(travels < 0)[::-1]


def lost(corner, travels, side, solved, rack, message):
    """List the travels of side past the solved ones, the first with the solver's reason."""
    if solved == len(side):
        return []
    first = travels[side[solved]]
    return [(corner, float(travels[i]), float(rack), message if k == 0 else
             f'past travel {first:g} mm, which is out of reach at this rack')
            for k, i in enumerate(side[solved:])]


def corner_map(scene: Scene, travels: np.ndarray, racks: np.ndarray,
               corner: str = '') -> GridMap:
    """Solve every grid point of a corner: travels (nt,) and racks (nr,) mm, ascending."""
    corner = corner or scene.name
    elements = scene if scene.elements else None
    columns = header(scene, True, elements)
    keep = [i for i, c in enumerate(columns) if c not in AXES + SKIPPED]
    values = np.full((len(travels), len(racks), len(keep)), np.nan)
    unreached = []
    for j, rack in enumerate(racks):
        for side in outwards(travels):
            if not len(side):
                continue
            result = sweep(scene, travels[side], rack=float(rack))
            solved = len(result.travel)
            if solved:
                values[side[:solved], j] = table(result, scene, True, elements)[:, keep]
            unreached += lost(corner, travels, side, solved, rack, result.message)
    unreached.sort(key=lambda point: point[1:3])
    return defined_only(GridMap('corner', corner, AXES, (travels, racks),
                                [columns[i] for i in keep], values, unreached))


def defined_only(grid: GridMap) -> GridMap:
    """
    Leave out the quantities NaN at every point solved.

    They are not quantities of this map (the steer axis of a corner without a steer: rack
    link, a roll centre without wheel radii): left out and named, not stored as NaN maps.
    """
    solved = grid.values[~np.isnan(grid.values).all(axis=2)]
    defined = (~np.isnan(solved).all(axis=0) if len(solved)
               else np.ones(len(grid.quantities), bool))
    return grid._replace(quantities=[n for n, ok in zip(grid.quantities, defined) if ok],
                         values=grid.values[:, :, defined],
                         undefined=[n for n, ok in zip(grid.quantities, defined) if not ok])


class WheelColumn(NamedTuple):
    """One wheel solved over its travels (n,) at rack 0: what an axle's map combines."""

    travel: np.ndarray          # (n,) mm
    patch: np.ndarray           # (n, 3) contact patch, mm; NaN without a wheel radius
    patch_velocity: np.ndarray  # (n, 3) its velocity per mm of travel, as a carrier point
    camber: np.ndarray          # (n,) deg
    toe: np.ndarray             # (n,) deg
    unreached: list             # (corner, travel mm, rack mm, why) beyond the limits


def wheel_column(scene: Scene, travels: np.ndarray, corner: str = '') -> WheelColumn:
    """Solve one wheel of an axle over travels (mm, ascending); NaN beyond its limits."""
    n = len(travels)
    patch, velocity = np.full((n, 3), np.nan), np.full((n, 3), np.nan)
    camber, toe = np.full(n, np.nan), np.full(n, np.nan)
    mech = compile_scene(scene)
    unreached = []
    for side in outwards(travels):
        if not len(side):
            continue
        result = sweep(scene, travels[side])
        done = side[:len(result.travel)]
        unreached += lost(corner or scene.name, travels, side, len(done), 0.0, result.message)
        if not len(done):
            continue
        camber[done], toe[done] = np.degrees(result.camber), np.degrees(result.toe)
        if scene.wheel_radius:
            v, w = tangent(mech, result.wheel_center, result.rotation)   # exact, per mm
            patch[done], velocity[done] = patch_motion(
                result.wheel_center, result.rotation @ mech.spin_axis, scene.wheel_radius, v, w)
    return WheelColumn(travels, patch, velocity, camber, toe, unreached)


def axle_map(left: WheelColumn, right: WheelColumn) -> dict[str, np.ndarray]:
    """
    Return an axle's quantities (AXLE_QUANTITIES) over (left travel, right travel), (nl, nr).

    The roll centre and its height above the ground from both wheels' patches and their
    velocities, by the axle table's functions (core/axle/roll_centre.py).
    """
    nl, nr = len(left.travel), len(right.travel)
    patch = np.stack(np.broadcast_arrays(left.patch[:, None], right.patch[None, :]), axis=2)
    velocity = np.stack(np.broadcast_arrays(left.patch_velocity[:, None],
                                            right.patch_velocity[None, :]), axis=2)
    patch, velocity = patch.reshape(-1, 2, 3), velocity.reshape(-1, 2, 3)
    centre = roll_centre(patch, velocity)
    grid = np.ones((nl, nr))
    return {'roll_centre_y_mm': centre[:, 0].reshape(nl, nr),
            'roll_centre_z_mm': centre[:, 1].reshape(nl, nr),
            'roll_centre_height_mm': height_above_ground(centre, patch).reshape(nl, nr),
            'track_mm': (patch[:, 0, 1] - patch[:, 1, 1]).reshape(nl, nr),
            'left_camber_deg': left.camber[:, None] * grid,
            'right_camber_deg': right.camber[None, :] * grid,
            'left_toe_deg': left.toe[:, None] * grid, 'right_toe_deg': right.toe[None, :] * grid}


def axle_grid_map(axle: Axle, travels: np.ndarray) -> GridMap:
    """Solve an axle's map over (left travel, right travel), both over travels (mm)."""
    left, right = wheel_column(axle.left, travels), wheel_column(axle.right, travels)
    found = axle_map(left, right)
    values = np.stack([found[q] for q in AXLE_QUANTITIES], axis=2)
    return defined_only(GridMap('axle', axle.name, ('left_travel_mm', 'right_travel_mm'),
                                (travels, travels), list(AXLE_QUANTITIES), values,
                                left.unreached + right.unreached))
