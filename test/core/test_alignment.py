# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Exact derivatives and the alignment set, checked against finite differences of sweeps."""

from linkage_ros.core.measure import alignment
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import compile_scene, Continuation, sweep, travel_range
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

TRAVEL = travel_range(-60.0, 60.0, 0.5)
H = 0.5   # mm: central differences of the sweep have an O(H^2) error of about 1e-9 rad/mm


def sweep_and_alignment(name, rack=0.0):
    scene = load_scene(name)
    result = sweep(scene, TRAVEL, rack=rack)
    return scene, result, alignment(scene, compile_scene(scene), result.wheel_center,
                                    result.rotation, rack)


@pytest.mark.parametrize('name', ['five_link', 'double_wishbone', 'macpherson'])
def test_camber_gain_and_bump_steer_match_finite_differences_of_the_sweep(name):
    _, result, align = sweep_and_alignment(name)
    inner = slice(1, -1)
    assert align.camber_gain[inner] == pytest.approx(
        np.gradient(result.camber, H)[inner], abs=1e-8)
    assert align.bump_steer[inner] == pytest.approx(np.gradient(result.toe, H)[inner], abs=1e-8)


@pytest.mark.parametrize('name', ['five_link', 'macpherson'])
def test_wheel_center_velocity_ratio_matches_finite_differences(name):
    _, result, align = sweep_and_alignment(name)
    numeric = np.gradient(result.wheel_center, H, axis=0)
    assert align.wheel_center_velocity[1:-1] == pytest.approx(numeric[1:-1], abs=1e-6)
    assert np.all(align.wheel_center_velocity[:, 2] == 1.0)   # travel is Z_M


def angular_rate(rotation, i):
    """Angular velocity per mm of travel at sweep row i, by central differences."""
    return Rotation.from_matrix(rotation[i + 1] @ rotation[i - 1].T).as_rotvec() / (2 * H)


def test_screw_axis_reproduces_the_joint_velocities():
    # A screw motion moves every point p at rate * (pitch * u + u x (p - axis point)).
    _, result, align = sweep_and_alignment('five_link')
    i = len(TRAVEL) // 3
    velocity = (result.joints[i + 1] - result.joints[i - 1]) / (2 * H)
    u, point, pitch = align.screw_axis[i], align.screw_point[i], align.screw_pitch[i]
    rate = angular_rate(result.rotation, i) @ u
    predicted = rate * (pitch * u + np.cross(u, result.joints[i] - point))
    assert predicted == pytest.approx(velocity, abs=1e-6)


def test_double_wishbone_steer_axis_runs_close_to_the_ball_joints():
    # The instantaneous steer axis (rack input at constant wheel-centre height) of a double
    # wishbone lies within a few mm of the line through its two ball joints.
    scene, _, align = sweep_and_alignment('double_wishbone')
    upper, lower = (c.carrier for c in scene.constraints[:2])
    i = len(TRAVEL) // 2
    kingpin = (upper - lower) / np.linalg.norm(upper - lower)
    assert abs(align.steer_axis[i] @ kingpin) > 0.9999
    offset = np.cross(align.steer_point[i] - lower, kingpin)
    assert np.linalg.norm(offset) < 2.0
    assert np.degrees(align.kingpin_inclination[i]) == pytest.approx(
        np.degrees(np.arctan2(60.0, 320.0)), abs=0.1)


def test_steer_axis_is_the_screw_axis_of_rack_motion_by_finite_differences():
    scene = load_scene('macpherson')
    mech = compile_scene(scene)
    base = Continuation(scene).solve(20.0)
    h = 1e-3
    plus = Continuation(scene).solve(20.0, h)
    minus = Continuation(scene).solve(20.0, -h)
    align = alignment(scene, mech, base.wheel_center, base.rotation)
    d_rot = (plus.rotation - minus.rotation) / (2 * h) @ base.rotation.T
    omega = np.array([d_rot[2, 1], d_rot[0, 2], d_rot[1, 0]])
    assert omega / np.linalg.norm(omega) * np.sign(omega[2]) == pytest.approx(
        align.steer_axis[0], abs=1e-6)


def test_alignment_without_a_steer_link_leaves_the_steer_quantities_undefined():
    _, _, align = sweep_and_alignment('five_link')
    assert np.isnan(align.caster).all() and np.isnan(align.scrub_radius).all()
    assert np.isfinite(align.track_change).all()


def test_lateral_shift_matches_the_reference_wheel_center_dy():
    # ../shared/refdata/double_wishbone_test.yaml: wheel_center_dy_mm -10.023 at +80 mm.
    scene = load_scene('double_wishbone')
    result = sweep(scene, [80.0, 0.0, -80.0])
    align = alignment(scene, compile_scene(scene), result.wheel_center, result.rotation)
    assert align.lateral_shift == pytest.approx([-10.023, 0.0, -6.560], abs=1e-3)


def test_contact_patch_is_one_radius_below_an_upright_wheel():
    scene = load_scene('double_wishbone')
    result = sweep(scene, [0.0, 10.0, 20.0])
    align = alignment(scene, compile_scene(scene), result.wheel_center, result.rotation)
    assert align.contact_patch[0] == pytest.approx([0.0, 760.0, 300.0 - 330.0])
    assert align.track_change[0] == 0.0 and align.wheelbase_change[0] == 0.0


def test_instant_centres_have_zero_projected_velocity():
    scene, result, align = sweep_and_alignment('double_wishbone')
    i = len(TRAVEL) // 2 + 10
    omega = angular_rate(result.rotation, i)
    v = align.wheel_center_velocity[i]
    m = result.wheel_center[i]
    sv = np.array([align.side_view_ic[i, 0], m[1], align.side_view_ic[i, 1]])
    side_velocity = v + np.cross(omega, sv - m)
    assert side_velocity[[0, 2]] == pytest.approx([0, 0], abs=1e-3)


def test_rack_moves_toe_and_steered_sweep_keeps_residuals_tiny():
    scene = load_scene('double_wishbone')
    left = sweep(scene, TRAVEL, rack=10.0)
    paper = sweep(scene, TRAVEL[::40], rack=10.0, method='paper')
    assert left.success and left.residual.max() <= 1e-9
    assert np.degrees(left.toe[len(TRAVEL) // 2]) == pytest.approx(3.885, abs=1e-3)
    assert np.abs(paper.joints - left.joints[::40]).max() <= 1e-9
