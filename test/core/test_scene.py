# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Scene loading: every malformed scene fails with one SceneError naming file, field, problem."""

import copy
from pathlib import Path

from linkage_ros.core.model import (bundled_scenes, KingpinPoint, load_scene, mirror,
                                    SceneError)
import numpy as np
import pytest
import yaml

VALID = {
    'name': 'probe',
    'units': 'mm',
    'side': 'left',
    'carrier': {'wheel_center': [0.0, 760.0, 300.0], 'spin_axis_point': [0.0, 660.0, 300.0]},
    'constraints': [
        {'name': 'upper_front', 'type': 'sphere',
         'base': [80, 350, 450], 'carrier': [15, 640, 485]},
        {'name': 'upper_rear', 'type': 'sphere',
         'base': [-120, 360, 440], 'carrier': [-15, 635, 475]},
        {'name': 'lower_front', 'type': 'sphere',
         'base': [150, 250, 180], 'carrier': [25, 700, 160]},
        {'name': 'lower_rear', 'type': 'sphere',
         'base': [-150, 250, 185], 'carrier': [-10, 695, 162]},
        {'name': 'tie_rod', 'type': 'sphere',
         'base': [-150, 300, 250], 'carrier': [-140, 690, 260]},
    ],
    'travel': {'min': -80, 'max': 80, 'step': 1},
}


def write(tmp_path, data, text=None):
    path = tmp_path / 'scene.yaml'
    path.write_text(text if text is not None else yaml.safe_dump(data))
    return path


def load_broken(tmp_path, edit):
    data = copy.deepcopy(VALID)
    edit(data)
    path = write(tmp_path, data)
    with pytest.raises(SceneError) as info:
        load_scene(path)
    assert str(path) in str(info.value), 'the error names the file'
    return info.value


def test_bundled_scenes_include_the_three_required():
    assert {'five_link', 'double_wishbone', 'macpherson'} <= set(bundled_scenes())


@pytest.mark.parametrize('name', ['five_link', 'double_wishbone', 'macpherson'])
def test_bundled_scene_loads_in_mm(name):
    scene = load_scene(name)
    assert sum(c.equations for c in scene.constraints) == 5
    assert np.linalg.norm(scene.wheel_center - scene.spin_axis_point) == pytest.approx(100.0)


def test_metre_scene_is_converted_to_mm():
    scene = load_scene('macpherson')   # units: m in the file
    assert scene.wheel_center == pytest.approx([-40.00403, 1099.99965, -26.02507])
    assert scene.travel == pytest.approx((-80.0, 80.0, 1.0))


def test_valid_probe_scene_loads(tmp_path):
    assert load_scene(write(tmp_path, VALID)).name == 'probe'


def test_missing_key_is_named(tmp_path):
    err = load_broken(tmp_path, lambda d: d['carrier'].pop('wheel_center'))
    assert err.field == 'carrier.wheel_center' and 'missing' in err.problem


def test_point_of_wrong_length_is_named(tmp_path):
    err = load_broken(tmp_path, lambda d: d['constraints'][2].update(base=[1.0, 2.0]))
    assert err.field == 'constraints[2] (lower_front).base'
    assert 'expected 3 coordinates' in err.problem


def test_non_numeric_coordinate_is_named(tmp_path):
    err = load_broken(tmp_path, lambda d: d['constraints'][0].update(carrier=[15, 'x', 485]))
    assert err.field == 'constraints[0] (upper_front).carrier' and "'x'" in err.problem


def test_non_finite_coordinate_is_refused(tmp_path):
    err = load_broken(tmp_path, lambda d: d['carrier'].update(wheel_center=[0, float('nan'), 1]))
    assert err.field == 'carrier.wheel_center' and 'not finite' in err.problem


def test_a_coordinate_too_large_for_millimetre_precision_is_refused(tmp_path):
    # 1e306 m once overflowed to inf when scaled to mm and was reported as coincident points
    err = load_broken(tmp_path, lambda d: d.update(units='m') or d['constraints'][0].update(
        base=[1e306, 0.35, 0.45]))
    assert err.field == 'constraints[0] (upper_front).base'
    assert 'beyond 1e+12 mm' in err.problem


def test_a_travel_too_large_for_millimetre_precision_is_refused(tmp_path):
    err = load_broken(tmp_path, lambda d: d['travel'].update(max=2e12))
    assert err.field == 'travel.max' and 'beyond 1e+12 mm' in err.problem


