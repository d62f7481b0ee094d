# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A scene -> Chrono::Vehicle suspension JSON: the template of its topology, its points replaced.

Two arms and a link go out as DoubleWishbone, an arm, a link and a strut as MacPhersonStrut,
an arm and three links (one of them steered) as MultiLink; any other topology (the five-link
5S among them) as GenericWheeledSuspension (generic.py). The fields that are not
kinematic (masses, inertias, radii, curves) come from --like ORIGINAL.json, kept as they are,
or else from the bundled generic file of the template (config/chrono/generic/suspension).
Points in m, left side (a right scene is mirrored), camber and toe from the design spin axis.
"""

from __future__ import annotations

import copy
import math

import numpy as np

from .bushings import bushing_data, named_misfit, SPRING_NAME
from .names import body_name
from .parts import length_stops
from .reader import ChronoError, read_chrono
from .templates import GENERIC, TEMPLATES
from ..core.base import camber_toe, M_PER_MM, MM_PER_M, unit


def export_scene(scene, original: dict | None = None, like: str = '',
                 damping: dict | None = None, names: dict | None = None
                 ) -> tuple[dict, str, list]:
    """
    Return (Chrono JSON object, template, notes) of a scene; original: the --like file's object.

    damping: {element name: N s/m}, the elements' x_damping; names: {'constraints': {name:
    Chrono's name}, 'elements': {...}}, their x_chrono_name (the scene keeps no free keys).
    Notes (one line each) say what was kept from the template's default file.
    """
    from ..core.model import mirror
    if scene.side == 'right':
        scene = mirror(scene)
    template, parts = match(scene, original.get('Template') if original else None, like)
    notes = []
    if template != GENERIC:
        template = _bushings_fit(scene, template, parts, like, notes)
    if template == GENERIC:
        data = _generic(scene, original, damping or {}, notes, names or {})
    else:
        data = copy.deepcopy(original) if original else _default(template)
        _named(scene, data, template, parts, original is None, notes)
    data['Name'] = data.get('Name', scene.name) if original else scene.name
    for key, angle in zip(('Camber Angle (deg)', 'Toe Angle (deg)'), design_angles(scene)):
        if key in data or angle != 0.0:   # an original without the key has them 0
            data[key] = data[key] if abs(data.get(key, math.nan) - angle) < 1e-9 else angle
    _put(data.setdefault('Spindle', {}), 'COM', scene.wheel_center)
    return data, template, notes


def match(scene, wanted: str | None, like: str) -> tuple[str, dict]:
    """Return (template, {part name: constraint}) for the scene's topology."""
    circles = sorted((c for c in scene.constraints if c.type == 'circle'),
                     key=lambda c: -c.carrier[2])   # the upper arm first
    spheres = [c for c in scene.constraints if c.type == 'sphere']
    lines = [c for c in scene.constraints if c.type == 'line']
    steered = [c for c in spheres if c.steer == 'rack']
    found, parts = GENERIC, {}
    shape = (len(circles), len(spheres), len(lines))
    if shape == (2, 1, 0):
        found = 'DoubleWishbone' if wanted != 'DoubleWishboneReduced' else wanted
        parts = {'UpperControlArm': circles[0], 'LowerControlArm': circles[1],
                 'Tierod': spheres[0]}
    elif shape == (1, 1, 1):
        found = 'MacPhersonStrut'
        parts = {'ControlArm': circles[0], 'Tierod': spheres[0], 'Strut': lines[0]}
    elif shape == (1, 3, 0) and len(steered) == 1:
        found = 'MultiLink'
        rest = sorted((c for c in spheres if c is not steered[0]),
                      key=lambda c: -abs(c.carrier[1] - c.base[0][1]))   # the lateral first
        parts = {'UpperArm': circles[0], 'Lateral': rest[0], 'TrailingLink': rest[1],
                 'Tierod': steered[0]}
    if wanted is not None and wanted != found and wanted != GENERIC:
        raise ChronoError(like, f'its template {wanted} does not fit the scene {scene.name} '
                          f'({shape[0]} arms, {shape[1]} links, {shape[2]} struts: {found})')
    return (GENERIC if wanted == GENERIC else found), parts


