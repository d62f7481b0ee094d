# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Static alignment in a scene: the design camber and toe in degrees instead of a spin-axis point.

carrier: {wheel_center: [...], static: {camber: 0.8, toe: 0.1}}: camber + = top outboard,
toe + = toe-in, on either side (right wheels mirror y). Solved at travel 0, the wheel has
exactly the alignment given: a spin-axis point rounded to 0.1 mm gives 0.79988 deg instead.
"""

import copy
import math

from linkage_ros.core.model import mirror, parse_scene, SceneError
from linkage_ros.core.solve import sweep
import numpy as np
import pytest

FIVE_LINK = {
    'name': 'aligned', 'units': 'mm', 'side': 'left',
    'carrier': {'wheel_center': [0.0, 760.0, 300.0], 'static': {'camber': 0.8, 'toe': 0.1}},
    'constraints': [
        {'name': 'upper_front', 'type': 'sphere', 'base': [80, 350, 450],
         'carrier': [15, 640, 485]},
        {'name': 'upper_rear', 'type': 'sphere', 'base': [-120, 360, 440],
         'carrier': [-15, 635, 475]},
        {'name': 'lower_front', 'type': 'sphere', 'base': [150, 250, 180],
         'carrier': [25, 700, 160]},
        {'name': 'lower_rear', 'type': 'sphere', 'base': [-150, 250, 185],
         'carrier': [-10, 695, 162]},
        {'name': 'tie_rod', 'type': 'sphere', 'base': [-150, 300, 250],
         'carrier': [-140, 690, 260]}],
}


def right_hand(data):
    """Return the same corner written by hand as a right wheel: every y negated, side: right."""
    right = copy.deepcopy(data)
    right['side'] = 'right'
    flip = lambda p: [p[0], -p[1], p[2]]   # noqa: E731
    right['carrier']['wheel_center'] = flip(right['carrier']['wheel_center'])
    for c in right['constraints']:
        c['base'], c['carrier'] = flip(c['base']), flip(c['carrier'])
    return right


def alignment_of_design_axis(scene):
    """
    Camber and toe (deg) of the scene's design spin axis, by the conventions' definitions.

    Written here apart from the package: camber is the axis's elevation below the horizontal
    toward the outboard end (asin), toe its heading forward of outboard (atan of x over the
    outboard y).
    """
    axis = scene.wheel_center - scene.spin_axis_point
    axis = axis / np.linalg.norm(axis)
    outboard_y = axis[1] if scene.side == 'left' else -axis[1]
    return math.degrees(math.asin(-axis[2])), math.degrees(math.atan(axis[0] / outboard_y))


@pytest.mark.parametrize('corner', ['left', 'mirrored right', 'right written by hand'])
def test_a_static_camber_and_toe_are_the_solved_alignment_at_travel_0(corner):
    scene = parse_scene(right_hand(FIVE_LINK) if corner == 'right written by hand'
                        else FIVE_LINK)
    if corner == 'mirrored right':
        scene = mirror(scene)
    assert scene.side == ('left' if corner == 'left' else 'right')
    solved = sweep(scene, np.array([0.0]))
    assert solved.residual[0] <= 1e-9
    assert math.degrees(solved.camber[0]) == pytest.approx(0.8, abs=1e-12)
    assert math.degrees(solved.toe[0]) == pytest.approx(0.1, abs=1e-12)
    assert alignment_of_design_axis(scene) == pytest.approx((0.8, 0.1), abs=1e-12)


def test_the_spin_axis_point_is_inboard_at_the_carrier_s_size():
    scene = parse_scene(FIVE_LINK)
    n = scene.spin_axis_point
    assert n[1] < scene.wheel_center[1]   # inboard of the left wheel's centre
    reach = np.mean([np.linalg.norm(c.carrier - scene.wheel_center)
                     for c in scene.constraints])
    assert np.linalg.norm(scene.wheel_center - n) == pytest.approx(reach, rel=1e-12)


def test_toe_in_points_the_outboard_spin_axis_forward_on_either_side():
    # toe-in: the front of the wheel turns toward the vehicle's centre plane; the wheel's
    # heading is square to its spin axis, so the outboard end of the axis turns forward (+x)
    for data in (FIVE_LINK, right_hand(FIVE_LINK)):
        scene = parse_scene(data)
        assert (scene.wheel_center - scene.spin_axis_point)[0] > 0


def test_giving_both_a_spin_axis_point_and_static_is_refused_by_name():
    data = copy.deepcopy(FIVE_LINK)
    data['carrier']['spin_axis_point'] = [0.0, 660.0, 300.0]
    with pytest.raises(SceneError) as raised:
        parse_scene(data, 'both.yaml')
    assert raised.value.field == 'carrier.static'
    assert raised.value.problem.startswith('give spin_axis_point or static, not both')


@pytest.mark.parametrize('static, field, problem', [
    ({'camber': 0.8}, 'carrier.static.toe', 'missing (required)'),
    ({'camber': 90, 'toe': 0}, 'carrier.static.camber', '90 deg: must be between -90 and 90 '
     'deg, or the spin axis does not point outboard'),
    ({'camber': 0.8, 'tow': 0}, 'carrier.static.tow', 'unknown key (did you mean toe?)'),
    ({'camber': '0.8 deg', 'toe': 0}, 'carrier.static.camber',
     "expected a number, got '0.8 deg'")])
def test_a_bad_static_block_names_its_field(static, field, problem):
    data = copy.deepcopy(FIVE_LINK)
    data['carrier']['static'] = static
    with pytest.raises(SceneError) as raised:
        parse_scene(data)
    assert (raised.value.field, raised.value.problem) == (field, problem)