def test_unknown_constraint_type_is_named(tmp_path):
    err = load_broken(tmp_path, lambda d: d['constraints'][4].update(type='cylinder'))
    assert err.field == 'constraints[4] (tie_rod).type' and "'cylinder'" in err.problem


def test_unknown_unit_is_named(tmp_path):
    err = load_broken(tmp_path, lambda d: d.update(units='inch'))
    assert err.field == 'units' and "'inch'" in err.problem and 'mm, m' in err.problem


def test_unknown_side_is_named(tmp_path):
    err = load_broken(tmp_path, lambda d: d.update(side='middle'))
    assert err.field == 'side'


def test_coincident_spin_axis_points_are_refused(tmp_path):
    err = load_broken(tmp_path, lambda d: d['carrier'].update(spin_axis_point=[0, 760, 300]))
    assert err.field == 'carrier.spin_axis_point' and 'coincides' in err.problem


def test_collinear_third_point_is_refused(tmp_path):
    err = load_broken(tmp_path, lambda d: d['carrier'].update(third_point=[0, 500, 300]))
    assert err.field == 'carrier.third_point' and 'collinear' in err.problem


def test_third_point_too_close_to_the_spin_axis_is_a_thin_triangle(tmp_path):
    err = load_broken(tmp_path, lambda d: d['carrier'].update(third_point=[0, 700, 300.01]))
    assert err.field == 'carrier.third_point' and 'too thin to define a frame' in err.problem


def test_zero_length_link_is_refused(tmp_path):
    err = load_broken(tmp_path, lambda d: d['constraints'][1].update(base=[-15, 635, 475]))
    assert err.field == 'constraints[1] (upper_rear).base' and 'zero-length link' in err.problem


def test_circle_with_coincident_axis_points_is_refused(tmp_path):
    def edit(d):
        d['constraints'][3:5] = [{'name': 'lower_arm', 'type': 'circle',
                                  'axis': [[150, 250, 180], [150, 250, 180]],
                                  'carrier': [10, 700, 160]}]
    err = load_broken(tmp_path, edit)
    assert err.field == 'constraints[3] (lower_arm).axis' and 'coincide' in err.problem


def test_circle_with_carrier_on_its_axis_is_a_zero_length_arm(tmp_path):
    def edit(d):
        d['constraints'][3:5] = [{'name': 'lower_arm', 'type': 'circle',
                                  'axis': [[150, 250, 180], [-150, 250, 180]],
                                  'carrier': [0, 250, 180]}]
    err = load_broken(tmp_path, edit)
    assert err.field == 'constraints[3] (lower_arm).carrier' and 'zero-length arm' in err.problem


def test_equation_count_other_than_five_is_refused(tmp_path):
    err = load_broken(tmp_path, lambda d: d['constraints'].pop())
    assert err.field == 'constraints' and 'give 4 equations' in err.problem


def test_joint_in_the_given_mnp_plane_is_refused(tmp_path):
    # P in the horizontal plane z = 300 through the spin axis; put a joint in that plane.
    def edit(d):
        d['carrier']['third_point'] = [100, 760, 300]
        d['constraints'][4]['carrier'] = [-140, 690, 300]
    err = load_broken(tmp_path, edit)
    assert err.field == 'carrier.third_point' and 'tie_rod' in err.problem


def test_invalid_yaml_is_reported_as_such(tmp_path):
    path = write(tmp_path, None, text='units: mm\nside: [left\n')
    with pytest.raises(SceneError, match='not valid YAML'):
        load_scene(path)


def test_unknown_scene_name_lists_the_bundled_ones():
    with pytest.raises(SceneError, match='five_link'):
        load_scene('no_such_scene')


def test_an_empty_scene_name_is_not_read_as_the_current_folder():
    # '' once became Path('.'), and the error was '.: file: cannot read (Is a directory)'
    with pytest.raises(SceneError, match="^'': scene: empty: .*bundled: .*five_link"):
        load_scene('')


def test_a_folder_is_named_as_a_folder_not_a_scene_file(tmp_path):
    with pytest.raises(SceneError, match=f'^{tmp_path}: scene: a folder, not a scene file'):
        load_scene(str(tmp_path))


def test_negative_travel_step_is_refused(tmp_path):
    err = load_broken(tmp_path, lambda d: d['travel'].update(step=-1))
    assert err.field == 'travel.step'


