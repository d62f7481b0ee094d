# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Stiff and extreme cases of the kinematics core.

Toggles, jumps, reversals, bad scaling, perturbed hardpoints, random scenes.

Expected values come from outside the core: an analytic toggle, the extended-precision 6-DOF
reference (linkage_ros.bench.reference, its own formulation), or an identity (the pose is a
function of travel; the same travel gives the same pose however it was reached).
Stress scenes live in config/stress/ (not bundled).
"""

import math
from pathlib import Path

from diagnostic_msgs.msg import DiagnosticStatus
from hypothesis import assume, example, given, HealthCheck, settings, strategies as st
from linkage_ros.bench import reference
from linkage_ros.bench.stress import hardpoint_count, perturbed, random_walk
from linkage_ros.core.model import bundled_scenes, load_scene, SceneError
from linkage_ros.core.solve import Continuation, Settings, sweep, travel_range
from linkage_ros.core.solve.pose_newton import FREE
from linkage_ros.ros.messages import status_values
import numpy as np
import pytest
from rclpy.parameter import Parameter

STRESS = Path(__file__).resolve().parents[2] / 'config' / 'stress'
# trailing_arm_toggle: M turns about the arm axis at radius hypot(150, 400) mm from an axis
# 100 mm below z = 0, starting at z = 300 mm: the bump travel ends with the arm vertical.
TOGGLE_LIMIT_MM = -100.0 + math.hypot(150.0, 400.0) - 300.0
LIMIT_TOL_MM = 0.01       # the issue: reachable limits located to 0.01 mm
TOL = Settings().tol      # 1e-10 mm
METHODS = ('fast', 'paper')


def stress_scene(name):
    return load_scene(STRESS / f'{name}.yaml')


def pose_error(ref, solutions):
    """errors() of a list of successful Solutions against a ReferencePoses."""
    return reference.errors(ref, np.array([s.wheel_center for s in solutions]),
                            np.array([s.rotation for s in solutions]))


# --- a link aligned with the travel, a toggle -----------------------------------------------

@pytest.mark.parametrize('method', METHODS)
def test_toggle_limit_is_located_to_0_01_mm_of_the_analytic_fold(method):
    cont = Continuation(stress_scene('trailing_arm_toggle'), method=method)
    beyond = cont.solve(80.0)
    assert not beyond.success
    assert beyond.reachable[1] == pytest.approx(TOGGLE_LIMIT_MM, abs=LIMIT_TOL_MM)


@pytest.mark.parametrize('method', METHODS)
def test_vertical_link_limit_agrees_with_an_independent_bisection_to_0_01_mm(method):
    scene = stress_scene('five_link_vertical_link')
    independent, _ = reference.reachable_limit(scene, 1)   # 6-DOF walk + least squares
    cont = Continuation(scene, method=method)
    beyond = cont.solve(80.0)
    assert not beyond.success
    assert beyond.reachable[1] == pytest.approx(independent, abs=LIMIT_TOL_MM)


@pytest.mark.parametrize('method', METHODS)
@pytest.mark.parametrize('past', [0.02, 1.0, 50.0])
def test_beyond_the_toggle_a_clear_error_and_never_a_pose(method, past):
    cont = Continuation(stress_scene('trailing_arm_toggle'), method=method)
    before = cont.solve(TOGGLE_LIMIT_MM - 1.0)
    sol = cont.solve(TOGGLE_LIMIT_MM + past)
    assert not sol.success
    assert 'out of reach' in sol.message and f'{TOGGLE_LIMIT_MM:.3f}' in sol.message
    assert sol.wheel_center is None and sol.rotation is None
    again = cont.solve(TOGGLE_LIMIT_MM - 1.0)            # the state stayed on the branch
    assert np.abs(again.wheel_center - before.wheel_center).max() <= 1e-9


@pytest.mark.parametrize('method', METHODS)
def test_poses_close_to_the_toggle_agree_with_the_reference(method):
    scene = stress_scene('trailing_arm_toggle')
    travels = [TOGGLE_LIMIT_MM - d for d in (1.0, 0.1, 0.02)]
    ref = reference.reference_poses(scene, travels, step=0.5)
    cont = Continuation(scene, method=method)
    sols = [cont.solve(t) for t in travels]
    assert all(s.success for s in sols)
    # The Jacobian's smallest singular value vanishes like sqrt(distance to the fold), so a
    # residual at tol moves the pose by more there: 3.5e-10 mm measured 0.02 mm from it.
    assert pose_error(ref, sols)['wheel_center_mm'] <= 1e-8


def test_condition_number_grows_past_the_node_warning_towards_the_toggle():
    cont = Continuation(stress_scene('trailing_arm_toggle'))
    design = cont.solve(0.0).condition
    near = cont.solve(TOGGLE_LIMIT_MM - 0.01).condition
    assert near > 1e4 > design                 # node parameter condition_warn, default 1e4
    assert near > 20 * design


@pytest.mark.parametrize('travel', [-80.0, 0.0, 45.0, 80.0])
def test_reported_condition_number_is_that_of_an_independent_jacobian(travel):
    scene = load_scene('five_link')
    sol = Continuation(scene).solve(travel)
    model = reference.build(scene)
    jac = reference.jacobian(model, sol.wheel_center, sol.rotation)[:5][:, FREE]
    assert sol.condition == pytest.approx(np.linalg.cond(jac), rel=1e-6)


def test_node_warns_near_the_toggle_with_its_default_condition_warn(ros_context, executor,
                                                                    probe):
    from linkage_ros.ros.node import SuspensionNode
    from linkage_ros.ros.testing import spin_until
    path = str(STRESS / 'trailing_arm_toggle.yaml')
    executor.add_node(SuspensionNode(context=ros_context, parameter_overrides=[
        Parameter('scene', value=path), Parameter('diagnostic_period', value=3600.0)]))
    near_m = (TOGGLE_LIMIT_MM - 0.01) / 1000.0
    probe.send(0.0, near_m)
    # At design: OK, nothing to say at once; near the toggle: WARN at once (level change).
    assert spin_until(executor, lambda: len(probe.statuses) == 1 and len(probe.poses) == 2)
    warn = probe.statuses[0]
    assert warn.level == DiagnosticStatus.WARN and 'condition number' in warn.message
    assert float(status_values(warn)['condition_max']) > 1e4
    assert len(probe.poses) == 2               # a warning still publishes the pose


# --- jumps and reversals --------------------------------------------------------------------

@pytest.mark.parametrize('method', METHODS)
@pytest.mark.parametrize('name', bundled_scenes())
def test_one_command_from_minus_80_to_plus_80_lands_on_the_fine_continuation_pose(name,
                                                                                  method):
    scene = load_scene(name)
    low, high, _ = scene.travel
    fine = sweep(scene, travel_range(0.0, high, 0.25), method='fast')
    cont = Continuation(scene, method=method)
    assert cont.solve(low).success
    jump = cont.solve(high)
    assert jump.success
    assert np.abs(jump.wheel_center - fine.wheel_center[-1]).max() <= 1e-9
    assert np.abs(jump.rotation - fine.rotation[-1]).max() <= 1e-12


@pytest.mark.parametrize('name', ['five_link', 'double_wishbone', 'macpherson'])
def test_a_single_unlimited_step_over_160_mm_keeps_the_branch(name):
    scene = load_scene(name)
    low, high, _ = scene.travel
    fine = sweep(scene, [high], method='fast')
    cont = Continuation(scene, max_step=1e6)            # no substeps unless Newton fails
    cont.solve(low)
    jump = cont.solve(high)
    assert jump.success
    assert np.abs(jump.wheel_center - fine.wheel_center[-1]).max() <= 1e-9


def test_1e5_random_commands_leave_the_pose_a_function_of_travel():
    scene = load_scene('five_link')
    travels = random_walk(100_000, *scene.travel[:2], seed=1)
    assert np.sum(np.diff(np.sign(np.diff(travels))) != 0) > 40_000     # reversals
    cont = Continuation(scene, method='fast')
    sols = [cont.solve(float(t)) for t in travels]
    assert all(s.success for s in sols)
    assert max(s.residual for s in sols) <= TOL + 1e-12
    table = sweep(scene, travels, method='fast')        # same travels, no history
    centers = np.array([s.wheel_center for s in sols])
    assert np.abs(centers - table.wheel_center).max() <= 1e-9
    home = cont.solve(0.0)
    assert np.abs(home.rotation - np.eye(3)).max() <= 1e-12
    assert np.abs(home.wheel_center - scene.wheel_center).max() <= 1e-9


def test_300_random_commands_with_the_paper_method_keep_the_pose_a_function_of_travel():
    scene = load_scene('five_link')
    travels = random_walk(300, *scene.travel[:2], seed=2)
    cont = Continuation(scene, method='paper')
    sols = [cont.solve(float(t)) for t in travels]
    assert all(s.success for s in sols)
    ref = reference.reference_poses(scene, travels)
    err = pose_error(ref, sols)
    assert err['wheel_center_mm'] <= 1e-9 and err['residual_mm'] <= 1e-9


# --- badly scaled scenes ------------------------------------------------------------------

def scaled_settings(scene, method):
    """Return settings whose lengths follow the scene size (the defaults are for about 1 m)."""
    scale = scene.size / 1000.0
    return {'method': method, 'tol': TOL * scale, 'max_step': 5.0 * scale,
            'min_step': 0.005 * scale}


@pytest.mark.parametrize('method', METHODS)
def test_submillimetre_scene_solves_its_range_with_default_settings(method):
    scene = stress_scene('five_link_submillimetre')     # links of 0.03 mm, in metres
    travels = np.linspace(*scene.travel[:2], 17)
    result = sweep(scene, travels, method=method)
    assert result.success, result.message
    err = reference.errors(reference.reference_poses(scene, travels), result.wheel_center,
                           result.rotation)
    assert err['residual_mm'] <= TOL and err['wheel_center_mm'] <= 10 * TOL


@pytest.mark.parametrize('method', METHODS)
def test_kilometre_scene_solves_with_default_settings(method):
    # Coordinates of 7.6e6 mm: float64 round-off (1e-9 mm) exceeds the 1e-10 mm default
    # tolerance, which the core must cope with rather than report "out of reach".
    scene = stress_scene('five_link_kilometres')
    travels = [2000.0, -2000.0]
    cont = Continuation(scene, method=method)
    sols = [cont.solve(t) for t in travels]
    assert all(s.success for s in sols), [s.message for s in sols]
    err = pose_error(reference.reference_poses(scene, travels), sols)
    assert err['wheel_center_mm'] <= 1e-14 * scene.size


@pytest.mark.parametrize('method', METHODS)
@pytest.mark.parametrize('name', ['five_link_kilometres', 'five_link_submillimetre'])
def test_scaled_scene_solves_its_whole_range_with_settings_scaled_to_its_size(name, method):
    scene = stress_scene(name)
    travels = np.linspace(*scene.travel[:2], 9)
    result = sweep(scene, travels, **scaled_settings(scene, method))
    assert result.success, result.message
    err = reference.errors(reference.reference_poses(scene, travels), result.wheel_center,
                           result.rotation)
    assert err['wheel_center_mm'] <= 1e-12 * scene.size
    assert err['camber_deg'] <= 1e-9


@pytest.mark.parametrize('method', METHODS)
def test_link_length_ratio_1e4_solves_the_range_and_reverses(method):
    scene = stress_scene('five_link_length_ratio')     # 3 km tie rod, 300 mm lower rear link
    travels = [-50.0, -40.0, 80.0, -80.0, 0.0]
    cont = Continuation(scene, method=method)
    sols = [cont.solve(t) for t in travels]
    assert all(s.success for s in sols), [s.message for s in sols]
    err = pose_error(reference.reference_poses(scene, travels), sols)
    # Round-off at the 3e6 mm body end of the tie rod is 5e-10 mm.
    assert err['residual_mm'] <= 1e-8 and err['wheel_center_mm'] <= 1e-7


@pytest.mark.parametrize('method, bound', [('fast', TOL), ('paper', 1e-7)])
def test_third_point_almost_on_the_spin_axis(method, bound):
    # The paper variant locates joints by eqs. 5-7, which divide by the M-N-P triangle's
    # 0.15 mm height: its step test (eqs. 11-12) lets residuals 1e2-1e3 times tol through.
    scene = stress_scene('five_link_p_near_axis')
    travels = travel_range(-80.0, 80.0, 10.0)
    result = sweep(scene, travels, method=method)
    assert result.success, result.message
    err = reference.errors(reference.reference_poses(scene, travels), result.wheel_center,
                           result.rotation)
    assert err['residual_mm'] <= bound and err['wheel_center_mm'] <= bound
    assert result.residual.max() == pytest.approx(err['residual_mm'], rel=0.1, abs=1e-12)


# --- perturbed hardpoints -----------------------------------------------------------------

@pytest.mark.parametrize('name', ['five_link', 'double_wishbone', 'macpherson'])
def test_hardpoints_moved_by_1e_9_mm_move_the_outputs_continuously(name):
    scene = load_scene(name)
    rng = np.random.default_rng(7)
    shift = rng.normal(size=(hardpoint_count(scene), 3))
    shift *= 1e-9 / np.linalg.norm(shift, axis=1, keepdims=True)
    moved = perturbed(scene, shift)
    travels = travel_range(-80.0, 80.0, 20.0)
    a, b = (sweep(s, travels, tol=1e-12) for s in (scene, moved))
    conds = np.array([Continuation(scene).solve(t).condition for t in travels])
    # A 1e-9 mm input change moves the pose by at most condition x 1e-9 mm.
    assert np.abs(a.wheel_center - b.wheel_center).max(axis=1) == pytest.approx(
        np.zeros(len(travels)), abs=1e-9 * conds.max())
    assert np.abs(a.camber - b.camber).max() <= 1e-9 * conds.max() / scene.size
    assert np.abs(a.toe - b.toe).max() <= 1e-9 * conds.max() / scene.size


# --- random valid scenes --------------------------------------------------------------------

BASES = ('five_link', 'double_wishbone', 'macpherson')
FAR_MM = 250.0    # asked-for travel: beyond +-80 mm most random scenes meet a limit
REF_LIMIT_STEP_MM = 0.25   # the reference walk's step towards a limit


@settings(max_examples=10, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(base=st.sampled_from(BASES),
       offsets=st.lists(st.floats(-40.0, 40.0), min_size=36, max_size=36))
@example(base='double_wishbone', offsets=[   # a fold at -243.634 mm the 0.76 mm walk jumped
    40.0, 0.0, -5.447360628217382, 0.0, 0.0, 0.0, 0.0, -17.628388731155923, 20.201702732609164,
    -29.231146446414066, 24.186798522223967, 0.0, 37.09610607627552, 36.45627524253625, -39.0,
    0.0, -27.046606621429007, -38.46984728703978, 0.0, -19.444869219215338,
    -31.278228551211953, 38.813722094767456, -36.949836269631625, -13.83494918908475,
    21.23001197006785, 0.0, 20.0, 0.0, -34.92857809582176, 0.1] + [0.0] * 6)
def test_random_valid_scene_solves_every_reachable_travel_like_the_reference(base, offsets):
    scene = load_scene(base)
    try:
        scene = perturbed(scene, np.reshape(offsets, (12, 3))[:hardpoint_count(scene)])
    except SceneError:
        assume(False)
    reach = {}
    for end in (FAR_MM, -FAR_MM):
        sol = Continuation(scene).solve(end)
        reach[end] = end if sol.success else sol.reachable[1 if end > 0 else 0]
    low, high = reach[-FAR_MM], reach[FAR_MM]
    assume(high - low > 1.0)
    # Every reachable travel solves: the table over the range found, short of its limits.
    travels = np.linspace(low + LIMIT_TOL_MM, high - LIMIT_TOL_MM, 9)
    result = sweep(scene, travels)
    assert result.success, result.message
    assert result.residual.max() <= TOL + 1e-12
    ref = reference.reference_poses(scene, travels)
    assert ref.success.all()
    err = reference.errors(ref, result.wheel_center, result.rotation)
    # Near a limit a 1e-10 mm residual is amplified by 1 / sqrt(distance to the limit).
    assert err['wheel_center_mm'] <= 1e-6
    # A limit the core reports is where the independent walk and bisection find it. The
    # walk's default step (1/1000 of the size, 0.76 mm) can jump a fold to the other branch
    # and walk on (double_wishbone perturbed, rebound limit -243.634 mm): a third of it.
    for end, found in reach.items():
        if found != end:
            independent, _ = reference.reachable_limit(scene, math.copysign(1, end),
                                                       step=REF_LIMIT_STEP_MM, far=FAR_MM + 1)
            assert found == pytest.approx(independent, abs=LIMIT_TOL_MM)
