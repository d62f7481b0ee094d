# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A scene or a vehicle, loaded by one loader: what a program, the node or a recording names.

    target = load_target('demo_vehicle')            # a bundled name or a path, either kind
    target = load_target(path, kind='scene')        # a kind the caller knows (the node's)
    target.corners    {corner: Scene}; a scene's one corner is ''
    target.files      every file read: the vehicle file, then each scene file, once

A bare name (no '/', no suffix) is a bundled vehicle if config/vehicles has it, else a bundled
scene; a path is a vehicle file if it holds a top-level `corners` mapping, else a scene file
(whose loader then says what is wrong with it). Errors are SceneError, one line.
"""

from __future__ import annotations

from os import PathLike
from pathlib import Path
from typing import NamedTuple

from .bundled import is_bare_name, vehicle_dir
from .scene import load_scene, Scene
from .vehicle import load_vehicle, Vehicle
from .yaml_file import read_yaml, SceneError

KINDS = ('scene', 'vehicle')


class Target(NamedTuple):
    """A loaded scene (vehicle None, corners {'': scene}) or vehicle (corners by name)."""

    vehicle: Vehicle | None
    corners: dict[str, Scene]

    @property
    def scene(self) -> Scene | None:
        """Return the scene of a scene file; None for a vehicle."""
        return None if self.vehicle is not None else self.corners['']

    @property
    def name(self) -> str:
        """Return the vehicle's name, or the scene's."""
        return self.vehicle.name if self.vehicle is not None else self.corners[''].name

    @property
    def prefixed(self) -> dict[str, Scene]:
        """Return the scenes by TF frame and topic prefix: '' for a scene, '<corner>/'."""
        if self.vehicle is None:
            return dict(self.corners)
        return {f'{corner}/': scene for corner, scene in self.corners.items()}

    @property
    def files(self) -> tuple[str, ...]:
        """Return every file read (the vehicle's, then each scene's once); none if stored."""
        sources = ([self.vehicle.source] if self.vehicle is not None else []) + [
            scene.source for scene in self.corners.values()]
        return tuple(p for p in dict.fromkeys(sources) if Path(p).is_file())

    @property
    def warnings(self) -> tuple[str, ...]:
        """Return the warnings of the scenes (Scene.warnings), each once, in order."""
        return tuple(dict.fromkeys(w for s in self.corners.values() for w in s.warnings))


def load_target(name_or_path: str | PathLike, kind: str | None = None) -> Target:
    """
    Load a scene or a vehicle (kind None: whichever the name or the file is); SceneError.

    kind 'scene' or 'vehicle' loads that kind only, as load_scene and load_vehicle do.
    """
    if kind not in (None, *KINDS):
        raise ValueError(f'kind must be None, scene or vehicle, not {kind!r}')
    if kind is None:
        kind = 'vehicle' if is_vehicle(name_or_path) else 'scene'
    if kind == 'vehicle':
        vehicle = load_vehicle(name_or_path)
        return Target(vehicle, vehicle.corners)
    return Target(None, {'': load_scene(name_or_path)})


def of_scene(scene: Scene) -> Target:
    """Return the Target of a scene loaded otherwise (a recording's stored text)."""
    return Target(None, {'': scene})


def is_vehicle(name_or_path: str | PathLike) -> bool:
    """Tell whether a name is a bundled vehicle, or a path a vehicle file (top-level corners)."""
    text = str(name_or_path)
    if is_bare_name(text):
        return (vehicle_dir() / f'{text}.yaml').is_file()
    path = Path(text)
    try:
        data = read_yaml(path, 'vehicle') if path.is_file() else None
    except (OSError, SceneError):
        return False   # load_scene then says what is wrong with it
    return isinstance(data, dict) and isinstance(data.get('corners'), dict)
