# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The hardpoints of a scene by name, and the scene they describe once moved.

Names: `<constraint>.base` (a link's or a strut's body point), `<constraint>.axis0` and
`<constraint>.axis1` (an arm's revolute axis), `<constraint>.carrier` (the carrier joint),
`wheel_center` and `spin_axis_point`. Coordinates are mm, vehicle frame, design position.

A moved design is the same Scene with other points (scene_moves.with_points: no file written or
read); a fitted design is written as the scene file it would be (scene_data_with): a spring
or damper on a link stays at its fraction of the link; one on an arm or the carrier keeps
its coordinates; a scene given with static camber and toe gets its spin_axis_point written
out once the wheel centre or that point moves (its spin axis is then the line through them,
as for any other scene).
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from typing import Any, TYPE_CHECKING

import numpy as np

from ..base.errors import LinkageError
from ..model.scene import parse_scene, resolve_scene_path, UNITS_TO_MM
from ..model.scene_moves import link_fraction, with_points
from ..model.yaml_file import read_yaml

if TYPE_CHECKING:
    from ..model.scene import Scene

AXES = ('x', 'y', 'z')


@dataclass(frozen=True)
class Design:
    """A scene with its file's data and its hardpoints. values (k, 3) mm, names (k,)."""

    scene: Scene
    data: dict            # the scene file's mapping, as read
    names: tuple[str, ...]
    values: np.ndarray

    def index(self, name: str) -> int:
        """Return the index of a hardpoint by name; LinkageError naming the known ones."""
        if name not in self.names:
            raise LinkageError(name, 'not a hardpoint of the scene '
                               f'{self.scene.name} (its points: {", ".join(self.names)})')
        return self.names.index(name)


def load_design(name_or_path: str) -> Design:
    """Load a scene (bundled name or path) with its file's data. Raises SceneError."""
    path = resolve_scene_path(name_or_path)
    data = read_yaml(path, 'scene')
    scene = parse_scene(data, source=str(path))
    return Design(scene, data, scene.point_names, scene.points)


def link_fractions(scene: Scene) -> list[float | None]:
    """Return, per element, its fraction along its link from the body end (None if not on one)."""
    return [link_fraction(e, scene.constraints) for e in scene.elements]


def scene_data_with(design: Design, values: np.ndarray) -> dict[str, Any]:
    """
    Return the scene file's mapping with the hardpoints at values (k, 3) mm.

    The mapping stays in the file's units; the reference table (results of independent
    solvers for the original design) is left out: it does not hold for a moved design.
    """
    scale = UNITS_TO_MM[design.scene.units]
    data = copy.deepcopy(design.data)
    data.pop('reference', None)
    points = {name: (np.asarray(v, dtype=float) / scale).tolist()
              for name, v in zip(design.names, values)}
    for item, c in zip(data['constraints'], design.scene.constraints):
        if c.type == 'circle':
            item['axis'] = [points[f'{c.name}.axis0'], points[f'{c.name}.axis1']]
        else:
            item['base'] = points[f'{c.name}.base']
        item['carrier'] = points[f'{c.name}.carrier']
    carrier = data['carrier']
    carrier['wheel_center'] = points['wheel_center']
    moved = design.index('spin_axis_point'), design.index('wheel_center')
    if 'static' not in carrier or not all(
            np.array_equal(values[i], design.values[i]) for i in moved):
        carrier.pop('static', None)
        carrier['spin_axis_point'] = points['spin_axis_point']
    by_name = {c.name: i for i, c in enumerate(design.scene.constraints)}
    for item, fraction in zip(data.get('elements') or [], link_fractions(design.scene)):
        if fraction is not None:   # on a link: the same fraction of the moved link
            i = by_name[item['link']]
            c = design.scene.constraints[i]
            base = np.asarray(points[f'{c.name}.base'])
            item['point'] = (base + fraction * (np.asarray(points[f'{c.name}.carrier'])
                                                - base)).tolist()
    return data


def scene_with(design: Design, values: np.ndarray) -> Scene:
    """Return the Scene of the design with its hardpoints at values (k, 3) mm (no file read)."""
    return with_points(design.scene, values)


def coordinate_names(names: tuple[str, ...]) -> list[tuple[str, str]]:
    """Return (point, axis) of every coordinate, in the order of values.ravel()."""
    return [(name, axis) for name in names for axis in AXES]