def _bushings_fit(scene, template, parts, like, notes) -> str:
    """
    Return the template that holds every bushing of the scene: template, or else GENERIC.

    A bushing a named template cannot hold (bushings.named_misfit) sends the scene to
    GenericWheeledSuspension with a note; with --like of a named template, or a strut (which
    only MacPhersonStrut has), it is refused, naming the bushing: never dropped.
    """
    misfits = [(c.name, why) for c in parts.values() for why in (named_misfit(c),) if why]
    if not misfits:
        return template
    name, why = misfits[0]
    if like or any(c.type == 'line' for c in scene.constraints):
        raise ChronoError(like or scene.source, f'{name}: its bushing cannot go into a '
                          f'{template} file: {why}' + (
                              '; without --like it goes out as GenericWheeledSuspension'
                              if like else '; a strut goes out only as MacPhersonStrut'))
    notes.append(f'not {template}, which cannot hold '
                 + ', '.join(f"{n}'s bushing ({w})" for n, w in misfits))
    return GENERIC


def design_angles(scene) -> tuple[float, float]:
    """Return Chrono's (camber, toe) deg of the design spin axis (left side; model/scene.py)."""
    camber, toe = camber_toe(unit(scene.wheel_center - scene.spin_axis_point), 1.0)
    return math.degrees(camber), math.degrees(toe)


def _named(scene, data, template, parts, fresh, notes):
    spec = TEMPLATES[template]
    for part in spec.parts:
        c = parts[part.name]
        obj = data.setdefault(part.key, {})
        if part.kind == 'arm':
            _put(obj, 'Location Chassis Front', c.base[0])
            _put(obj, 'Location Chassis Back', c.base[1])
        else:
            _put(obj, 'Location Chassis', c.base[0])
        _put(obj, 'Location Upright', c.carrier)
        if part.kind == 'arm':
            _arm_bushing(obj, c, notes)
        elif fresh:
            obj.pop('Bushing Data', None)   # the template file's (none has one)
    for tsda in spec.tsdas:
        e = element_for(scene, tsda, parts)
        if tsda.key not in data:
            continue
        if e is None and not fresh:
            notes.append(f'"{tsda.key}": the scene has no element for it: the original\'s kept')
            continue
        if e is None:   # Chrono needs one: a spring or damper that holds nothing
            _idle(data[tsda.key], tsda, parts, scene,
                  keep_points=any(part.key == tsda.key for part in spec.parts))
            notes.append(f'"{tsda.key}": the scene has none: one that holds nothing is written '
                         '(Chrono needs it; it imports as an element that holds nothing)')
            continue
        _put(data[tsda.key], 'Location Chassis', e.body)
        _put(data[tsda.key], tsda.point, e.mount.point)
        if fresh and e.type == 'spring' and not e.has_rate:   # a length only: no force
            _idle(data[tsda.key], tsda, parts, scene, keep_points=True)
        elif fresh and e.type == 'spring':
            for key in ('Spring Coefficient', 'Spring Curve Data', 'Minimum Length',
                        'Maximum Length'):   # the template file's, of another spring
                data[tsda.key].pop(key, None)
            data[tsda.key].update(_spring_fields(e), **length_stops(scene.elements)[0].get(
                e.name, {}))


def _arm_bushing(obj: dict, c, notes: list) -> None:
    """Write an arm's bushing into its named template object (see _bushing_merged)."""
    _bushing_merged(obj, bushing_data(c) if c.bushing is not None else None, c.name, notes)


def _bushing_merged(obj: dict, new: dict | None, name: str, notes: list) -> None:
    """
    Put our "Bushing Data" (None: a rigid joint) into obj, an original's damping kept.

    An original's stiffness that ours equals (to 1e-12: N/m -> N/mm and back) is kept as
    it is; a joint the scene has rigid takes an original's bushing out, with a note.
    """
    old = obj.get('Bushing Data')
    if new is None:
        if old is not None:
            obj.pop('Bushing Data')
            notes.append(f'{name}: the original\'s "Bushing Data" is taken out: the scene\'s '
                         'joint is rigid')
        return
    if not isinstance(old, dict):
        obj['Bushing Data'] = new
        return
    for key in ('Stiffness Linear', 'Stiffness Rotational'):
        old[key] = _kept(old.get(key), new[key])
    dof = old.setdefault('DOF', dict(new['DOF']))
    if isinstance(dof, dict):
        dof['Stiffness Rotational'] = _kept(dof.get('Stiffness Rotational'),
                                            new['DOF']['Stiffness Rotational'])
    else:
        old['DOF'] = new['DOF']


def _kept(old, new: float) -> float:
    """Return old if it is a number within 1e-12 relative of new, else new."""
    same = isinstance(old, (int, float)) and not isinstance(old, bool) \
        and abs(old - new) <= 1e-12 * max(abs(old), abs(new))
    return old if same else new


