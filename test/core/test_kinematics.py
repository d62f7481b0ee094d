# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The kinematics core: reference agreement, residuals, paper = fast, Jacobians, continuation."""

from pathlib import Path
import subprocess
import sys

from linkage_ros.core.base import camber_toe, exp_so3, Status, trilaterate
from linkage_ros.core.model import bundled_scenes, load_scene, mirror
from linkage_ros.core.solve import (Continuation, METHODS, paper_method, pose_newton, sweep,
                                    travel_range)
from linkage_ros.core.solve.mechanism import carrier_points, compile_scene, linearize
import numpy as np
import pytest
import yaml

SCENES = ['five_link', 'double_wishbone', 'macpherson']
FULL = travel_range(-80.0, 80.0, 1.0)
REFDATA = Path(__file__).resolve().parents[3] / 'shared' / 'refdata'


@pytest.fixture(scope='module')
def sweeps():
    """Full -80..+80 mm sweeps of every bundled scene by both methods."""
    return {(name, method): sweep(load_scene(name), FULL, method=method)
            for name in SCENES for method in ('paper', 'fast')}


def reference_rows(name):
    ref = load_scene(name).extras['reference']
    return ref['columns'], np.array(ref['rows'], dtype=float)


@pytest.mark.parametrize('method', ['paper', 'fast'])
@pytest.mark.parametrize('name', ['five_link', 'double_wishbone'])
def test_reference_results_are_reproduced(sweeps, name, method):
    # Reference: independent solvers (exudyn, pymycar, MuJoCo, ...) in ../shared/refdata,
    # given to 4 decimals (deg) and 3 decimals (mm); tolerance 1e-4 deg and 1e-3 mm.
    result = sweeps[name, method]
    columns, rows = reference_rows(name)
    scene = load_scene(name)
    for row in rows:
        i = int(np.flatnonzero(result.travel == row[0])[0])
        assert np.degrees(result.camber[i]) == pytest.approx(row[1], abs=1e-4)
        assert np.degrees(result.toe[i]) == pytest.approx(row[2], abs=1e-4)
        if 'wheel_center_dy_mm' in columns:
            dy = result.wheel_center[i, 1] - scene.wheel_center[1]
            assert dy == pytest.approx(row[3], abs=1e-3)


@pytest.mark.skipif(not REFDATA.is_dir(), reason='../shared/refdata is not beside the repository')
@pytest.mark.parametrize('name,source', [('five_link', 'five_link_test.yaml'),
                                         ('double_wishbone', 'double_wishbone_test.yaml')])
def test_scene_reference_block_is_a_faithful_copy_of_refdata(name, source):
    original = yaml.safe_load((REFDATA / source).read_text())['results']
    columns, rows = reference_rows(name)
    assert columns == original['columns']
    assert rows.tolist() == np.array(original['rows'], dtype=float).tolist()


@pytest.mark.parametrize('method', ['paper', 'fast'])
@pytest.mark.parametrize('name', SCENES)
def test_constraint_residual_is_below_1e_9_mm_at_every_position(sweeps, name, method):
    result = sweeps[name, method]
    assert result.success and len(result.travel) == len(FULL)
    assert result.residual.max() <= 1e-9


@pytest.mark.parametrize('name', SCENES)
def test_paper_and_fast_methods_agree_to_1e_9_mm(sweeps, name):
    paper, fast = sweeps[name, 'paper'], sweeps[name, 'fast']
    assert np.abs(paper.wheel_center - fast.wheel_center).max() <= 1e-9
    assert np.abs(paper.joints - fast.joints).max() <= 1e-9


