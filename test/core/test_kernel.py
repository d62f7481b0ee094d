# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The compiled one-command path against the batched sweep and the paper's method.

The one-command path is kernel.walk under Continuation.solve, the batched sweep
kernel.step_many; on every bundled and stress scene.

Expected: the same carrier joints to 1e-9 mm (scenes of about a metre; for the kilometre
stress scene, float64 round-off alone is 1.7e-9 mm, so the bound scales with the size).
"""

import hashlib
from pathlib import Path

from linkage_ros.core.base import camber_toe, force_table, matrix_from_quaternion, so3
from linkage_ros.core.model import bundled_scenes, load_scene
from linkage_ros.core.solve import (body_kernel, Continuation, element_kernel, jacobian_kernel,
                                    kernel, state, sweep)
from linkage_ros.core.solve.mechanism import carrier_points, length_errors, linearize
from linkage_ros.core.vary import pose_kernel, variant_kernel
import numpy as np
import pytest

STRESS = Path(__file__).resolve().parents[2] / 'config' / 'stress'
SCENES = bundled_scenes() + sorted(str(p) for p in STRESS.glob('*.yaml'))


# eqs. 5-7 of the paper divide by the height of the M-N-P triangle, nearly zero in this
# scene: there the paper's joints hold to 1e-7 mm only (test_stability, README).
PAPER_BOUND = {'five_link_p_near_axis': 1e-7}


def reachable_travels(scene, settings, count=33):
    """
    Return count travels across the scene's travel block.

    They stop 1 mm (scaled) short of a travel limit inside it (the toggle and vertical-link
    stress scenes have one).
    """
    scale = settings['max_step'] / 5.0
    ends = []
    for end in scene.travel[:2]:
        probe = Continuation(scene, **settings).solve(end)
        ends.append(end if probe.success else
                    probe.reachable[end > 0] - scale * (1.0 if end > 0 else -1.0))
    return np.linspace(*ends, count)


def scaled(scene):
    """Return the default settings for a scene of about 1 m, scaled to this one's size."""
    scale = max(scene.size / 1000.0, 1e-6)
    return {'tol': 1e-10 * scale, 'max_step': 5.0 * scale, 'min_step': 0.005 * scale}


@pytest.mark.parametrize('name', SCENES, ids=lambda n: Path(n).stem)
def test_one_command_at_a_time_equals_the_batched_sweep_and_the_paper_method(name):
    scene = load_scene(name)
    settings = scaled(scene)
    travels = reachable_travels(scene, settings)
    cont = Continuation(scene, **settings)
    one = [cont.solve(t) for t in travels]
    assert all(s.success for s in one), [s.message for s in one if not s.success][:1]
    joints = np.array([carrier_points(cont.mech, s.wheel_center, s.rotation) for s in one])
    batched = sweep(scene, travels, **settings)
    paper = sweep(scene, travels[::4], method='paper', **settings)
    assert batched.success and paper.success
    bound = 1e-9 * max(1.0, scene.size / 1000.0)
    assert np.abs(joints - batched.joints).max() <= bound
    assert np.abs(joints[::4] - paper.joints).max() <= max(
        bound, PAPER_BOUND.get(scene.name, 0.0))
    assert max(s.residual for s in one) <= settings['tol'] * 10


@pytest.mark.parametrize('module, compiled_in, attribute', [
    (kernel, 'so3.py', 'SO3_DIGEST'), (element_kernel, 'so3.py', 'SO3_DIGEST'),
    (kernel, 'jacobian_kernel.py', 'JACOBIAN_KERNEL_DIGEST'),
    (element_kernel, 'jacobian_kernel.py', 'JACOBIAN_KERNEL_DIGEST'),
    (element_kernel, 'force_table.py', 'FORCE_TABLE_DIGEST'),
    (pose_kernel, 'so3.py', 'SO3_DIGEST'),
    (pose_kernel, 'jacobian_kernel.py', 'JACOBIAN_KERNEL_DIGEST'),
    (body_kernel, 'so3.py', 'SO3_DIGEST'),
    (variant_kernel, 'so3.py', 'SO3_DIGEST'), (variant_kernel, 'kernel.py', 'KERNEL_DIGEST')],
    ids=lambda v: getattr(v, '__name__', v))
def test_a_kernel_module_names_the_digest_of_each_file_it_compiles_in(module, compiled_in,
                                                                      attribute):
    # numba's cache follows each file alone: a module that compiles another file's functions
    # in (so3.py's rotations, jacobian_kernel.py's linear algebra) must change when it does.
    source = {'so3.py': so3, 'jacobian_kernel.py': jacobian_kernel, 'kernel.py': kernel,
              'force_table.py': force_table}[compiled_in]
    digest = hashlib.sha256(Path(source.__file__).read_bytes()).hexdigest()
    name = Path(module.__file__).name
    assert getattr(module, attribute) == digest, (
        f"{compiled_in} changed: set {attribute} = '{digest}' in {name}, so that numba "
        'recompiles the kernels that call it')


def test_the_state_accessors_read_what_the_kernels_write():
    # kernel.walk fills a state (compiled code, kernel.views); state.py reads it (Python).
    cont = Continuation(load_scene('double_wishbone'))
    walked = kernel.walk(tuple(cont.setup), cont.state, 30.0, 4.0, 0.0, 0.0)
    assert walked.outcome == kernel.REACHED and walked.steps == 6 and walked.high == 30.0
    center, rotation, jac = kernel.views(walked.state)
    assert state.travel(walked.state) == 30.0 and state.rack(walked.state) == 4.0
    assert np.array_equal(state.center(walked.state), center)
    assert np.array_equal(state.rotation(walked.state), rotation)
    assert np.array_equal(state.jacobian(walked.state), jac)
    # the report against independent computations of the same pose
    mech = cont.mech
    _, expected_jac = linearize(mech, center, rotation, 4.0)
    assert np.array_equal(jac, expected_jac)
    residual, condition, camber, toe = state.report(walked.state)
    assert residual == pytest.approx(length_errors(mech, center, rotation, 4.0), abs=1e-15)
    assert condition == pytest.approx(np.linalg.cond(jac[:, list(kernel.FREE)]), rel=1e-9)
    assert (camber, toe) == pytest.approx(camber_toe(rotation @ mech.spin_axis, 1.0), abs=1e-15)
    assert np.allclose(matrix_from_quaternion(state.quaternion(walked.state)), rotation,
                       atol=1e-15)
    many = np.stack([walked.state, cont.state])
    assert np.array_equal(state.centers(many)[0], center)
    assert np.array_equal(state.rotations(many)[1], np.eye(3))
    assert state.travels(many).tolist() == [30.0, 0.0]