def _idle(obj: dict, tsda, parts, scene, keep_points: bool) -> None:
    """
    Make a template's spring or shock one that holds nothing: rate or damping 0, no preload.

    keep_points: its points are written already (a strut's own, MacPhersonStrut's "Spring",
    or an element's); else its moving point on its part (or the wheel centre) and IDLE_M
    straight above it on the chassis.
    """
    for key in FORCE_KEYS:
        obj.pop(key, None)
    if not keep_points:
        end = parts[tsda.on].carrier if tsda.on else scene.wheel_center
        point = [float(v) / MM_PER_M for v in end]
        obj.update({'Location Chassis': point[:2] + [point[2] + IDLE_M], tsda.point: point})
    if tsda.key == 'Spring':
        length = np.linalg.norm(np.subtract(obj['Location Chassis'], obj[tsda.point]))
        obj.update({'Free Length': float(length), 'Spring Coefficient': 0.0})
    else:
        obj['Damping Coefficient'] = 0.0


IDLE_M = 0.1   # an idle spring's or shock's length (m), straight up from its moving point
# the keys of a Chrono TSDA's force (ReadTSDAFunctorJSON)
FORCE_KEYS = ('Spring Coefficient', 'Spring Curve Data', 'Damping Coefficient',
              'Damping Curve Data', 'Map Data', 'Free Length', 'Preload', 'Minimum Length',
              'Maximum Length', 'Degressivity Compression', 'Degressivity Expansion')


def element_for(scene, tsda, parts):
    """Return the scene's element for a template's spring or shock (by name, else by role)."""
    names = {e.name: e for e in scene.elements}
    for name in (tsda.key, f'{tsda.key}Spring', f'{tsda.key}Damper'):
        if name in names:
            return names[name]
    on = parts[tsda.on].name if tsda.on else ''
    kind = 'spring' if tsda.key == 'Spring' else 'damper'
    for e in scene.elements:
        where = scene.constraints[e.mount.constraint].name if e.mount.constraint >= 0 else ''
        if e.type == kind and not e.is_stop and (where == on or e.mount.kind == 'along'):
            return e
    return None


def _spring_fields(e) -> dict:
    """Return a Chrono spring's fields of a spring element (N/m, m; a curve in Chrono's sign)."""
    if e.force_table is not None:
        return {'Free Length': e.free_length * M_PER_MM,
                'Spring Curve Data': [[-d * M_PER_MM, -f] for d, f in e.force_table[::-1]]}
    return {'Free Length': e.free_length * M_PER_MM, 'Spring Coefficient': e.rate / M_PER_MM}


def _generic(scene, original, damping, notes, names):
    from .generic import generic_of
    mounted = {scene.constraints[e.mount.constraint].name for e in scene.elements
               if e.mount.kind == 'link'}
    data = {'Name': scene.name, 'Type': 'Suspension', 'Template': GENERIC}
    like = original if original and original.get('Template') == GENERIC else None
    if like:
        data.update({k: copy.deepcopy(v) for k, v in like.items() if k not in KINEMATIC})
    data.setdefault('Spindle', {'Mass': 14.705, 'Inertia': [0.04117, 0.07352, 0.04117],
                                'Radius': 0.1, 'Width': 0.06})
    upright = data['Spindle'].setdefault('Attachment Body', 'Upright')
    limits, folded = length_stops(scene.elements)
    tsdas = [{**t, **limits.get(e.name, {})} for e, t in
             ((e, tsda_of(scene, e, damping.get(e.name), upright)) for e in scene.elements
              if e.name not in folded) if t is not None]
    fresh = _chrono_names(generic_of(scene, mounted, tsdas, notes, upright), names)
    if like:   # each of ours on its namesake: the original's fields, our kinematic ones
        fresh = {key: _merged(value, like.get(key), KINEMATIC.get(key, ()), notes)
                 if isinstance(value, list) else like.get(key, value)
                 for key, value in fresh.items()}
    data.update(fresh)
    data.setdefault('Axle', {'Inertia': 0.4})
    return data