@pytest.mark.parametrize('name', SCENES)
def test_rigid_body_distances_hold_along_the_sweep(sweeps, name):
    result = sweeps[name, 'fast']
    design = result.joints[len(FULL) // 2]   # travel 0
    for joints in result.joints[::20]:
        gaps = np.linalg.norm(joints[:, None] - joints[None], axis=2)
        assert np.abs(gaps - np.linalg.norm(design[:, None] - design[None], axis=2)).max() < 1e-9


@pytest.mark.parametrize('method', ['paper', 'fast'])
@pytest.mark.parametrize('name', SCENES)
def test_sweep_down_gives_the_same_poses_as_sweep_up(sweeps, name, method):
    down = sweep(load_scene(name), FULL[::-1], method=method)
    up = sweeps[name, method]
    assert np.abs(down.joints[::-1] - up.joints).max() <= 1e-9


@pytest.mark.parametrize('name', SCENES)
def test_pose_jacobian_matches_finite_differences(name):
    mech = compile_scene(load_scene(name))
    center = mech.design_center + np.array([1.0, -2.0, 30.0])
    rotation = exp_so3(np.array([0.01, -0.02, 0.015]))
    _, jac = linearize(mech, center, rotation)
    h = 1e-6
    numeric = np.empty_like(jac)
    for k in range(6):
        step = np.zeros(6)
        step[k] = h
        plus = linearize(mech, center + step[:3], exp_so3(step[3:]) @ rotation)[0]
        minus = linearize(mech, center - step[:3], exp_so3(-step[3:]) @ rotation)[0]
        numeric[:, k] = (plus - minus) / (2 * h)
    assert np.abs(jac - numeric).max() <= 1e-6 * max(1.0, np.abs(jac).max())


@pytest.mark.parametrize('name', SCENES)
def test_paper_jacobian_with_chain_rule_through_joints_matches_finite_differences(name):
    scene = load_scene(name)
    model = paper_method.build(scene, compile_scene(scene))
    rng = np.random.default_rng(7)
    m, n, p = paper_method.points_of_pose(model, scene.wheel_center + [0.5, -1.0, 20.0],
                                          exp_so3(np.array([0.01, 0.02, -0.01])))
    x = np.concatenate((m[:2], n, p)) + rng.normal(scale=0.05, size=8)  # off the rigid set too
    _, jac = paper_method.system(model, x, m[2])
    h = 1e-6
    numeric = np.column_stack([
        (paper_method.system(model, x + h * e, m[2])[0]
         - paper_method.system(model, x - h * e, m[2])[0]) / (2 * h) for e in np.eye(8)])
    assert np.abs(jac - numeric).max() <= 1e-6 * np.abs(jac).max()


def test_trilateration_recovers_a_point_from_its_three_distances():
    m, n, p = np.array([0.0, 760, 300]), np.array([0.0, 660, 300]), np.array([50.0, 700, 390])
    joint = np.array([-140.0, 690, 260])
    radii = np.linalg.norm(joint - np.array([m, n, p]), axis=1)
    side = np.sign(np.cross(n - m, p - m) @ (joint - m))
    found, disc = trilaterate(m, n, p, radii, side)
    assert disc > 0 and found == pytest.approx(joint, abs=1e-10)


def test_gauss_jordan_solves_like_lu():
    rng = np.random.default_rng(3)
    a, b = rng.normal(size=(8, 8)), rng.normal(size=8)
    assert paper_method.gauss_jordan(a, b) == pytest.approx(np.linalg.solve(a, b), abs=1e-12)


def test_tangent_predicts_the_next_position_to_second_order():
    scene = load_scene('five_link')
    mech = compile_scene(scene)
    cont = Continuation(scene)
    base = cont.solve(10.0)
    jac = linearize(mech, base.wheel_center, base.rotation)[1]
    errors = []
    for h in (1.0, 0.5):
        guess = pose_newton.predict(mech, base.wheel_center, base.rotation, jac, h)
        exact = Continuation(scene).solve(10.0 + h)
        errors.append(np.abs(carrier_points(mech, *guess)
                             - carrier_points(mech, exact.wheel_center, exact.rotation)).max())
    assert errors[1] < errors[0] / 3   # O(h^2): halving h quarters the error


def test_design_position_has_zero_camber_toe_and_identity_rotation():
    sol = Continuation(load_scene('five_link')).solve(0.0)
    assert sol.success and sol.substeps == 0
    assert sol.quaternion == pytest.approx([0, 0, 0, 1])
    assert sol.camber == 0.0 and sol.toe == 0.0


def test_camber_and_toe_signs_follow_the_conventions():
    # Spin axis tilted up outboard: top of the wheel inboard, negative camber.
    camber, toe = camber_toe(np.array([0.0, np.cos(0.1), np.sin(0.1)]), +1)
    assert camber == pytest.approx(-0.1) and toe == 0.0
    # Left wheel axis pointing forward-outboard: the wheel's front turns inboard, toe-in (+).
    camber, toe = camber_toe(np.array([np.sin(0.02), np.cos(0.02), 0.0]), +1)
    assert toe == pytest.approx(0.02)


@pytest.mark.parametrize('name', SCENES)
def test_mirrored_right_wheel_has_the_same_camber_and_toe(sweeps, name):
    left = sweeps[name, 'fast']
    right = sweep(mirror(load_scene(name)), FULL)
    assert right.camber == pytest.approx(left.camber, abs=1e-12)
    assert right.toe == pytest.approx(left.toe, abs=1e-12)
    assert right.wheel_center[:, 1] == pytest.approx(-left.wheel_center[:, 1], abs=1e-9)


@pytest.mark.parametrize('travel', [float('nan'), float('inf'), -float('inf')])
def test_non_finite_travel_fails_with_a_clear_message(travel):
    cont = Continuation(load_scene('five_link'))
    sol = cont.solve(travel)
    assert not sol.success and 'not a finite number' in sol.message
    assert sol.status == Status.NOT_FINITE and sol.wheel_center is None


@pytest.mark.parametrize('method', ['paper', 'fast'])
def test_unreachable_travel_reports_the_reachable_range_and_keeps_the_state(method):
    cont = Continuation(load_scene('five_link'), method=method)
    before = cont.solve(20.0)
    sol = cont.solve(1000.0)
    assert not sol.success and sol.status == Status.OUT_OF_REACH
    assert 'out of reach' in sol.message and 'reachable range found' in sol.message
    assert sol.reachable[1] > 80.0          # the limit lies beyond the design range
    assert cont.travel == 20.0 and np.array_equal(cont.center, before.wheel_center)
    again = cont.solve(21.0)
    assert again.success and again.residual <= 1e-9


def test_unreachable_sweep_keeps_the_positions_solved_before_the_limit():
    result = sweep(load_scene('five_link'), travel_range(0.0, 1000.0, 50.0))
    assert not result.success and result.status == Status.OUT_OF_REACH
    assert 'out of reach' in result.message
    assert len(result.travel) >= 3 and result.residual.max() <= 1e-9


@pytest.mark.parametrize('method', METHODS)
@pytest.mark.parametrize('step', [1e-6, 1e-3, 0.004])
def test_a_step_shorter_than_min_step_is_one_plain_continuation_step(method, step):
    # Below min_step (0.005 mm) only a *failing* step means out of reach; a tiny command
    # that converges is one step, not a detour by arclength (which would count two).
    cont = Continuation(load_scene('five_link'), method=method)
    cont.solve(20.0)
    sol = cont.solve(20.0 + step)
    assert sol.success and sol.substeps == 1 and sol.travel == 20.0 + step


def test_large_jump_is_walked_in_substeps_to_the_same_pose():
    scene = load_scene('double_wishbone')
    jump = Continuation(scene)
    jump.solve(-80.0)
    far = jump.solve(80.0)
    fine = sweep(scene, FULL)
    assert far.substeps >= 160 / 5
    assert far.wheel_center == pytest.approx(fine.wheel_center[-1], abs=1e-9)


def test_the_core_package_imports_nothing_of_ros_mcap_rerun_or_matplotlib():
    code = ('import sys, linkage_ros, linkage_ros.core, linkage_ros.core.measure.alignment, '
            'linkage_ros.core.model.vehicle, linkage_ros.tools.sweep; '
            'print(sorted(m for m in ("rclpy", "mcap", "rerun", "matplotlib") '
            'if m in sys.modules))')
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == '[]'


def test_the_core_is_used_from_the_package_itself_without_loading_ros_mcap_or_rerun():
    code = ('import sys; from linkage_ros import Continuation, load_scene, sweep; '
            'solution = Continuation(load_scene("five_link")).solve(10.0); '
            'table = sweep(load_scene("five_link"), [-10.0, 0.0, 10.0]); '
            'print(solution.success, table.success, '
            'sorted(m for m in ("rclpy", "mcap", "rerun") if m in sys.modules))')
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == 'True True []'


@pytest.mark.parametrize('name', [n for n in bundled_scenes() if n.startswith('chrono_')])
def test_chrono_reference_scene_sweeps_with_paper_and_fast_agreeing(name):
    # ../shared/refdata Chrono hardpoint sets: no published curves, so the checks are the
    # residual bound and agreement of two formulations over the scene's travel block.
    scene = load_scene(name)
    fast = sweep(scene, FULL)
    paper = sweep(scene, FULL[::8], method='paper')
    assert fast.success and paper.success
    assert fast.residual.max() <= 1e-9 and paper.residual.max() <= 1e-9
    assert np.abs(paper.joints - fast.joints[::8]).max() <= 1e-9


def test_bmw_front_keeps_its_static_camber_of_minus_2_deg():
    # refdata: chrono_bmw_e90_macpherson_front static_alignment camber_deg -2 (Chrono header).
    sol = Continuation(load_scene('chrono_bmw_e90_macpherson_front')).solve(0.0)
    assert np.degrees(sol.camber) == pytest.approx(-2.0, abs=1e-6)


@pytest.mark.parametrize('method', METHODS)
@pytest.mark.parametrize('travels, limit', [([400.0], 387.469),
                                            (travel_range(-300.0, 0.0, 1.0), -274.673)])
def test_a_sweep_whose_first_travel_is_out_of_reach_is_a_table_of_no_rows(method, travels,
                                                                          limit):
    # Issue 18 defect 4: the table had no rows and linkage-sweep a traceback.
    result = sweep(load_scene('five_link'), travels, method=method)
    assert not result.success and result.status == Status.OUT_OF_REACH
    assert f'limit {limit:.3f} mm' in result.message
    assert result.travel.shape == (0,) and result.wheel_center.shape == (0, 3)
    assert result.rotation.shape == (0, 3, 3) and result.quaternion.shape == (0, 4)
    assert result.joints.shape == (0, 5, 3) and result.residual.shape == (0,)
