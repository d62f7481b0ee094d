# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Tolerance stack-up (linkage_ros.study.tolerance): Monte Carlo against first order.

Also seeds, variants out of reach, and linkage-study tolerance's table, bar and picture.
"""

import math
from pathlib import Path
import subprocess
import sys

from linkage_ros.core.base import camber_toe, LinkageError
from linkage_ros.core.solve import compile_scene, Continuation, kernel, lengthened, radii, sweep
from linkage_ros.core.vary import load_design, scene_with
from linkage_ros.study.executor import executor
from linkage_ros.study.tables import TOLERANCE_COLUMNS
from linkage_ros.study.tolerance import (BATCH, length_sigmas, perturbed, problem, sigmas,
                                         solve_batch, tolerance)
import numpy as np
import pytest
from scipy.optimize import root
from scipy.spatial.transform import Rotation

TRAVELS = np.linspace(-50.0, 50.0, 11)
PROG = str(Path(sys.executable).parent / 'linkage-study')


def run(*args, cwd=None):
    """Run linkage-study; return (status, stdout, stderr)."""
    done = subprocess.run([PROG, *args], capture_output=True, text=True, timeout=600, cwd=cwd)
    return done.returncode, done.stdout, done.stderr


@pytest.mark.parametrize('name', ['five_link', 'macpherson'])
def test_at_small_sigma_the_monte_carlo_spread_is_the_first_order_one(name):
    # sigma 0.05 mm: the quantities are linear in the hardpoints to about sigma / 100 mm
    # (1e-3 of the spread), so the sample std estimates rss_std. The relative standard
    # error of a normal sample's std is 1 / sqrt(2 (N - 1)) (0.78 % for N = 8192); the
    # bound is 4 of them, and the mean is within 4 standard errors of the nominal value.
    design = load_design(name)
    samples = 2 * BATCH
    result = tolerance(problem(design, sigmas(design, 0.05), samples, TRAVELS, seed=7))
    assert result.out_of_reach.sum() == 0
    error = 1.0 / math.sqrt(2 * (samples - 1))
    ratio = result.std / result.rss_std
    assert np.abs(ratio - 1.0).max() < 4 * error, ratio
    assert np.all(np.abs(result.mean - result.nominal) < 4 * result.rss_std / math.sqrt(samples))
    # the spread of a normal distribution between its 1st and 99th percentiles
    width = (result.p99 - result.p01) / (2 * 2.3263478740408408 * result.rss_std)
    assert np.abs(width - 1.0).max() < 0.05, width


def test_the_same_seed_gives_the_same_numbers_and_another_seed_others():
    design = load_design('double_wishbone')
    spread = sigmas(design, 0.1)
    first = tolerance(problem(design, spread, 300, TRAVELS, seed=11))
    again = tolerance(problem(design, spread, 300, TRAVELS, seed=11))
    other = tolerance(problem(design, spread, 300, TRAVELS, seed=12))
    assert np.array_equal(first.values, again.values)
    assert np.array_equal(first.std, again.std) and np.array_equal(first.p99, again.p99)
    assert not np.array_equal(first.values, other.values)


def test_batches_give_the_same_bits_in_this_process_and_in_a_pool_of_processes():
    design = load_design('five_link')
    prob = problem(design, sigmas(design, 0.2), BATCH + 100, [-30.0, 30.0], seed=4)
    here = tolerance(prob)
    with executor(None, workers=2) as pool:
        there = tolerance(prob, pool)
    assert np.array_equal(here.values, there.values)
    assert np.array_equal(here.std, there.std)


def test_variants_without_spread_are_the_design_as_linkage_sweep_solves_it():
    design = load_design('macpherson')
    fixed = sigmas(design, 1.0, dict.fromkeys(design.names, 0.0))
    prob = problem(design, fixed, 3, TRAVELS)
    values = solve_batch((prob, 0))
    table = sweep(design.scene, TRAVELS)
    expected = np.column_stack([np.degrees(table.camber), np.degrees(table.toe),
                                table.wheel_center])
    for variant in values:
        np.testing.assert_allclose(variant, expected, rtol=0, atol=1e-9)


def test_each_variant_is_what_continuation_solves_and_those_out_of_reach_are_counted():
    # Near five_link's bump limit (387.469 mm at design) a 2 mm spread puts some variants'
    # limits below the travel asked for: they are counted, not solved from another branch.
    design = load_design('five_link')
    prob = problem(design, sigmas(design, 2.0), 48, [0.0, 384.0], seed=3)
    values = solve_batch((prob, 0))
    lost = 0
    for points, variant in zip(perturbed(prob, 0)[0], values):
        solution = Continuation(scene_with(design, points)).solve(384.0)
        if not solution.success:
            lost += 1
            assert np.isnan(variant[1]).all()
            continue
        expected = [math.degrees(solution.camber), math.degrees(solution.toe),
                    *solution.wheel_center]
        np.testing.assert_allclose(variant[1], expected, rtol=0, atol=1e-8)
    assert 0 < lost < len(values)
    result = tolerance(prob)
    assert result.out_of_reach[1].tolist() == [lost] * 5 and result.out_of_reach[0].sum() == 0


def reassembled_toe_camber(scene, longer):
    """
    Return (toe, camber) deg at design travel of a scene of links whose lengths are longer.

    longer (c,) mm per constraint. Independent of the package's solvers: scipy's root on
    |M + R (b - M0) - A| = |b - A| + longer, unknowns M_x, M_y and R's rotation vector, M_z
    kept at design (travel 0), from the design pose.
    """
    m0 = scene.wheel_center
    base = np.array([c.base[0] for c in scene.constraints])
    offset = np.array([c.carrier for c in scene.constraints]) - m0
    length = np.linalg.norm(offset + m0 - base, axis=1) + longer

    def residuals(x):
        rotation = Rotation.from_rotvec(x[2:]).as_matrix()
        joints = np.array([x[0], x[1], m0[2]]) + offset @ rotation.T
        return np.linalg.norm(joints - base, axis=1) - length

    found = root(residuals, np.array([m0[0], m0[1], 0.0, 0.0, 0.0]), tol=1e-14)
    assert found.success and np.abs(residuals(found.x)).max() < 1e-11, found
    axis = Rotation.from_rotvec(found.x[2:]).as_matrix() @ (m0 - scene.spin_axis_point)
    camber, toe = camber_toe(axis / np.linalg.norm(axis), scene.side_sign)
    return math.degrees(toe), math.degrees(camber)


def test_a_tie_rod_length_tolerance_spreads_static_toe_by_its_sensitivity_times_sigma():
    # The static toe spread is d(toe)/d(tie-rod length) x sigma to first order. The rate is
    # a central difference of two designs re-assembled at travel 0 with the tie rod h
    # longer and shorter (scipy, above): truncation (h / 400 mm)^2 ~ 1e-9 relative, rounding
    # 1e-12 mm / h ~ 1e-10. The study's first order (rss_std) holds it to 1e-6; its Monte
    # Carlo std to 4 standard errors of a sample std (1 / sqrt(2 (N - 1))), sigma 0.05 mm
    # being linear to about 1e-4 of the spread.
    design = load_design('five_link')
    scene, sigma, h = design.scene, 0.05, 0.01
    tie_rod = [c.name for c in scene.constraints].index('tie_rod')
    longer = np.zeros(len(scene.constraints))
    longer[tie_rod] = h
    (toe_up, camber_up), (toe_down, camber_down) = (
        reassembled_toe_camber(scene, sign * longer) for sign in (1.0, -1.0))
    toe_rate, camber_rate = (toe_up - toe_down) / (2 * h), (camber_up - camber_down) / (2 * h)
    assert abs(toe_rate) > 0.01   # deg/mm: the tie rod steers
    lengths = length_sigmas(design, {'tie_rod.length': sigma})
    assert lengths.tolist() == [0.0, 0.0, 0.0, 0.0, sigma]
    samples = 2 * BATCH
    no_points = np.zeros_like(design.values)
    result = tolerance(problem(design, no_points, samples, [-30.0, 0.0, 30.0], seed=5,
                               lengths=lengths))
    assert result.out_of_reach.sum() == 0
    toe, camber, static = 1, 0, 1   # SWEEP_COLUMNS, the travel 0 row
    np.testing.assert_allclose(result.rss_std[static, toe], abs(toe_rate) * sigma, rtol=1e-6)
    np.testing.assert_allclose(result.rss_std[static, camber], abs(camber_rate) * sigma,
                               rtol=1e-6)
    error = 1.0 / math.sqrt(2 * (samples - 1))
    assert abs(result.std[static, toe] / (abs(toe_rate) * sigma) - 1.0) < 4 * error
    assert result.std[static, 4] == 0.0   # travel is imposed: M_z does not spread


def test_an_arms_length_tolerance_moves_its_ball_that_far_from_the_axis():
    # double_wishbone's arms are circles: a pivot-to-ball tolerance changes the radius about
    # the arm's axis by delta and keeps the ball's place along it (l^2 - rho^2).
    scene = load_design('double_wishbone').scene
    layout, mech = scene.layout, compile_scene(scene)
    delta = np.linspace(0.1, 0.5, len(scene.constraints))
    moved = lengthened(layout, mech.equations, mech.design_center, delta)
    rho = radii(layout, mech.equations, mech.design_center)
    arm = np.array([scene.constraints[c].type == 'circle' for c in layout.constraint])
    assert arm.sum() == 4
    before, after = mech.equations[:, kernel.LENGTH], moved[:, kernel.LENGTH]
    grown = rho + delta[layout.constraint]
    np.testing.assert_allclose(after[arm] ** 2 - grown[arm] ** 2,   # mm^2, of 1e5: rounding
                               before[arm] ** 2 - rho[arm] ** 2, rtol=0, atol=1e-9)
    np.testing.assert_allclose(after[~arm], before[~arm] + delta[layout.constraint[~arm]],
                               rtol=1e-15)


def test_a_length_the_scene_lacks_is_refused_naming_its_lengths():
    design = load_design('macpherson')
    with pytest.raises(LinkageError, match='strut.length: not a length of the scene '
                       'macpherson .its lengths: .*tie_rod.length'):
        length_sigmas(design, {'strut.length': 0.1})


def test_linkage_study_tolerance_writes_the_table_a_progress_bar_and_the_picture(tmp_path):
    status, out, err = run('tolerance', 'five_link', '--sigma', '0.05', '--samples', '500',
                           '--travel', '-20', '0', '20', '--seed', '1', '--plot',
                           str(tmp_path / 'tolerance.png'), '-o', str(tmp_path / 't.csv'))
    assert status == 0, err
    lines = (tmp_path / 't.csv').read_text().splitlines()
    assert lines[0] == ','.join(TOLERANCE_COLUMNS) and len(lines) == 1 + 3 * 5
    assert lines[1].startswith('-20,camber_deg,') and lines[-1].endswith(',0')
    assert '[##############################] 1/1 batches (100%)' in err
    assert (tmp_path / 'tolerance.png').read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'
    # per-point sigmas from a file: only the tie rod's body point varies, and only in z
    (tmp_path / 'sd.yaml').write_text('{' + ', '.join(
        f'{n}: 0' for n in load_design('five_link').names if n != 'tie_rod.base')
        + ', tie_rod.base: {x: 0, y: 0, z: 0.3}}\n')
    status, out, err = run('tolerance', 'five_link', '--sigma', '1', '--samples', '50',
                           '--travel', '30', '--tolerances', str(tmp_path / 'sd.yaml'))
    assert status == 0, err
    rows = {line.split(',')[1]: line.split(',') for line in out.splitlines()[1:]}
    assert float(rows['wheel_center_z_mm'][4]) == 0.0        # std: nothing moves z0
    assert 0.0 < float(rows['toe_deg'][5]) < 0.5             # rss_std from the tie rod alone


def test_a_tolerances_file_with_a_tie_rod_length_gives_the_static_toe_spread(tmp_path):
    # every point fixed, the tie rod's length 0.1 mm: the design re-assembles at travel 0
    # with other toe (and a little camber); M_z does not move, since travel is imposed
    (tmp_path / 'sd.yaml').write_text('{' + ', '.join(
        f'{n}: 0' for n in load_design('five_link').names) + ', tie_rod.length: 0.1}\n')
    status, out, err = run('tolerance', 'five_link', '--sigma', '1', '--samples', '200',
                           '--travel', '0', '--tolerances', str(tmp_path / 'sd.yaml'))
    assert status == 0, err
    rows = {line.split(',')[1]: line.split(',') for line in out.splitlines()[1:]}
    assert float(rows['toe_deg'][4]) > 0.0 and float(rows['toe_deg'][5]) > 0.0
    assert float(rows['wheel_center_z_mm'][4]) == 0.0


@pytest.mark.parametrize('args, says', [
    (['--sigma', '0'], '--sigma: must be a number of mm above 0, got 0'),
    (['--sigma', '-1'], '--sigma: must be a number of mm above 0, got -1'),
    (['--sigma', 'nan'], '--sigma: must be a number of mm above 0, got nan'),
    (['--samples', '1'], '--samples: must be at least 2, got 1'),
    (['--travel', 'inf'], 'linkage-study: --travel: expected FROM[:TO:STEP], finite numbers '
     "with STEP > 0, got 'inf'"),
    (['--scene', 'nowhere'], 'nowhere: scene: no such file'),
    (['--tolerances', 'sd.yaml'], 'not_a_point: not a hardpoint of the scene five_link'),
])
def test_a_mistake_in_a_tolerance_command_is_one_line_with_status_2(args, says, tmp_path):
    (tmp_path / 'sd.yaml').write_text('not_a_point: 0.1\n')
    command = {'--scene': 'five_link', '--sigma': '0.1', '--samples': '10', '--travel': '0'}
    extra = []
    for option, value in zip(args[::2], args[1::2]):
        if option in command:
            command[option] = value
        else:
            extra += [option, value]
    argv = ['tolerance', command.pop('--scene')]
    for option, value in command.items():
        argv += [option, value]
    status, out, err = run(*argv, *extra, cwd=tmp_path)
    assert status == 2 and out == '', (out, err)
    assert err.count('\n') == 1 and err.startswith('linkage-study: ') and says in err, err
    assert 'Traceback' not in err


def test_a_scheduler_without_dask_installed_names_the_extra_in_one_line(tmp_path):
    # distributed made unimportable in a fresh interpreter (None in sys.modules fails it)
    code = ("import runpy, sys; sys.modules['distributed'] = None; sys.argv = ['linkage-study', "
            "'tolerance', 'five_link', '--sigma', '0.1', '--samples', '10', '--travel', '0', "
            "'--scheduler', 'tcp://127.0.0.1:8786']; "
            "runpy.run_module('linkage_ros.study.cli', run_name='__main__')")
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          timeout=300, cwd=tmp_path)
    assert done.returncode == 2 and done.stdout == '', done
    assert done.stderr.count('\n') == 1, done.stderr
    assert ('linkage-study: --scheduler: needs the Python package '
            "dask[distributed], which is not installed: pip install -e '.[study]'"
            in done.stderr)
