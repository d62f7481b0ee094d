# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The scene or vehicle a program names, as the node's frames see it, and its text output.

linkage-urdf and linkage-foxglove both take SCENE_OR_VEHICLE and -o FILE ('-': stdout): the
corners come keyed by their TF frame prefix ('' for a scene, '<corner>/' for a vehicle's
corner), and the text goes to stdout or is written whole (cli.whole_file).
"""

from __future__ import annotations

import sys
from typing import NamedTuple, TYPE_CHECKING

from .. import cli

if TYPE_CHECKING:
    from ..core.model import Scene


class Target(NamedTuple):
    """A scene or vehicle by its frames: name, {frame prefix: Scene}, warnings, input files."""

    name: str
    scenes: dict[str, Scene]
    warnings: tuple[str, ...]
    inputs: tuple[str, ...]


def load_frames(target: str) -> Target:
    """Load a bundled name or file of a scene or a vehicle (LinkageError if it is bad)."""
    from .kinematic_map import load_target
    vehicle, corners = load_target(target)
    if vehicle is None:
        (scene,) = corners.values()
        scenes, name, warnings = {'': scene}, scene.name, scene.warnings
    else:
        scenes = {f'{corner}/': s for corner, s in corners.items()}
        name, warnings = vehicle.name, vehicle.warnings
    inputs = [getattr(vehicle, 'source', '')] + [s.source for s in scenes.values()]
    return Target(name, scenes, tuple(warnings), tuple(p for p in inputs if p))


def check_text_output(output: str, target: Target) -> None:
    """Refuse -o FILE if it cannot be written or is one of the target's inputs (cli.Mistake)."""
    if output != '-':
        cli.check_output(output, '-o', inputs=target.inputs)


def write_text(output: str, text: str) -> None:
    """Write text to stdout ('-') or whole to the file output."""
    if output == '-':
        sys.stdout.write(text)
        return
    with cli.whole_file(output, encoding='utf-8') as stream:
        stream.write(text)
