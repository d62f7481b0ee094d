# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The files of linkage-chrono: a Chrono file in, the scene (or vehicle) text out, checked.

Every text is made and checked whole before anything is written: the scene must load
(model/scene.py) and solve at design travel, or the import is a ChronoError, one line.
"""

from __future__ import annotations

import os
from pathlib import Path

import yaml

from .importer import import_suspension
from .names import KEEP
from .needs import check_chrono
from .reader import ChronoError, Fields, read_chrono
from .templates import WHEEL_RADIUS_M
from .writer import json_text, scene_text

LICENCE = ('Chrono::Vehicle data: Project Chrono (BSD-3-Clause, projectchrono/chrono); '
           'keep its attribution')


def import_file(source: str, output: str, wheel_radius: float | None = None):
    """Return ({path: text} to write, a one-line summary) for a suspension or vehicle file."""
    data = read_chrono(source)
    if data.get('Type') == 'Vehicle':
        return import_vehicle(data, source, output, wheel_radius)
    text, imported = scene_of(data, source, output, wheel_radius)
    return {output: text}, (f'{imported.template} {source}: {len(imported.scene["constraints"])}'
                            f' constraints, {len(imported.scene.get("elements", []))} elements'
                            f' -> {output}' + ''.join(f'; {n}' for n in imported.notes))


def inputs_of(source: str) -> list[str]:
    """Return the files an import of source reads: it and, for a vehicle, its suspensions."""
    data = read_chrono(source)
    if data.get('Type') != 'Vehicle':
        return [source]
    top = Fields(source, data)
    return [source] + [str(data_file(source, axle.text('Suspension Input File')))
                       for axle in top.objects('Axles')]


def scene_of(data: dict, source: str, output: str, wheel_radius: float | None = None,
             name: str = '', steered: bool = True):
    """Return (scene text, Imported) of a suspension file's object, loaded and solved."""
    radius = WHEEL_RADIUS_M if wheel_radius is None else wheel_radius
    if not radius > 0:
        raise ChronoError('--wheel-radius', f'must be a positive number of metres, got {radius}')
    imported = import_suspension(data, source, radius, name or Path(output).stem, steered)
    header = [f'Chrono::Vehicle {imported.template} imported by linkage-chrono from {source}',
              LICENCE + '.',
              "Chrono's suspension frame: ISO axes (x forward, y left, z up), left side, m.",
              'Not imported (kept in the JSON, for linkage-chrono export --like): masses, '
              'inertias, radii, visualisation.'] + [f'Note: {n}' for n in imported.notes]
    text = scene_text(imported.scene, header)
    check_scene(text, output)
    return text, imported


def check_scene(text: str, where: str):
    """Load a scene text and solve it at design travel; raise a LinkageError if either fails."""
    from ..core import Continuation
    from ..core.model import parse_scene
    scene = parse_scene(yaml.safe_load(text), source=where)
    solution = Continuation(scene).solve(0.0)
    if not solution.success:
        raise ChronoError(where, f'the imported scene does not solve at design travel: '
                          f'{solution.message}')
    return scene


