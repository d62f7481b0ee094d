# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A singular mechanism is an answer with a status, never an exception (issue 23 item 2).

test/data/five_link_singular.yaml is five_link with its tie rod replaced by a copy of
upper_front: two links alike, a Jacobian of rank 4 at every pose. It loads; every travel
but the design one is then out of reach with Status.SINGULAR, through Continuation.solve
and sweep(), by both methods; the design position itself is singular by design_condition.
"""

import os
from pathlib import Path
import subprocess
import sys

from linkage_ros.core.base import Status
from linkage_ros.core.model import bundled_scenes, load_scene
from linkage_ros.core.solve import (arclength, compile_scene, Continuation, design_condition,
                                    design_jacobian, linearize, METHODS, paper_method, pose_newton,
                                    SINGULAR_CONDITION, sweep, travel_range)
import numpy as np
import pytest

SINGULAR = Path(__file__).resolve().parents[1] / 'data' / 'five_link_singular.yaml'


@pytest.fixture(scope='module')
def scene():
    return load_scene(SINGULAR)


def independent_scaled_condition(scene):
    """Return numpy's condition number of the design J_free, rotation columns / the lever."""
    mech = compile_scene(scene)
    _, jac = linearize(mech, scene.wheel_center, np.eye(3))
    lever = np.max(np.linalg.norm(scene.carrier_offsets, axis=1))
    return np.linalg.cond(np.column_stack((jac[:, :2], jac[:, 3:] / lever)))


@pytest.mark.parametrize('name', ['five_link', 'macpherson', 'trailing_arm_toggle'])
def test_design_condition_of_a_sound_scene_is_numpys_and_far_below_the_threshold(name):
    path = name if name != 'trailing_arm_toggle' else (
        Path(__file__).resolve().parents[2] / 'config' / 'stress' / f'{name}.yaml')
    scene = load_scene(path)
    found = design_condition(scene)
    assert found == pytest.approx(independent_scaled_condition(scene), rel=1e-9)
    assert found < 100.0 < SINGULAR_CONDITION


def test_design_condition_does_not_depend_on_the_scene_units_or_scale():
    # five_link_submillimetre is five_link scaled by 1e-4: the same mechanism.
    small = load_scene(Path(__file__).resolve().parents[2] / 'config' / 'stress'
                       / 'five_link_submillimetre.yaml')
    assert design_condition(small) == pytest.approx(design_condition(load_scene('five_link')),
                                                    rel=1e-6)


def test_design_condition_of_the_singular_scene_is_beyond_the_threshold(scene):
    # numpy's SVD of the same matrix: smallest singular value 0 to rounding (1e16 and more)
    assert independent_scaled_condition(scene) > 1e15
    assert design_condition(scene) > SINGULAR_CONDITION


@pytest.mark.parametrize('method', METHODS)
@pytest.mark.parametrize('travel', [10.0, -0.5, 1e-3])
def test_a_travel_of_the_singular_scene_is_refused_as_singular(scene, method, travel):
    cont = Continuation(scene, method=method)
    sol = cont.solve(travel)
    assert not sol.success and sol.status == Status.SINGULAR
    assert sol.wheel_center is None and 'singular' in sol.message
    assert cont.travel == 0.0                       # the design position is kept
    assert cont.solve(0.0).success                  # and is still an answer


@pytest.mark.parametrize('method', METHODS)
def test_a_rack_on_the_singular_scene_is_refused_as_singular(scene, method):
    sol = Continuation(scene, method=method).solve(0.0, 5.0)
    assert not sol.success and sol.status == Status.SINGULAR


@pytest.mark.parametrize('method', METHODS)
def test_a_sweep_of_the_singular_scene_is_an_empty_table_with_the_status(scene, method):
    result = sweep(scene, travel_range(-10.0, 10.0, 1.0), method=method)
    assert not result.success and result.status == Status.SINGULAR
    assert len(result.travel) == 0 and result.wheel_center.shape == (0, 3)
    assert 'singular' in result.message


def test_the_design_position_of_the_singular_scene_has_no_slope_and_says_nan(scene):
    mech = compile_scene(scene)
    _, jac = linearize(mech, scene.wheel_center, np.eye(3))
    d_center, d_omega = pose_newton.slope_of(jac)
    assert np.isnan(d_center[:2]).all() and np.isnan(d_omega).all()


def test_the_arclength_path_answers_singular_where_the_curve_has_no_tangent(scene):
    mech = compile_scene(scene)
    status, travel = arclength.walk(mech, scene.wheel_center, np.eye(3), 0.0, 10.0, 1e-9, 25)
    assert status == Status.SINGULAR and travel == 0.0


def test_gauss_jordan_says_none_for_a_singular_matrix():
    a = np.array([[1.0, 2.0], [2.0, 4.0]])
    assert paper_method.gauss_jordan(a, [1.0, 2.0]) is None


def all_scene_files():
    """Return every bundled scene name and every stress scene path, and the singular scene."""
    stress = sorted((Path(__file__).resolve().parents[2] / 'config' / 'stress').glob('*.yaml'))
    return list(bundled_scenes()) + stress + [SINGULAR]


@pytest.mark.parametrize('name', all_scene_files(), ids=str)
def test_the_numpy_design_jacobian_is_the_kernel_s_at_the_design_position(name):
    # design_jacobian is kernel.linearize written out at R = I, rack 0 for numpy: the two
    # formulations agree to rounding, strut lines (macpherson) and steered links included.
    mech = compile_scene(load_scene(name))
    _, kernel_jac = linearize(mech, mech.design_center, np.eye(3))
    scale = np.abs(kernel_jac).max()
    assert np.abs(design_jacobian(mech) - kernel_jac).max() <= 1e-12 * scale


def test_the_singular_scene_loads_with_one_warning_that_names_its_file(scene):
    assert len(scene.warnings) == 1
    assert scene.warnings[0].startswith(f'{SINGULAR}: the design position is singular (scaled '
                                        'condition number ')
    assert 'only travel 0 can be solved' in scene.warnings[0]


@pytest.mark.parametrize('name', all_scene_files()[:-1], ids=str)
def test_no_bundled_or_stress_scene_is_warned_of_as_singular(name):
    assert not [w for w in load_scene(name).warnings if 'singular' in w]


def test_a_scene_load_compiles_no_kernel_on_a_cold_cache(tmp_path):
    # The warning is computed at every load, before the node compiles the kernels in a child
    # process (interruptibly): the load itself must not compile one (5 s, uninterruptible).
    script = ('from linkage_ros.core.model.scene import load_scene; import sys; '
              'print(len(load_scene(sys.argv[1]).warnings))')
    env = {**os.environ, 'NUMBA_CACHE_DIR': str(tmp_path / 'cache')}
    done = subprocess.run([sys.executable, '-c', script, str(SINGULAR)], env=env,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stdout == '1\n'
    assert not [p for p in (tmp_path / 'cache').rglob('*') if p.is_file()]
