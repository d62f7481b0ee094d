# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Axle quantities (core.axle.axle) against computations of their own, on every bundled scene.

Each bundled scene is made an axle with its mirror image as the right corner. The roll
centre, the anti quantities and the Ackermann percentage of solve_axle (exact velocities by
the implicit function theorem) are checked against velocities from five-point central
differences of sweeps of each corner (the contact patch held as a point of the carrier), the
roll centre by intersecting the two front-view lines directly, and the steer angles from
sweeps of each corner at the rack.
"""

import math

from linkage_ros.core.axle import Axle, solve_axle, wheel_travels
from linkage_ros.core.base import Status
from linkage_ros.core.measure import contact_patch
from linkage_ros.core.model import bundled_scenes, load_scene, mirror
from linkage_ros.core.solve import compile_scene, sweep
import numpy as np
import pytest

H = 0.5    # mm: the five-point stencil's O(H^4) error and its rounding both stay below 1e-7 mm
STENCIL = np.array([1.0, -8.0, 0.0, 8.0, -1.0]) / (12.0 * H)
TOL = 1e-12   # mm: the sweeps' residual tolerance (floored at round-off of the scene size)
HEAVE = np.array([-30.0, 0.0, 25.0, 0.0, 10.0])
ROLL = np.radians([0.0, 0.0, 0.0, 2.0, -1.5])
WHEELBASE, CG_HEIGHT = 2800.0, 550.0


def axle_of(name, **kwargs):
    scene = load_scene(name)
    return Axle(scene, mirror(scene), name=name, **kwargs)


def carrier_point_velocity(scene, travel, rack=0.0):
    """
    Return a wheel's contact patch, wheel centre and their velocities per mm of its travel.

    Five-point central differences of a sweep around travel; the patch is the lowest point
    of the wheel at travel, followed as a point fixed in the carrier.
    """
    result = sweep(scene, travel + H * np.arange(-2, 3), rack=rack, tol=TOL)
    center, rotation = result.wheel_center[2], result.rotation[2]
    axis = rotation @ compile_scene(scene).spin_axis
    patch = contact_patch(center[None], axis[None], scene.wheel_radius)[0]
    followed = result.wheel_center + result.rotation @ (rotation.T @ (patch - center))
    return patch, STENCIL @ followed, center, STENCIL @ result.wheel_center


def intersect(patch_left, velocity_left, patch_right, velocity_right):
    """Return (y, z) where the front-view lines through the patches, square to v, meet."""
    along_left = np.array([-velocity_left[2], velocity_left[1]])
    along_right = np.array([-velocity_right[2], velocity_right[1]])
    a, _ = np.linalg.solve(np.column_stack((along_left, -along_right)),
                           patch_right[1:] - patch_left[1:])
    return patch_left[1:] + a * along_left


@pytest.mark.parametrize('name', bundled_scenes())
def test_roll_centre_is_where_the_lines_square_to_the_patch_velocities_meet(name):
    axle = axle_of(name)
    result = solve_axle(axle, HEAVE, ROLL, tol=TOL)
    assert result.success
    for i, travels in enumerate(result.travel):
        left, right = (carrier_point_velocity(s, t) for s, t in zip(axle.scenes, travels))
        expected = intersect(left[0], left[1], right[0], right[1])
        if np.abs(expected).max() > 1e5:
            # Nearly parallel lines (chrono_bmw_e90_macpherson_front rolled by 2 deg meets 537 m
            # away): the intersection magnifies the differences' 1e-10 error; relative there.
            assert result.roll_centre[i] == pytest.approx(expected, rel=1e-6)
            continue
        assert result.roll_centre[i] == pytest.approx(expected, abs=1e-6)
        # Height above the line through the two patches, by the triangle's area.
        ground = right[0][1:] - left[0][1:]
        to_centre = expected - left[0][1:]
        height = (ground[0] * to_centre[1] - ground[1] * to_centre[0]) / np.hypot(*ground)
        assert result.roll_centre_height[i] == pytest.approx(-height, abs=1e-6)


@pytest.mark.parametrize('name', bundled_scenes())
def test_a_symmetric_axle_in_heave_has_its_roll_centre_on_the_centreline(name):
    axle = axle_of(name)
    low, high, _ = axle.left.travel
    result = solve_axle(axle, np.linspace(0.75 * low, 0.75 * high, 31))
    assert result.success
    assert np.abs(result.roll_centre[:, 0]).max() < 1e-9   # mm: round-off of mirrored solves
    assert np.all(np.isfinite(result.roll_centre_height))


@pytest.mark.parametrize('name', bundled_scenes())
@pytest.mark.parametrize('front, brakes', [(True, 'outboard'), (True, 'inboard'),
                                           (False, 'outboard')])
def test_anti_dive_lift_and_squat_follow_milliken_from_the_side_view_velocities(
        name, front, brakes):
    axle = axle_of(name, front=front, wheelbase=WHEELBASE, cg_height=CG_HEIGHT,
                   brake_share=0.6, drive_share=0.4, brakes=brakes)
    result = solve_axle(axle, HEAVE, ROLL, tol=TOL)
    braking, drive = ('anti_dive', 'anti_lift') if front else ('anti_lift', 'anti_squat')
    sign = 1.0 if front else -1.0
    for i, travels in enumerate(result.travel):
        wheels = [carrier_point_velocity(s, t) for s, t in zip(axle.scenes, travels)]
        # Milliken ch. 17: anti % = tan(theta) / (h / L) x share, tan(theta) the slope of the
        # line from the point to the side-view instant centre = the point's v_x / v_z (front).
        brake_point = 1 if brakes == 'outboard' else 3
        tan_brake = np.mean([sign * w[brake_point][0] / w[brake_point][2] for w in wheels])
        tan_drive = np.mean([sign * w[3][0] / w[3][2] for w in wheels])
        assert result.anti[braking][i] == pytest.approx(
            100 * tan_brake / (CG_HEIGHT / WHEELBASE) * 0.6, abs=1e-6)
        assert result.anti[drive][i] == pytest.approx(
            100 * tan_drive / (CG_HEIGHT / WHEELBASE) * 0.4, abs=1e-6)


STEERED = [n for n in bundled_scenes()
           if any(c.steer == 'rack' for c in load_scene(n).constraints)]


@pytest.mark.parametrize('name', STEERED)
def test_ackermann_and_mean_steer_match_the_turning_centre_of_the_inner_wheel(name):
    axle = axle_of(name, wheelbase=WHEELBASE)
    racks = np.array([-12.0, -4.0, 5.0, 15.0])
    result = solve_axle(axle, 10.0, 0.0, racks)
    assert result.success
    for i, rack in enumerate(racks):
        yaws, patches = [], []
        for scene in axle.scenes:
            corner = sweep(scene, [10.0], rack=rack)
            axis = corner.rotation[0] @ compile_scene(scene).spin_axis
            yaws.append(math.atan2(-axis[0], axis[1] * scene.side_sign) * scene.side_sign)
            patches.append(contact_patch(corner.wheel_center, axis[None],
                                         scene.wheel_radius)[0])
        assert np.degrees(result.steer[i]) == pytest.approx(np.degrees(yaws), abs=1e-6)
        assert np.degrees(result.mean_steer[i]) == pytest.approx(np.degrees(np.mean(yaws)),
                                                                 abs=1e-6)
        inner = 0 if np.mean(yaws) > 0 else 1
        outer = 1 - inner
        d_inner, d_outer = abs(yaws[inner]), abs(yaws[outer])
        # The turning centre lies on the rear axle line, L behind the front axle, where the
        # inner wheel's axis meets it: L / tan(d_inner) inboard of the inner patch. The outer
        # wheel's ideal angle points it at the same centre.
        track = abs(patches[0][1] - patches[1][1])
        ideal = math.atan2(WHEELBASE, WHEELBASE / math.tan(d_inner) + track)
        assert result.ackermann[i] == pytest.approx(
            100 * (d_inner - d_outer) / (d_inner - ideal), abs=1e-6)


def test_ackermann_is_nan_below_the_mean_steer_threshold_as_in_roll_at_rack_0():
    # The demo front axle rolled 4 deg at rack 0: the wheels yaw 0.36 and 0.55 deg by roll
    # steer alone, which gave -15347 %; 1 deg of steer from the rack gives a value again.
    from linkage_ros.core.axle import ACKERMANN_MIN_STEER
    axle = axle_of('double_wishbone', wheelbase=WHEELBASE)
    result = solve_axle(axle, 0.0, np.radians([-4.0, 4.0, 0.0, 0.0]), [0.0, 0.0, 0.0, 10.0])
    assert result.success
    assert np.all(np.abs(result.mean_steer[:2]) < ACKERMANN_MIN_STEER)
    assert np.all(np.abs(result.mean_steer[:2]) > math.radians(0.4))
    assert np.isnan(result.ackermann[:3]).all()
    assert abs(result.mean_steer[3]) > ACKERMANN_MIN_STEER
    assert -10.0 < result.ackermann[3] < 0.0   # slightly anti-Ackermann (doc/axle.md)


def test_ackermann_is_100_for_wheels_at_the_ideal_angles_and_0_for_parallel_steer():
    from linkage_ros.core.axle import ackermann
    inner = math.radians(20.0)
    ideal = math.atan(2800.0 / (2800.0 / math.tan(inner) + 1500.0))
    steer = np.array([[inner, ideal], [inner, inner], [-ideal, -inner]])   # left, right
    assert ackermann(steer, 2800.0, np.full(3, 1500.0)) == pytest.approx([100.0, 0.0, 100.0])


def test_roll_puts_the_right_wheel_in_bump_by_half_the_design_track_times_tan_phi():
    axle = axle_of('double_wishbone')   # design track 1520 mm at the contact patches
    left, right = wheel_travels(axle, np.array([5.0]), np.radians([3.0]))
    s = 760.0 * math.tan(math.radians(3.0))
    assert axle.design_track == pytest.approx(1520.0)
    assert (left[0], right[0]) == pytest.approx((5.0 - s, 5.0 + s))


def test_roll_camber_relative_to_the_ground_adds_the_body_roll():
    # Right side down by phi: the body carries a wheel's top towards -y, inboard on the left
    # wheel and outboard on the right, by phi for a wheel without toe.
    axle = axle_of('five_link')
    result = solve_axle(axle, 0.0, np.radians([2.0]))
    shift = np.degrees(result.camber_ground - result.camber)[0]
    assert shift == pytest.approx([-2.0, 2.0], abs=2e-3)   # toe of 0.1 deg: cos effects only


def wide_axle_of(name, travel=(-1000.0, 1000.0, 1.0)):
    """Return axle_of(name) with a travel block wide enough to reach the kinematic limits."""
    from dataclasses import replace
    scene = replace(load_scene(name), travel=travel)
    return Axle(scene, mirror(scene), name=name)


def test_a_roll_beyond_reach_ends_the_result_with_the_limit_of_the_wheel():
    axle = wide_axle_of('five_link')
    result = solve_axle(axle, 0.0, np.radians([0.0, 5.0, 40.0, 10.0]))
    assert not result.success and result.status == Status.OUT_OF_REACH
    assert len(result.heave) == 2
    assert result.message.startswith('heave 0 mm, roll 40 deg, rack 0 mm: the left wheel ')
    assert 'rebound limit' in result.message


@pytest.mark.parametrize('heave, roll_deg, rack, solved, says', [
    # heave: both wheels at the bump limit of 80 mm are within; 81 mm is not
    ([0.0, 40.0, 80.0, 81.0, 20.0], 0.0, 0.0, 3, 'the left wheel (double_wishbone) would '
     'travel 81 mm'),
    # roll: s = 760 tan(phi) passes 80 mm between 6.0 deg (79.9 mm) and 6.1 deg (81.2 mm)
    (0.0, [0.0, 3.0, 6.0, 6.1, 2.0], 0.0, 3, 'the left wheel (double_wishbone) would travel '
     '-81.2'),
    # steer: a rack grid at a heave beyond the limits stops before its first rack
    (-85.0, 0.0, [-10.0, 0.0, 10.0], 0, 'the left wheel (double_wishbone) would travel -85 mm'),
])
def test_a_position_beyond_a_corners_travel_limits_ends_the_result_before_it(
        heave, roll_deg, rack, solved, says):
    axle = axle_of('double_wishbone')   # travel block -80 to 80 mm, design track 1520 mm
    result = solve_axle(axle, heave, np.radians(roll_deg), rack)
    assert not result.success and result.status == Status.OUT_OF_REACH
    assert len(result.heave) == len(result.wheel_center) == solved
    assert np.abs(result.travel).max(initial=0.0) <= 80.0 + 1e-9
    assert says in result.message
    assert result.message.endswith("beyond its travel limits -80 to 80 mm (the scene's "
                                   'travel block)')


def test_an_axle_without_wheel_radius_leaves_the_patch_quantities_out_and_says_why():
    scene = load_scene('five_link')
    from dataclasses import replace
    bare = replace(scene, wheel_radius=0.0)
    result = solve_axle(Axle(bare, mirror(bare)), [0.0, 10.0])
    assert np.isnan(result.roll_centre).all() and np.isnan(result.track).all()
    assert np.isfinite(result.camber).all()
    assert len(result.notes) == 2 and 'no wheel_radius' in result.notes[0]


def pivoting_scene(axis):
    """
    Return a wheel carrier on an arm that turns about a body-fixed axis [[x, y, z], [x, y, z]].

    Two carrier points on circles about the axis, a third on a sphere centred on it; wheel
    radius 330 mm. An axis along x makes a swing axle, one along y a trailing arm.
    """
    from linkage_ros.core.model import parse_scene
    return parse_scene({
        'units': 'mm', 'side': 'left', 'wheel_radius': 330,
        'carrier': {'wheel_center': [0.0, 760.0, 300.0], 'spin_axis_point': [0.0, 660.0, 300.0]},
        'constraints': [
            {'name': 'arm_a', 'type': 'circle', 'axis': axis, 'carrier': [60.0, 650.0, 180.0]},
            {'name': 'arm_b', 'type': 'circle', 'axis': axis, 'carrier': [-40.0, 700.0, 260.0]},
            {'name': 'brace', 'type': 'sphere', 'base': list(np.mean(axis, axis=0)),
             'carrier': [20.0, 620.0, 330.0]}]}, source='pivot')


def test_a_swing_axle_rolls_about_where_the_lines_from_the_patches_through_the_pivots_meet():
    # Textbook swing axle: each wheel turns about a longitudinal axis at y = 100, z = 250 mm;
    # its patch (y 760, z -30) moves square to the line to that pivot, so the roll centre is on
    # that line at the centreline: (250 + 30) x 760 / (760 - 100) above the ground.
    scene = pivoting_scene([[200.0, 100.0, 250.0], [-200.0, 100.0, 250.0]])
    result = solve_axle(Axle(scene, mirror(scene)), [0.0])
    assert result.roll_centre[0, 0] == pytest.approx(0.0, abs=1e-9)
    assert result.roll_centre_height[0] == pytest.approx(280.0 * 760.0 / 660.0, abs=1e-9)


def test_a_trailing_arm_front_axle_has_the_anti_dive_of_its_pivot_angle():
    # Milliken ch. 17: anti-dive = tan(theta) L / h x brake share, theta the side-view angle of
    # the line from the patch (x 0, z -30) to the pivot (x -400, z 120, behind and above):
    # tan(theta) = 150 / 400. Drive (anti-lift) uses the wheel centre (z 300): -180 / 400.
    scene = pivoting_scene([[-400.0, 300.0, 120.0], [-400.0, 500.0, 120.0]])
    axle = Axle(scene, mirror(scene), wheelbase=2800.0, cg_height=550.0, brake_share=0.6,
                drive_share=0.4)
    result = solve_axle(axle, [0.0])
    assert result.anti['anti_dive'][0] == pytest.approx(100 * 150 / 400 * 2800 / 550 * 0.6)
    assert result.anti['anti_lift'][0] == pytest.approx(100 * -180 / 400 * 2800 / 550 * 0.4)