def import_vehicle(data: dict, source: str, output: str, wheel_radius: float | None):
    """Return ({path: text}, summary): each axle's scene beside output, and the vehicle."""
    top = Fields(source, data)
    out = Path(output)
    texts, corners, xs = {}, {}, []
    names = ('front', 'rear') if len(top.objects('Axles')) == 2 else None
    for i, axle in enumerate(top.objects('Axles')):
        sub = data_file(source, axle.text('Suspension Input File'))
        where = axle.vector('Suspension Location')
        name = names[i] if names else f'axle{i}'
        path = out.with_name(f'{out.stem}_{name}.yaml')
        text, _ = scene_of(read_chrono(sub), str(sub), str(path), wheel_radius, path.stem,
                           steered=axle.has('Steering Index'))
        texts[str(path)] = text
        xs.append(where[0])
        for side, mirror in (('left', False), ('right', True)):
            corners[f'{name}_{side}'] = {'scene': path.name, 'offset': [float(v) for v in where],
                                         **({'mirror': True} if mirror else {})}
    if not corners:
        raise ChronoError(source, '"Axles": none: no suspension to import')
    vehicle = {'name': out.stem, 'units': 'm', 'corners': corners}
    if names:
        vehicle['wheelbase'] = float(xs[0] - xs[1])   # from the axle locations
        vehicle['axles'] = {n: {'left': f'{n}_left', 'right': f'{n}_right'} for n in names}
    header = [f'Chrono::Vehicle {top.text("Name") if top.has("Name") else ""} imported by '
              f'linkage-chrono from {source}', LICENCE + '.',
              'Offsets: Chrono\'s "Suspension Location" (m); right corners mirror the left.']
    texts[output] = scene_text(vehicle, header)
    return texts, f'vehicle {source}: {len(corners)} corners -> {output}'


def data_file(vehicle: str, name: str) -> Path:
    """
    Find a file a vehicle names as Chrono does: under its data folder (vehicle::GetDataFile).

    Chrono reads "hmmwv/suspension/X.json" as <data>/vehicle/hmmwv/suspension/X.json; here
    <data>/vehicle is the nearest of the DATA_LEVELS folders above the vehicle file that holds
    the name (Chrono's layout <data>/vehicle/hmmwv/vehicle/V.json: the third). A name
    that is empty, absolute, has a NUL, or climbs out of that folder ("../../etc/passwd", or
    a symbolic link that leads out) is refused, never opened.
    """
    what = f'"Suspension Input File" {name[:80]!r}'
    if not name or '\0' in name or name.startswith(('/', '\\')) or Path(name).is_absolute():
        raise ChronoError(vehicle, f"{what}: expected a name relative to Chrono's data folder "
                          '(vehicle::GetDataFile), e.g. "hmmwv/suspension/X.json"')
    if os.path.normpath(name).split(os.sep)[0] == '..':
        raise ChronoError(vehicle, f"{what}: leaves Chrono's data folder: refused")
    for folder in Path(vehicle).resolve().parents[:DATA_LEVELS]:
        candidate = folder / name
        try:
            found = candidate.is_file()
            inside = candidate.resolve().is_relative_to(folder)
        except (OSError, RuntimeError):   # a name too long, a loop of links
            continue
        if found and not inside:
            raise ChronoError(vehicle, f"{what}: leads out of Chrono's data folder {folder} "
                              '(a symbolic link): refused')
        if found:
            return candidate
    raise ChronoError(vehicle, f'{what}: not found in the {DATA_LEVELS} folders above the '
                      'vehicle file (Chrono reads it from its data/vehicle folder)')


DATA_LEVELS = 4   # folders above a vehicle file where its data folder may be


def export_file(scene_ref: str, like: str | None = None):
    """Return (Chrono JSON text, summary) of a scene, keeping an original's other fields."""
    from .exporter import export_scene
    from ..core import load_scene
    from ..core.model import resolve_scene_path
    scene = load_scene(scene_ref)
    raw = yaml.safe_load(resolve_scene_path(scene_ref).read_text(encoding='utf-8'))
    damping = {item.get('name'): item.get('x_damping') for item in raw.get('elements') or []
               if isinstance(item, dict) and isinstance(item.get('x_damping'), (int, float))}
    names = {key: {item.get('name'): item[KEEP] for item in raw.get(key) or []
                   if isinstance(item, dict) and isinstance(item.get(KEEP), str)}
             for key in ('constraints', 'elements')}   # Chrono's names of an imported scene
    original = read_chrono(like) if like else None
    if original is not None:
        check_chrono(original, like)   # a suspension file Chrono reads, else refused
    data, template, notes = export_scene(scene, original, like or '', damping, names)
    check_chrono(data, like or scene_ref)   # what is written is a file Chrono reads
    return json_text(data), f'{scene.name}: {template}' + ''.join(f'; {n}' for n in notes)
