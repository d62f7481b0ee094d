# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The extended-precision 6-DOF reference and the baseline solvers of linkage-bench.

Expected values: the published reference rows of the bundled scenes (refdata, agreed by
independent solvers), the analytic toggle of a trailing arm, and identities (design pose at
travel 0, orthonormal rotations, a known displacement measured as such).
"""

import math
from pathlib import Path

from linkage_ros.bench import peers, reference
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import sweep, travel_range
import numpy as np
import pytest
from test_stability import stress_scene, TOGGLE_LIMIT_MM


def reference_rows(scene):
    """{column: array} of the scene file's published reference table."""
    table = scene.extras['reference']
    rows = np.array(table['rows'], dtype=float)
    return {name: rows[:, i] for i, name in enumerate(table['columns'])}


@pytest.mark.parametrize('name', ['five_link', 'double_wishbone'])
def test_reference_camber_and_toe_equal_the_published_rows_to_their_4_decimals(name):
    scene = load_scene(name)
    rows = reference_rows(scene)
    ref = reference.reference_poses(scene, rows['travel_mm'])
    camber, toe = reference.wheel_angles(ref.model, ref.rotation)
    assert np.degrees(camber.astype(float)) == pytest.approx(rows['camber_deg'], abs=5e-5)
    assert np.degrees(toe.astype(float)) == pytest.approx(rows['toe_deg'], abs=5e-5)


def test_reference_lateral_wheel_centre_shift_equals_the_published_rows():
    scene = load_scene('double_wishbone')
    rows = reference_rows(scene)
    ref = reference.reference_poses(scene, rows['travel_mm'])
    dy = (ref.center[:, 1] - ref.model.m0[1]).astype(float)
    assert dy == pytest.approx(rows['wheel_center_dy_mm'], abs=5e-4)


@pytest.mark.parametrize('name', ['five_link', 'double_wishbone', 'macpherson'])
def test_reference_residual_is_at_the_extended_precision_floor(name):
    scene = load_scene(name)
    ref = reference.reference_poses(scene, travel_range(-80.0, 80.0, 10.0))
    assert ref.success.all()
    assert ref.residual.max() <= 1e-17 * scene.size     # float64 would leave about 1e-13 mm


def test_reference_at_zero_travel_is_the_design_pose():
    scene = load_scene('five_link')
    ref = reference.reference_poses(scene, [0.0])
    assert np.abs(ref.center[0] - ref.model.m0).max() <= 1e-16
    assert np.abs(ref.rotation[0] - np.eye(3)).max() <= 1e-18


def test_reference_rotations_are_orthonormal_in_extended_precision():
    ref = reference.reference_poses(load_scene('macpherson'), [-80.0, -40.0, 40.0, 80.0])
    for rot in ref.rotation:
        assert np.abs(rot @ rot.T - np.eye(3)).max() <= 1e-17


@pytest.mark.parametrize('name', ['five_link', 'double_wishbone', 'macpherson'])
def test_core_fast_sweep_agrees_with_the_reference_to_its_tolerance(name):
    scene = load_scene(name)
    travels = travel_range(-80.0, 80.0, 5.0)
    ref = reference.reference_poses(scene, travels)
    result = sweep(scene, travels, method='fast')
    err = reference.errors(ref, result.wheel_center, result.rotation)
    assert err['residual_mm'] <= 1e-10          # Settings().tol: the fast stopping residual
    assert err['wheel_center_mm'] <= 1e-9
    assert err['camber_deg'] <= 1e-9 and err['toe_deg'] <= 1e-9


def test_errors_measure_a_known_wheel_centre_displacement():
    scene = load_scene('five_link')
    ref = reference.reference_poses(scene, [30.0])
    center = ref.center.astype(float) + [0.0, 0.0, 1e-6]
    err = reference.errors(ref, center, ref.rotation.astype(float))
    assert err['wheel_center_mm'] == pytest.approx(1e-6, rel=1e-6)
    # A link of unit direction u lengthens by u_z * 1e-6 mm (to first order).
    model = ref.model
    links = (ref.center[0] + model.offsets[model.dist_point] @ ref.rotation[0].T
             - model.dist_base).astype(float)
    u_z = links[:, 2] / np.linalg.norm(links, axis=1)
    assert err['residual_mm'] == pytest.approx(1e-6 * np.abs(u_z).max(), rel=1e-6)
    assert err['camber_deg'] <= 1e-13


def test_reference_shares_no_code_with_the_core_solvers():
    # Independent by construction: the module imports no part of linkage_ros at all (scenes
    # come in as loaded Scene objects).
    source = Path(reference.__file__).read_text()
    imports = [line for line in source.splitlines() if line.startswith(('import ', 'from '))]
    assert not [line for line in imports if 'linkage_ros' in line or line.startswith('from .')]
    scene = load_scene('five_link')
    ref = reference.reference_poses(scene, [-80.0, 80.0])
    assert ref.success.all()
    assert reference.reachable_limit(stress_scene('trailing_arm_toggle'), 1)[0] > 0


def test_reachable_limit_finds_the_analytic_toggle_of_the_trailing_arm():
    limit, _ = reference.reachable_limit(stress_scene('trailing_arm_toggle'), 1)
    assert limit == pytest.approx(TOGGLE_LIMIT_MM, abs=1e-3)


def test_reachable_limit_is_infinite_where_the_walk_never_stops():
    limit, _ = reference.reachable_limit(stress_scene('trailing_arm_toggle'), -1, far=300.0)
    assert limit == -math.inf


@pytest.mark.parametrize('solver', [peers.LUNewton, peers.RootHybr,
                                    peers.LeastSquares6Dof])
@pytest.mark.parametrize('name', ['five_link', 'macpherson'])
def test_each_baseline_reaches_the_reference_at_a_tight_tolerance(solver, name):
    scene = load_scene(name)
    travels = travel_range(0.0, 80.0, 5.0)[1:]
    ref = reference.reference_poses(scene, travels)
    baseline = solver(scene, 1e-10)
    out = [baseline.solve(float(t)) for t in travels]
    assert all(o[3] for o in out)
    err = reference.errors(ref, np.array([o[0] for o in out]), np.array([o[1] for o in out]))
    assert err['residual_mm'] <= 1e-10
    assert err['wheel_center_mm'] <= 1e-9


def test_a_baseline_that_fails_says_so_and_returns_no_pose():
    baseline = peers.LUNewton(stress_scene('trailing_arm_toggle'), 1e-10)
    center, rotation, _, converged = baseline.solve(60.0)    # beyond the 27.2 mm toggle
    assert (center, rotation, converged) == (None, None, False)
