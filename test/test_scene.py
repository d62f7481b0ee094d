"""Scene loading: every malformed scene fails with one SceneError naming file, field, problem."""

import copy

from linkage_ros.core.scene import bundled_scenes, load_scene, mirror, SceneError
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
