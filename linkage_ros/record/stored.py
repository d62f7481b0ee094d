# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The scene and vehicle files a run was solved from, as its recording stores them.

A recording (suspension_node's, linkage-replay's) keeps their content in its MCAP metadata
record RECORD, so that it can be solved again and drawn from any folder:
    'scene_yaml'             the scene file (a run of one scene)
    'vehicle_yaml'           the vehicle file (a vehicle run)
    'scene_yaml/<corner>'    each corner's scene file, as the vehicle file names it

load_stored(metadata, where) loads them again with the loaders' own checks and bounds, as a
core.model Target (the one scene-or-vehicle loader's result).
"""

from __future__ import annotations

from pathlib import Path
import tempfile
from typing import TYPE_CHECKING

from ..core.model import FILE_LIMIT_BYTES, load_target, of_scene, parse_scene, parse_yaml, \
    SceneError

if TYPE_CHECKING:
    from ..core.model import Target

RECORD = 'linkage_ros'
SCENE_KEY, VEHICLE_KEY = 'scene_yaml', 'vehicle_yaml'


def load_stored(metadata: dict, where: str) -> Target | None:
    """
    Return the Target (a vehicle or a scene) a recording's metadata stores, or None if none.

    metadata: {record name: {key: value}} (Bag.metadata); where: the recording, for errors.
    Raises SceneError naming where and the key for stored content that does not load.
    """
    stored = metadata.get(RECORD, {})
    if stored.get(VEHICLE_KEY):
        return _vehicle(stored, where)
    if stored.get(SCENE_KEY):
        origin = f'{where} (its {SCENE_KEY})'
        return of_scene(parse_scene(_parsed(stored[SCENE_KEY], origin), source=origin))
    return None


def _parsed(text, origin):
    """Return the data of stored YAML text, within the bounds of a file (core.model.yaml_file)."""
    size = len(text.encode())
    if size > FILE_LIMIT_BYTES:
        raise SceneError(origin, 'file', f'{size:,} bytes, over the limit of '
                         f'{FILE_LIMIT_BYTES:,} bytes for a scene or vehicle file')
    return parse_yaml(text, origin)


def _vehicle(stored, where):
    """
    Load a stored vehicle file, its corners' stored scene files beside it.

    Each corner's scene is written where the vehicle file names it (a relative path, kept
    inside a temporary folder); bundled names need no file.
    """
    origin = f'{where} (its {VEHICLE_KEY})'
    data = _parsed(stored[VEHICLE_KEY], origin)
    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder).resolve()
        corners = data.get('corners') if isinstance(data, dict) else None
        for corner, spec in (corners if isinstance(corners, dict) else {}).items():
            text = stored.get(f'{SCENE_KEY}/{corner}')
            ref = spec.get('scene') if isinstance(spec, dict) else None
            if not (text and isinstance(ref, str) and Path(ref).suffix):
                continue
            target = (root / ref).resolve()
            if root in target.parents:   # never write outside the temporary folder
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_text(text)
        path = root / 'vehicle.yaml'
        path.write_text(stored[VEHICLE_KEY])
        try:
            return load_target(path, 'vehicle')
        except SceneError as exc:
            raise SceneError(origin, exc.field, exc.problem.replace(str(root), '.')) from None