def test_chosen_third_point_keeps_every_joint_off_the_mnp_plane():
    scene = load_scene('five_link')
    m, n, p = scene.wheel_center, scene.spin_axis_point, scene.third_point
    normal = np.cross(n - m, p - m)
    normal /= np.linalg.norm(normal)
    clearance = min(abs((c.carrier - m) @ normal) for c in scene.constraints)
    assert clearance > 10.0   # mm; the joints of five_link are 15 mm or more off any axis plane


def test_mirror_flips_y_and_side():
    left = load_scene('double_wishbone')
    right = mirror(left)
    assert right.side == 'right'
    assert right.wheel_center == pytest.approx([0.0, -760.0, 300.0])
    assert right.constraints[0].base[:, 1] == pytest.approx(-left.constraints[0].base[:, 1])


# --- keys the format does not know ---------------------------------------------------------

@pytest.mark.parametrize('edit, field, problem', [
    (lambda d: d.update(unit=d.pop('units')), 'unit', 'unknown key (did you mean units?)'),
    (lambda d: d['carrier'].update(wheel_centre=d['carrier'].pop('wheel_center')),
     'carrier.wheel_centre', 'unknown key (did you mean wheel_center?)'),
    (lambda d: d['constraints'][1].update(cariier=d['constraints'][1].pop('carrier')),
     'constraints[1].cariier', 'unknown key (did you mean carrier?)'),
    (lambda d: d['travel'].update(stpe=d['travel'].pop('step')), 'travel.stpe',
     'unknown key (did you mean step?)')])
def test_a_misspelt_key_is_named_with_the_key_it_resembles(tmp_path, edit, field, problem):
    # the error was "units: missing (required)", naming the key the user did give
    err = load_broken(tmp_path, edit)
    assert (err.field, err.problem) == (field, problem)


def test_an_unknown_key_like_no_other_lists_the_keys_there_are(tmp_path):
    err = load_broken(tmp_path, lambda d: d.update(zzz=1))
    assert (err.field, err.problem) == ('zzz', 'unknown key (known: name, units, side, '
                                        'wheel_radius, carrier, constraints, travel, elements, '
                                        'kingpin; also allowed: description, source, notes, '
                                        'reference, x_...)')


def test_free_keys_are_kept_for_the_user_and_ignored_by_the_solver(tmp_path):
    data = copy.deepcopy(VALID)
    data.update(description='probe', source='drawing 12', notes='n', reference={'rows': []},
                x_supplier='ACME')
    data['carrier']['notes'] = 'measured at curb weight'
    data['constraints'][0].update(description='upper link', x_part='A-1')
    scene = load_scene(write(tmp_path, data))
    assert scene.description == 'probe'
    assert scene.extras == {'source': 'drawing 12', 'notes': 'n', 'reference': {'rows': []},
                            'x_supplier': 'ACME'}


def test_every_bundled_scene_uses_only_known_and_free_keys():
    for name in bundled_scenes():
        load_scene(name)   # a bundled scene with a key the format refuses would raise


def test_an_axis_on_a_sphere_is_refused_not_ignored(tmp_path):
    err = load_broken(tmp_path, lambda d: d['constraints'][0].update(axis=[[0, 0, 0]] * 2))
    assert err.field == 'constraints[0] (upper_front).axis'
    assert err.problem == 'not used by a sphere, which takes base'


def test_a_name_that_is_not_text_is_refused(tmp_path):
    err = load_broken(tmp_path, lambda d: d.update(name=[['lol'] * 3] * 3))
    assert (err.field, err.problem) == ('name', 'expected text, got list')


# --- implausible sizes: a warning, not a refusal -------------------------------------------

def test_a_scene_in_mm_labelled_m_loads_with_one_warning_that_says_why(tmp_path):
    # five_link's numbers (mm) labelled m: a corner 1520 km wide with a 330 m tyre
    data = dict(copy.deepcopy(VALID), units='m', wheel_radius=330)
    path = write(tmp_path, data)
    scene = load_scene(path)
    assert scene.wheel_center[1] == 760_000.0
    assert scene.warnings == (
        f'{path}: wheel_radius 330000 mm and half-track 760000 mm (|y| of the wheel centre) '
        'are outside 50-3000 mm, implausible for a road vehicle: a file written in mm but '
        'labelled units: m? (solved as given)',)
    assert mirror(scene).warnings == scene.warnings


