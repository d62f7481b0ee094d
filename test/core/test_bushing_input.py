# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Bushings in scene files: read in N/mm, checked, refused in one line naming the field."""

import math
from pathlib import Path
import subprocess
import sys

from linkage_ros.core.base import Status
from linkage_ros.core.model import load_scene, mirror, SceneError, translate
from linkage_ros.tools.sweep import main
import pytest
import yaml

ARM = {'axial': 1500, 'radial': 6000, 'torsion': 0.5}
LINK = {'axial': 3000, 'radial': 3000}


def scene_with(tmp_path, bushings, base='double_wishbone', units=None):
    """Write the bundled base scene with exactly the bushings {constraint name: mapping}."""
    data = yaml.safe_load(Path(load_scene(base).source).read_text())
    for item in data['constraints']:
        item.pop('bushing', None)
        if item['name'] in bushings:
            item['bushing'] = bushings[item['name']]
    path = tmp_path / 'scene.yaml'
    path.write_text(yaml.safe_dump(data))
    return str(path)


def test_bushing_rates_are_read_in_n_per_mm_and_n_m_per_deg(tmp_path):
    scene = load_scene(scene_with(tmp_path, {'lower_arm': ARM, 'tie_rod': LINK}))
    arm, link = scene.constraints[1].bushing, scene.constraints[2].bushing
    assert (arm.axial, arm.radial, arm.torsion, arm.conical, arm.at) == (
        1500.0, 6000.0, 0.5, 0.0, 'pivots')
    assert (link.axial, link.radial) == (3000.0, 3000.0)
    assert scene.constraints[0].bushing is None and scene.has_bushings


def test_bushing_rates_of_a_metre_scene_are_converted_to_n_per_mm(tmp_path):
    data = yaml.safe_load(Path(load_scene('chrono_generic_doublewishbone').source).read_text())
    assert data['units'] == 'm'
    name = next(c['name'] for c in data['constraints'] if c['type'] == 'circle')
    for item in data['constraints']:
        if item['name'] == name:
            item['bushing'] = {'axial': 1.5e6, 'radial': 6e6, 'torsion': 0.5}
    path = tmp_path / 'm.yaml'
    path.write_text(yaml.safe_dump(data))
    bushing = next(c.bushing for c in load_scene(str(path)).constraints if c.name == name)
    assert (bushing.axial, bushing.radial, bushing.torsion) == (1500.0, 6000.0, 0.5)


def test_a_scene_without_bushings_has_none(tmp_path):
    scene = load_scene('macpherson')
    assert not scene.has_bushings
    assert all(c.bushing is None for c in scene.constraints)


def test_mirror_and_translate_keep_the_bushings(tmp_path):
    scene = load_scene(scene_with(tmp_path, {'lower_arm': ARM}))
    for moved in (mirror(scene), translate(scene, (1.0, 2.0, 3.0))):
        assert moved.constraints[1].bushing == scene.constraints[1].bushing


def test_loading_a_bushing_free_scene_leaves_statics_unimported():
    code = ('import sys; from linkage_ros.core.model import load_scene; '
            "from linkage_ros.core.solve import sweep; s = load_scene('macpherson'); "
            'sweep(s, [0.0, 10.0]); '
            "print(sorted(m for m in sys.modules if 'statics' in m or 'bushing' in m))")
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == '[]'


BAD = [
    ({'lower_arm': {**ARM, 'axial': 0}}, 'constraints[1] (lower_arm).bushing.axial: 0 N/mm '
     'is outside 0.001 to 1e+11 N/mm (doc/scenes.md#ranges)'),
    ({'lower_arm': {**ARM, 'radial': -5.0}}, 'constraints[1] (lower_arm).bushing.radial: '
     '-5.0 N/mm is outside 0.001 to 1e+11 N/mm'),
    ({'lower_arm': {**ARM, 'radial': math.nan}}, 'constraints[1] (lower_arm).bushing.radial: '
     'must be finite, got nan'),
    ({'lower_arm': {**ARM, 'axial': math.inf}}, 'constraints[1] (lower_arm).bushing.axial: '
     'must be finite, got inf'),
    ({'lower_arm': {**ARM, 'torsion': -0.1}}, 'constraints[1] (lower_arm).bushing.torsion: '
     '-0.1 N m/deg is outside 0, or 0.001 to 1e+10 N m/deg'),
    ({'lower_arm': {**ARM, 'conical': math.inf}}, 'constraints[1] (lower_arm).bushing.conical: '
     'must be finite, got inf'),
    ({'lower_arm': {'radial': 10}}, 'constraints[1] (lower_arm).bushing.axial: missing'),
    ({'lower_arm': {**ARM, 'at': 'middle'}}, ('constraints[1] (lower_arm).bushing.at: unknown '
                                              "value 'middle' (expected one of: pivots, centre)")),
    ({'lower_arm': {**ARM, 'axail': 3}}, 'constraints[1] (lower_arm).bushing.axail: unknown '
     'key (did you mean axial?)'),
    ({'tie_rod': {**LINK, 'torsion': 1.0}}, 'constraints[2] (tie_rod).bushing.torsion: only '
     'an arm (circle) takes it'),
    ({'lower_arm': [1500, 6000]}, 'constraints[1] (lower_arm).bushing: expected a mapping'),
]


@pytest.mark.parametrize('bushings, said', BAD)
def test_a_bad_bushing_is_one_line_naming_file_constraint_and_field(tmp_path, capsys,
                                                                    bushings, said):
    path = scene_with(tmp_path, bushings)
    with pytest.raises(SceneError) as info:
        load_scene(path)
    assert path in str(info.value) and said in str(info.value)
    assert main([path, '--travel', '0:10:10']) == 2
    out, err = capsys.readouterr()
    assert out == '' and len(err.splitlines()) == 1 and said in err


def test_a_bushing_on_a_strut_line_is_refused(tmp_path):
    data = yaml.safe_load(Path(load_scene('macpherson').source).read_text())
    strut = next(c for c in data['constraints'] if c['type'] == 'line')
    strut['bushing'] = dict(LINK)
    path = tmp_path / 'strut.yaml'
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(SceneError, match=r'\(%s\)\.bushing: a line takes no bushing'
                       % strut['name']):
        load_scene(str(path))


def test_status_not_carried_is_seven():
    assert Status.NOT_CARRIED == 7 and Status.NOT_CARRIED.phrase == 'not carried'
