# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The geometric kingpin beside the instantaneous steer axis.

core.measure.kingpin beside core.measure.alignment.

Checked against two published Lotus Suspension Analysis printouts (test/resources, sources in
each file), against the ball-joint coordinates of the solved positions, and against a
least-squares closest approach for five_link's virtual ball joints.
"""

from pathlib import Path

from linkage_ros.core.axle import Axle, solve_axle
from linkage_ros.core.measure import alignment, contact_patch, geometric_kingpin, kingpin_points
from linkage_ros.core.model import load_scene, mirror, parse_scene, SceneError
from linkage_ros.core.solve import compile_scene, sweep
import numpy as np
import pytest
import yaml

RESOURCES = Path(__file__).resolve().parents[1] / 'resources'
LOTUS = ['lotus_4x4v23_front.yaml', 'lotus_bat_front.yaml']
PRINTED = 0.005 + 1e-9   # the printouts give 2 decimals
# What each printout prints (STATIC VALUES, GENERAL DATA VALUES), by scene file.
LOTUS_PRINTED = yaml.safe_load((RESOURCES / 'lotus_printouts.yaml').read_text())


def kingpin_at(scene, travels, rack=0.0):
    result = sweep(scene, travels, rack=rack)
    axis = result.rotation @ compile_scene(scene).spin_axis
    patch = contact_patch(result.wheel_center, axis, scene.wheel_radius)
    return result, patch, geometric_kingpin(scene, result.joints, result.wheel_center, patch,
                                            rack)


@pytest.mark.parametrize('name', LOTUS)
def test_geometric_kingpin_reproduces_every_printed_lotus_static_value(name):
    scene = load_scene(RESOURCES / name)
    printed = LOTUS_PRINTED[name]
    _, _, king = kingpin_at(scene, [0.0])
    assert np.degrees(king.caster[0]) == pytest.approx(printed['castor_angle_deg'], abs=PRINTED)
    assert np.degrees(king.kingpin_inclination[0]) == pytest.approx(
        printed['kingpin_angle_deg'], abs=PRINTED)
    # Lotus's castor offset is the ground distance (our mechanical trail); its mechanical
    # trail is that times cos(castor), the distance square to the axis in the side view.
    assert king.mechanical_trail[0] == pytest.approx(printed['castor_offset_mm'], abs=PRINTED)
    assert king.mechanical_trail[0] * np.cos(king.caster[0]) == pytest.approx(
        printed['mechanical_trail_mm'], abs=PRINTED)
    assert king.scrub_radius[0] == pytest.approx(printed['kingpin_offset_at_ground_mm'],
                                                 abs=PRINTED)
    assert king.offset_wheel_centre[0] == pytest.approx(printed['kingpin_offset_at_wheel_mm'],
                                                        abs=PRINTED)


def test_the_instantaneous_steer_axis_of_the_lotus_double_wishbone_differs_as_issue_19_says():
    # Issue 19: linkage-sweep --alignment gives 15.59 and 9.96 deg where Lotus prints 16.22 and
    # 9.75 (the ball-joint line), and a trail 13 mm shorter than Lotus's 73.27 mm.
    scene = load_scene(RESOURCES / LOTUS[0])
    result = sweep(scene, [0.0])
    align = alignment(scene, compile_scene(scene), result.wheel_center, result.rotation)
    assert np.degrees(align.caster[0]) == pytest.approx(15.59, abs=PRINTED)
    assert np.degrees(align.kingpin_inclination[0]) == pytest.approx(9.96, abs=PRINTED)
    assert 73.27 - align.mechanical_trail[0] == pytest.approx(13.0, abs=0.5)


@pytest.mark.parametrize('name', LOTUS)
def test_roll_centre_height_of_the_mirrored_lotus_axle_matches_the_printout(name):
    # The printed hardpoints are rounded to 0.01 mm, which alone moves this roll centre by
    # up to 0.06 mm (200 random roundings of every point: std 0.021 and 0.014 mm).
    scene = load_scene(RESOURCES / name)
    result = solve_axle(Axle(scene, mirror(scene)), [0.0])
    assert result.roll_centre_height[0] == pytest.approx(
        LOTUS_PRINTED[name]['roll_centre_height_mm'], abs=0.1)


def axis_from(upper, lower, center, patch, side):
    """Caster, KPI (deg), scrub, trail and offset at the wheel centre (mm) of one line."""
    d = upper - lower
    caster = np.degrees(np.arctan((lower[0] - upper[0]) / (upper[2] - lower[2])))
    kpi = np.degrees(np.arctan(side * (lower[1] - upper[1]) / (upper[2] - lower[2])))
    ground = lower + d * (patch[2] - lower[2]) / d[2]
    at_centre = lower + d * (center[2] - lower[2]) / d[2]
    return (caster, kpi, side * (patch[1] - ground[1]), ground[0] - patch[0],
            side * (center[1] - at_centre[1]))


@pytest.mark.parametrize('name, upper, lower', [
    ('double_wishbone', ('carrier', 0), ('carrier', 1)),
    ('macpherson', ('base', 2), ('carrier', 0))])
@pytest.mark.parametrize('mirrored', [False, True])
def test_geometric_kingpin_runs_through_the_ball_joints_or_top_mount(name, upper, lower,
                                                                     mirrored):
    scene = load_scene(name)
    scene = mirror(scene) if mirrored else scene
    rack = 6.0
    result, patch, king = kingpin_at(scene, [-50.0, 0.0, 30.0, 60.0], rack)
    for i in range(len(result.travel)):
        ends = [result.joints[i, index] if kind == 'carrier'
                else scene.constraints[index].base[0] for kind, index in (upper, lower)]
        expected = axis_from(*ends, result.wheel_center[i], patch[i], scene.side_sign)
        got = (np.degrees(king.caster[i]), np.degrees(king.kingpin_inclination[i]),
               king.scrub_radius[i], king.mechanical_trail[i], king.offset_wheel_centre[i])
        assert got == pytest.approx(expected, abs=1e-9)


def test_five_link_virtual_ball_joints_are_the_closest_approach_of_each_link_pair():
    scene = load_scene('five_link')
    result, _, king = kingpin_at(scene, [-40.0, 0.0, 35.0])
    names = [c.name for c in scene.constraints]
    for i in range(len(result.travel)):
        for point, pair in ((king.upper[i], ('upper_front', 'upper_rear')),
                            (king.lower[i], ('lower_front', 'lower_rear'))):
            a, b = (scene.constraints[names.index(n)] for n in pair)
            ja, jb = (result.joints[i, names.index(n)] for n in pair)
            u, v = ja - a.base[0], jb - b.base[0]
            (s, t), *_ = np.linalg.lstsq(np.column_stack((u, -v)), b.base[0] - a.base[0],
                                         rcond=None)
            closest = 0.5 * (a.base[0] + s * u + b.base[0] + t * v)
            assert point == pytest.approx(closest, abs=1e-9)


def test_scene_kingpin_defaults_two_arms_or_strut_and_arm_else_the_key():
    assert [p.kind for p in kingpin_points(load_scene('double_wishbone'))] == ['carrier'] * 2
    assert [p.kind for p in kingpin_points(load_scene('macpherson'))] == ['base', 'carrier']
    assert [p.kind for p in kingpin_points(load_scene('five_link'))] == ['virtual'] * 2
    mixed = kingpin_points(load_scene('chrono_generic_multilink'))
    assert [p.kind for p in mixed] == ['carrier', 'virtual']


def five_link_data(**changes):
    data = yaml.safe_load((Path(load_scene('five_link').source)).read_text())
    data.update(changes)
    return data


def test_a_scene_without_a_kingpin_has_no_geometric_columns():
    data = five_link_data()
    del data['kingpin']
    scene = parse_scene(data)
    _, _, king = kingpin_at(scene, [0.0, 10.0])
    assert np.isnan(king.caster).all() and np.isnan(king.scrub_radius).all()


@pytest.mark.parametrize('kingpin, field, says', [
    (['upper_front', 'nope'], 'kingpin[1]', "'nope' is not a constraint of the scene"),
    ([['upper_front', 'upper_rear']], 'kingpin', 'expected [UPPER, LOWER]'),
    ([['upper_front', 'upper_front'], 'tie_rod'], 'kingpin[0]', 'a pair of two link names'),
    ([['upper_front', 'upper_rear'], ['upper_rear', 'upper_front']], 'kingpin',
     'names the same joint twice'),
])
def test_a_bad_kingpin_key_fails_on_load_naming_the_file_and_the_key(kingpin, field, says):
    with pytest.raises(SceneError) as error:
        parse_scene(five_link_data(kingpin=kingpin), source='bad.yaml')
    assert error.value.field == field and says in error.value.problem


def test_a_virtual_ball_joint_needs_links_not_arms():
    data = yaml.safe_load(Path(load_scene('double_wishbone').source).read_text())
    data['kingpin'] = [['upper_arm', 'tie_rod'], 'lower_arm']
    with pytest.raises(SceneError, match=r'kingpin\[0\]\[0\]: upper_arm is a circle, not a '):
        parse_scene(data, source='bad.yaml')


def test_linkage_sweep_alignment_gives_both_conventions_side_by_side(capsys):
    import csv
    import io

    from linkage_ros.tools.sweep import main
    assert main([str(RESOURCES / LOTUS[0]), '--travel', '0:0:1',
                 '--alignment']) == 0
    row = next(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    printed = LOTUS_PRINTED[LOTUS[0]]
    assert float(row['caster_deg']) == pytest.approx(15.59, abs=PRINTED)   # instantaneous
    assert float(row['caster_geometric_deg']) == pytest.approx(printed['castor_angle_deg'],
                                                               abs=PRINTED)
    assert float(row['kingpin_inclination_geometric_deg']) == pytest.approx(
        printed['kingpin_angle_deg'], abs=PRINTED)
    assert float(row['scrub_radius_geometric_mm']) == pytest.approx(
        printed['kingpin_offset_at_ground_mm'], abs=PRINTED)
    assert float(row['mechanical_trail_geometric_mm']) == pytest.approx(
        printed['castor_offset_mm'], abs=PRINTED)
    assert float(row['kingpin_offset_wheel_centre_geometric_mm']) == pytest.approx(
        printed['kingpin_offset_at_wheel_mm'], abs=PRINTED)
