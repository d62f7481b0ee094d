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
import importlib
import inspect
from pathlib import Path
import pkgutil

from linkage_ros.core.base import camber_toe, compiled, matrix_from_quaternion
from linkage_ros.core.model import bundled_scenes, load_scene
from linkage_ros.core.solve import Continuation, kernel, state, sweep
from linkage_ros.core.solve.mechanism import carrier_points, length_errors, linearize
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


def _dispatchers():
    """Return every numba Dispatcher defined in the core, found by importing every module."""
    from numba.core.dispatcher import Dispatcher
    import linkage_ros.core as core
    found = []
    for info in pkgutil.walk_packages(core.__path__, core.__name__ + '.'):
        module = importlib.import_module(info.name)
        found += [v for v in vars(module).values()
                  if isinstance(v, Dispatcher) and v.__module__ == module.__name__]
    return found


def test_every_kernel_is_cached_under_the_one_key_of_every_kernel_source():
    # numba keys a function's cache on its own file alone, yet kernels compile in other
    # files' functions (so3.py's rotations): the one key must cover every file that holds a
    # compiled function, found here by what imports define, not by compiled.py's own scan
    dispatchers = _dispatchers()
    files = {Path(inspect.getfile(d.py_func)).resolve() for d in dispatchers}
    files |= compiled.JITABLE   # the files of functions that kernels compile in (@jitable)
    assert files | {Path(compiled.__file__).resolve()} == set(compiled.kernel_sources())
    expected = hashlib.sha256()
    for path in sorted(files | {Path(compiled.__file__).resolve()}):
        expected.update(str(path.relative_to(compiled.CORE)).encode() + b'\0')
        expected.update(path.read_bytes() + b'\0')
    for dispatcher in dispatchers:
        locator = dispatcher._cache._impl.locator
        assert isinstance(locator, compiled.LOCATORS), dispatcher.__qualname__
        assert locator.get_source_stamp() == expected.hexdigest()


def test_an_edit_of_any_kernel_source_changes_the_key_and_of_another_file_not(tmp_path):
    core = tmp_path / 'core'
    for path in compiled.kernel_sources():
        target = core / path.relative_to(compiled.CORE)
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(path.read_bytes())
    (core / 'model').mkdir(exist_ok=True)
    (core / 'model' / 'scene.py').write_text('"""No compiled function here."""\n')
    before = compiled.digest_of(compiled.kernel_sources(core), core)
    (core / 'model' / 'scene.py').write_text('"""Still none, edited."""\n')
    assert compiled.digest_of(compiled.kernel_sources(core), core) == before
    so3_copy = core / 'base' / 'so3.py'
    so3_copy.write_text(so3_copy.read_text() + '# an edit\n')
    assert compiled.digest_of(compiled.kernel_sources(core), core) != before


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