def test_a_scene_in_m_labelled_mm_is_warned_of_too(tmp_path):
    data = copy.deepcopy(VALID)
    data['carrier'] = {'wheel_center': [0.0, 0.76, 0.3], 'spin_axis_point': [0.0, 0.66, 0.3]}
    for c in data['constraints']:
        c['base'] = [v / 1000 for v in c['base']]
        c['carrier'] = [v / 1000 for v in c['carrier']]
    data['travel'] = {'min': -0.08, 'max': 0.08, 'step': 0.001}
    scene = load_scene(write(tmp_path, data))
    assert len(scene.warnings) == 1
    assert 'half-track 0.76 mm (|y| of the wheel centre) is outside 50-3000 mm' \
        in scene.warnings[0]
    assert scene.warnings[0].endswith('a file written in m but labelled units: mm? (solved as '
                                      'given)')


def test_bundled_scenes_are_of_a_plausible_size_and_stress_scenes_warn_but_load():
    assert [s for s in bundled_scenes() if load_scene(s).warnings] == []
    stress = Path(__file__).resolve().parents[2] / 'config' / 'stress'
    huge = load_scene(stress / 'five_link_kilometres.yaml')
    tiny = load_scene(stress / 'five_link_submillimetre.yaml')
    assert 'wheel_radius 3.3e+06 mm and half-track 7.6e+06 mm' in huge.warnings[0]
    assert 'half-track 0.076 mm' in tiny.warnings[0]


# --- travel blocks that no sweep could hold ------------------------------------------------

def test_a_travel_step_too_small_to_sweep_is_refused_with_what_it_would_need(tmp_path):
    err = load_broken(tmp_path, lambda d: d['travel'].update(step=1e-300))
    assert err.field == 'travel.step'
    assert err.problem == ('1.6e+302 positions (from -80 to 80 mm at steps of 1e-300 mm) '
                           'would need about 1.49e+296 GiB; the limit is 1,000,000 positions '
                           '(a larger step, or a shorter range)')


# --- names and paths -----------------------------------------------------------------------

def test_a_bare_name_is_the_bundled_scene_whatever_the_current_folder_holds(
        tmp_path, monkeypatch):
    # a suffix-less file five_link here once replaced the bundled scene silently
    monkeypatch.chdir(tmp_path)
    (tmp_path / 'five_link').write_text(yaml.safe_dump(dict(VALID, name='impostor')))
    assert load_scene('five_link').name == 'five_link'
    assert load_scene('./five_link').name == 'impostor'


def test_a_bare_name_of_a_file_here_that_is_not_bundled_says_how_to_give_the_path(
        tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / 'mine').write_text(yaml.safe_dump(VALID))
    with pytest.raises(SceneError, match=r'^mine: scene: not a bundled scene \(bundled: .*\); '
                       r'a bare name means a bundled scene: for the file mine in this folder, '
                       r'give \./mine$'):
        load_scene('mine')
    assert load_scene('./mine').name == 'probe'


@pytest.mark.parametrize('name, stem', [
    ('five_link', 'five_link'), ('../escaped', 'escaped'), ('a//etc/passwd', 'a_etc_passwd'),
    ('a/../../b', 'a_.._.._b'), ('-rf', 'rf'), ('..', 'scene'), ('', 'scene'),
    ('Kurvenfahrt ÄÖÜ', 'Kurvenfahrt'), ('x' * 300, 'x' * 100)])
def test_a_scene_name_gives_a_file_stem_that_stays_in_its_folder(tmp_path, name, stem):
    data = dict(copy.deepcopy(VALID), name=name)
    scene = load_scene(write(tmp_path, data))
    assert scene.file_stem == stem
    out = tmp_path / f'{scene.file_stem}_sweep.mcap'
    assert out.resolve().parent == tmp_path.resolve()


def test_a_scenes_kingpin_key_is_kept_as_a_typed_field_of_two_joints():
    # kingpin: [UpperArm, [Lateral, TrailingLink]]: a ball joint and a virtual one (two links)
    scene = load_scene('chrono_generic_multilink')
    names = [c.name for c in scene.constraints]
    upper, lower = scene.kingpin
    assert upper == KingpinPoint('carrier', (names.index('UpperArm'),))
    assert lower == KingpinPoint('virtual', tuple(sorted((names.index('Lateral'),
                                                          names.index('TrailingLink')))))
    assert mirror(scene).kingpin == scene.kingpin
    assert load_scene('double_wishbone').kingpin is None   # no key: the default axis