def _chrono_names(data: dict, names: dict) -> dict:
    """Give the bodies, links and springs of data back the Chrono names they were imported by."""
    bodies, springs = names.get('constraints', {}), names.get('elements', {})

    def body(name):
        return bodies.get(name, name) if isinstance(name, str) else name

    for key in ('Bodies', 'Joints', 'Distance Constraints', 'TSDAs'):
        for item in data.get(key, []):
            for end in ('Body1', 'Body2'):
                if end in item:
                    item[end] = body(item[end])
            match = SPRING_NAME.match(item['Name'])
            if key == 'TSDAs' and match:   # a bushing's spring: its body's name
                item['Name'] = f'{body(match["body"])}{item["Name"][len(match["body"]):]}'
            elif key == 'TSDAs':
                item['Name'] = springs.get(item['Name'], item['Name'])
            elif key != 'Joints':
                item['Name'] = body(item['Name'])
    data['Antiroll Body'] = body(data.get('Antiroll Body'))
    return data


# GenericWheeledSuspension's lists and the keys of their objects that are kinematic (a body's
# Position is its centre of mass: not kinematic here)
KINEMATIC = {'Bodies': (), 'Joints': ('Type', 'Body1', 'Body2', 'Position', 'Rotation'),
             'Distance Constraints': ('Body1', 'Body2', 'Point1', 'Point2'),
             'TSDAs': ('Body1', 'Body2', 'Point1', 'Point2')}


def _merged(ours: list, theirs, keys: tuple, notes: list) -> list:
    """
    Return ours, each object on its namesake in theirs with only keys taken from ours.

    A joint's "Bushing Data" is the scene's (bushing_merged); a bushing's spring is ours.
    """
    from .generic import same_axis
    theirs = [o for o in theirs or [] if isinstance(o, dict)]
    by_name = {o.get('Name'): o for o in theirs}
    out = []
    for item in ours:
        old = by_name.get(item['Name'])
        if old is None and 'Type' in keys:   # a joint: the original's between the same bodies
            old = _joint_between(item, theirs, out)
        if old is None or SPRING_NAME.match(item['Name']):
            out.append(item)
            continue
        merged = copy.deepcopy(old)
        for key in keys:
            if key == 'Rotation' and same_axis(old.get(key), item[key]):
                continue   # a revolute's frame: only its z axis matters
            if key in item:
                _put(merged, key, item[key], scale=1.0)
        if 'Type' in keys:   # a joint
            _bushing_merged(merged, item.get('Bushing Data'), item['Name'], notes)
        out.append(merged)
    return out


def _joint_between(ours: dict, theirs: list, done: list) -> dict | None:
    """Return the first of theirs of our joint's type between its two bodies, not yet used."""
    used = {id(o) for o in done} | {o.get('Name') for o in done}
    ends = {ours['Body1'], ours['Body2']}
    for old in theirs:
        try:
            same = {body_name(old.get('Body1')), body_name(old.get('Body2'))} == ends
        except ChronoError:
            continue
        if same and old.get('Type') == ours['Type'] and old.get('Name') not in used:
            return old
    return None


def _put(obj: dict, key: str, value, scale: float = 1.0 / MM_PER_M) -> None:
    """
    Set obj[key] to value (a point mm -> m, or as given), keeping the original's if equal.

    An unmoved point read from a file and written back is the file's own number, byte for
    byte: mm -> m and back may differ in the last bit.
    """
    new = [float(v) * scale for v in value] if isinstance(value, (list, tuple, np.ndarray)) \
        else value
    old = obj.get(key)
    if isinstance(new, list) and isinstance(old, list) and len(old) == len(new) and all(
            isinstance(v, (int, float)) and abs(v - w) <= 1e-12 for v, w in zip(old, new)):
        return
    if new != old:
        obj[key] = new


def tsda_of(scene, e, damping: float | None = None, upright: str = 'Upright') -> dict | None:
    """Return a GenericWheeledSuspension TSDA of an element (None: a plain length)."""
    on = upright if e.mount.kind in ('carrier', 'along') else \
        scene.constraints[e.mount.constraint].name
    out = {'Name': e.name, 'Mirrored': True, 'Body1': 'Chassis', 'Body2': on,
           'Point1': _m(e.body), 'Point2': _m(e.mount.point)}
    if e.type == 'spring' and e.has_rate:
        out.update(_spring_fields(e))
    if e.type == 'damper':
        out['Damping Coefficient'] = float(damping or 0.0)   # N s/m
    return out if len(out) > 6 else None


def _default(template: str) -> dict:
    from ..core.model import config_dir
    return read_chrono(config_dir() / 'chrono' / 'generic' / 'suspension' / f'{template}.json')


def _m(point) -> list:
    return [float(v) / MM_PER_M for v in point]   # mm -> m, correctly rounded
