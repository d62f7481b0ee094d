"""
Kinematic maps: every quantity of the tables, solved on a regular grid, for lookup tables.

A corner's map is over (travel, rack), mm: at every grid point the pose, camber and toe, the
alignment set and the scene's elements, in the units of linkage-sweep's columns (mm, deg).
Each rack's column is solved by continuation from the design position outwards, bump and
rebound apart (kinematics.sweep), so a travel limit ends one side only; points beyond a limit
are NaN and listed with the reason, never extrapolated.

An axle's map is over (left travel, right travel) at rack 0: the corners move independently,
so it combines the two corners' columns; only the roll centre couples them, through a
function of both wheels' contact patches and their velocities (axle_map).
"""

from __future__ import annotations

import math
from typing import Callable, NamedTuple, TYPE_CHECKING

import numpy as np

from .sweep import header, table
from ..core.alignment import alignment
from ..core.kinematics import sweep, travel_range
from ..core.mechanism import compile_scene
from ..core.pose_newton import tangent

if TYPE_CHECKING:
    from ..core.scene import Scene

AXES = ('travel_mm', 'rack_mm')
SKIPPED = ('iterations',)   # how the solver got there, not a quantity of the position


class Grid(NamedTuple):
    """A regular grid axis FROM:TO:STEP (mm), counted before anything is allocated."""

    start: float
    stop: float
    step: float

    @property
    def count(self) -> int:
        """Return how many values travel_range gives (the stop is always included)."""
        steps = math.floor(abs(self.stop - self.start) / self.step + 1e-9)
        return steps + 1 + (self.start + math.copysign(self.step * steps,
                                                       self.stop - self.start) != self.stop)

    def values(self) -> np.ndarray:
        """Return the grid's points as an array of count floats, mm, ascending."""
        return np.sort(travel_range(self.start, self.stop, self.step))


class CornerMap(NamedTuple):
    """A corner's quantities on the (travel, rack) grid; values (nt, nr, q), NaN unreached."""

    corner: str
    travel: np.ndarray       # (nt,) mm, ascending
    rack: np.ndarray         # (nr,) mm, ascending
    quantities: list[str]    # (q,) names with units, as linkage-sweep's columns
    values: np.ndarray       # (nt, nr, q)
    unreached: list[tuple[float, float, str]]   # (travel mm, rack mm, why)
    undefined: list[str] = []   # quantities the corner does not have (NaN wherever solved)


def quantities(scene: Scene) -> list[str]:
    """Return the names of what a corner map holds: the table columns but the grid axes."""
    return [c for c in header(scene, True, scene if scene.elements else None)
            if c not in AXES + SKIPPED]


def corner_map(scene: Scene, travels: np.ndarray, racks: np.ndarray,
               corner: str = '') -> CornerMap:
    """Solve every grid point of a corner: travels (nt,) and racks (nr,) mm, ascending."""
    columns = header(scene, True, scene if scene.elements else None)
    keep = [i for i, c in enumerate(columns) if c not in AXES + SKIPPED]
    values = np.full((len(travels), len(racks), len(keep)), np.nan)
    unreached = []
    for j, rack in enumerate(racks):
        for side in (np.flatnonzero(travels >= 0), np.flatnonzero(travels < 0)[::-1]):
            if not len(side):
                continue
            result = sweep(scene, travels[side], rack=float(rack))
            solved = len(result.travel)
            if solved:
                rows = table(result, scene, True, scene if scene.elements else None)
                values[side[:solved], j] = rows[:, keep]
            if solved < len(side):
                first = travels[side[solved]]
                unreached += [(float(travels[i]), float(rack), result.message if k == 0 else
                               f'past travel {first:g} mm, which is out of reach at this rack')
                              for k, i in enumerate(side[solved:])]
    unreached.sort(key=lambda point: point[:2])
    names = [columns[i] for i in keep]
    # A quantity NaN at every point solved is not one of this corner (a steer axis without
    # a steer: rack link): it is left out, not stored as a map of NaN.
    solved = values[~np.isnan(values).all(axis=2)]
    defined = ~np.isnan(solved).all(axis=0) if len(solved) else np.ones(len(names), bool)
    return CornerMap(corner or scene.name, travels, racks,
                     [n for n, ok in zip(names, defined) if ok], values[:, :, defined],
                     unreached, [n for n, ok in zip(names, defined) if not ok])


class WheelColumn(NamedTuple):
    """One wheel solved over its travels (n,) at rack 0: what an axle's map combines."""

    travel: np.ndarray          # (n,) mm
    patch: np.ndarray           # (n, 3) contact patch (wheel centre without a radius), mm
    patch_velocity: np.ndarray  # (n, 3) its velocity per mm of travel, as a carrier point
    camber: np.ndarray          # (n,) deg
    toe: np.ndarray             # (n,) deg


def wheel_column(scene: Scene, travels: np.ndarray) -> WheelColumn:
    """Solve one wheel of an axle over travels (mm, ascending); NaN beyond its limits."""
    n = len(travels)
    patch, velocity = np.full((n, 3), np.nan), np.full((n, 3), np.nan)
    camber, toe = np.full(n, np.nan), np.full(n, np.nan)
    mech = compile_scene(scene)
    for side in (np.flatnonzero(travels >= 0), np.flatnonzero(travels < 0)[::-1]):
        if not len(side):
            continue
        result = sweep(scene, travels[side])
        done = side[:len(result.travel)]
        a = alignment(scene, mech, result.wheel_center, result.rotation)
        patch[done] = a.contact_patch if scene.wheel_radius else result.wheel_center
        v, w = tangent(mech, result.wheel_center, result.rotation)   # exact, per mm
        velocity[done] = v + np.cross(w, patch[done] - result.wheel_center)   # a carrier point
        camber[done], toe[done] = np.degrees(result.camber), np.degrees(result.toe)
    return WheelColumn(travels, patch, velocity, camber, toe)


def axle_map(left: WheelColumn, right: WheelColumn,
             roll_centre: Callable[[np.ndarray, np.ndarray], np.ndarray]
             ) -> dict[str, np.ndarray]:
    """
    Return an axle's quantities over (left travel, right travel), arrays (nl, nr).

    roll_centre(patch (n, 2, 3), patch_velocity (n, 2, 3)) -> (n, 2) is the roll centre's
    (y, z) mm from both wheels (column 0 left, 1 right), e.g. core.axle.roll_centre.
    """
    nl, nr = len(left.travel), len(right.travel)
    patch = np.stack(np.broadcast_arrays(left.patch[:, None], right.patch[None, :]), axis=2)
    velocity = np.stack(np.broadcast_arrays(left.patch_velocity[:, None],
                                            right.patch_velocity[None, :]), axis=2)
    centre = roll_centre(patch.reshape(-1, 2, 3), velocity.reshape(-1, 2, 3)).reshape(nl, nr, 2)
    grid = np.ones((nl, nr))
    return {'roll_centre_y_mm': centre[..., 0], 'roll_centre_z_mm': centre[..., 1],
            'track_mm': patch[..., 0, 1] - patch[..., 1, 1],
            'left_camber_deg': left.camber[:, None] * grid,
            'right_camber_deg': right.camber[None, :] * grid,
            'left_toe_deg': left.toe[:, None] * grid, 'right_toe_deg': right.toe[None, :] * grid}
