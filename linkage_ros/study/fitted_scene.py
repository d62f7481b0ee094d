# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The fitted scene file: the original scene with its moved hardpoints, saying what changed.

The file is the original scene's mapping (hardpoints.scene_data_with) dumped as YAML, exact
(float64 written so that it reads back the same), under a header of comments naming the
targets file, each coordinate moved (from, to, by, in the scene's units) and what else
follows: points of springs and dampers on moved links, a spin axis written out, the
reference table left out. It is read back before it is kept: a fitted scene always loads.
"""

from __future__ import annotations

import numpy as np
import yaml

from ..core.model import parse_scene, parse_yaml, UNITS_TO_MM
from ..core.vary import scene_data_with
from ..outputs import whole_file


def _flow_lists(dumper, data):
    """Write lists of numbers in flow style ([x, y, z]), as scene files do."""
    flow = all(isinstance(v, (int, float)) for v in data)
    return dumper.represent_sequence('tag:yaml.org,2002:seq', data, flow_style=flow)


class _Dumper(yaml.SafeDumper):
    """A safe dumper that writes points as [x, y, z]."""


_Dumper.add_representer(list, _flow_lists)


def header(targets, result) -> list[str]:
    """Return the comment lines saying how the scene was made and what moved."""
    design = targets.design
    scale = UNITS_TO_MM[design.scene.units]
    unit = design.scene.units
    lines = [f'Fitted by linkage-study fit from {targets.source}',
             f'to the scene {design.scene.name} ({design.scene.source}).',
             f'Coordinates moved ({unit}, vehicle frame, design position):']
    for (i, a), offset in zip(targets.free, result.offsets):
        name = f'{design.names[i]}.{"xyz"[a]}'
        old = design.values[i, a] / scale
        lines.append(f'  {name}: {old:.10g} -> {(design.values[i, a] + offset) / scale:.10g} '
                     f'({offset / scale:+.6g})')
    for t, before, after in zip(targets.targets, result.before.errors, result.after.errors):
        lines.append(f'Target {t.quantity}: largest error {np.max(np.abs(before)):.6g} -> '
                     f'{np.max(np.abs(after)):.6g}')
    if any(e.mount.kind == 'link' for e in design.scene.elements):
        lines.append('Springs and dampers on a link keep their fraction of the link.')
    if 'static' in design.data.get('carrier', {}):
        lines.append('carrier.static: kept unless the wheel centre or the spin axis point '
                     'moved (then spin_axis_point is written).')
    if 'reference' in design.data:
        lines.append('The reference table of the original scene is left out: it holds for '
                     'the original design only.')
    return lines


def write_fitted(path: str, targets, result) -> None:
    """
    Write the fitted scene to path whole, its text checked to load first (SceneError).

    The text, not the file, is loaded: a device (-o /dev/null) is written in place and does
    not read back.
    """
    data = scene_data_with(targets.design, result.hardpoints)
    data['name'] = f'{targets.design.scene.name}_fitted'
    text = ''.join(f'# {line}\n' for line in header(targets, result))
    text += yaml.dump(data, Dumper=_Dumper, sort_keys=False, allow_unicode=True, width=99)
    parse_scene(parse_yaml(text, path), source=str(path))   # as load_scene would load it
    with whole_file(path) as stream:
        stream.write(text)
