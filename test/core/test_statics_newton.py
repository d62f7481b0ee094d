# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Newton's matrix is the derivative of the residual it drives to zero (issue 37 item 1).

The residual is F(q, lambda) = (grad L - M, c) at any pose (kernel.assemble), the moment M
fixed in space; its derivative in the bodies' coordinates (left increments of the rotations)
is what newton.newton factorises. Checked against central differences of F itself, and by
its consequence: from a pose off the equilibrium, the steps fall quadratically.
"""

from linkage_ros.core.base import exp_so3
from linkage_ros.core.model import load_scene
from linkage_ros.core.statics import command, kernel, Load, newton, Statics
import numpy as np
import pytest

SCENES = ('double_wishbone_bushings', 'five_link_bushings',
          'chrono_sedan_doublewishbone_bushings')   # every bundled scene with bushings
LOADS = [Load((300.0, 2000.0, -500.0), 'cp', (40.0, -20.0, 150.0)),
         Load((0.0, 0.0, 0.0), 'wc', (100.0, -200.0, 300.0))]
ROUND_OFF = 64 * np.finfo(float).eps   # per mm of scene size, as solve.continuation's floor


def loaded_state(name, load, travel=20.0):
    """Return (Statics, Model, the loaded equilibrium's c, r, lambda, its kernel.Inputs)."""
    statics = Statics(load_scene(name))
    assert statics.solve(travel, load).status == 0
    model = kernel.unpack(statics.packed.ints, statics.packed.reals)
    bodies, m = len(statics.system.bodies), len(statics.system.constraints)
    done, zero = (command.views(statics._state, bodies, m, k) for k in (1, 0))
    x_load = np.empty(3)
    command.load_point(model, zero.r[0], load.at == 'cp', x_load)
    inputs = kernel.Inputs(done.head[0], 0.0, x_load, np.array(load.force_n, dtype=float),
                           1000.0 * np.array(load.moment_nm, dtype=float))
    return statics, model, done.c.copy(), done.r.copy(), done.lam.copy(), inputs


def perturbed(statics, c, r, seed):
    """Move every body off the pose: translations by up to 1e-2 mm, rotations by 1e-4 rad."""
    rng = np.random.default_rng(seed)
    c, r = c.copy(), r.copy()
    for k, body in enumerate(statics.system.bodies):
        if body.kind in ('carrier', 'arm', 'base'):
            c[k] += rng.uniform(-1e-2, 1e-2, 3)
        if body.kind in ('carrier', 'arm'):
            r[k] = exp_so3(rng.uniform(-1e-4, 1e-4, 3)) @ r[k]
        elif body.kind == 'hinge':
            r[k] = exp_so3(body.axis * rng.uniform(-1e-4, 1e-4)) @ r[k]
    return c, r


def residual(model, c, r, lam, inputs):
    """Return F = grad L - M (n,) at a pose (kernel.assemble) and the exact matrix (n, n)."""
    work = newton.work(model)
    kernel.assemble(model, c, r, lam, inputs, kernel.EXACT, work)
    return work.grad.copy(), work.hess.copy()


def moved(model, c, r, k, h):
    """Return the pose moved by h along coordinate k (a left increment for a rotation)."""
    step = np.zeros(model.n)
    step[k] = h
    c, r = c.copy(), r.copy()
    kernel.move(model, c, r, step)
    return c, r


def rotation_coordinates(model):
    """Return a mask (n,) of the coordinates that are rotations (rad)."""
    mask = np.zeros(model.n, dtype=bool)
    for kind, start in zip(model.b_kind, model.b_start):
        if kind <= kernel.ARM:
            mask[start + 3:start + 6] = True
        elif kind == kernel.HINGE:
            mask[start] = True
    return mask


@pytest.mark.parametrize('name', SCENES)
@pytest.mark.parametrize('load', LOADS, ids=['cp_wrench', 'moment'])
def test_the_newton_matrix_equals_central_differences_of_the_residual(name, load):
    """
    The exact matrix against (F(q + h e_k) - F(q - h e_k)) / 2h, off the equilibrium.

    In units of N/mm throughout (rotations times the lever, L): h = 1e-3 mm (1e-3 / L rad)
    leaves a truncation of (h / L)^2 ~ 2e-11 and a round-off of eps |F| / h ~ 1e-8 of the
    largest entry; 1e-6 of it holds with room. The symmetric Hessian (the matrix before
    issue 37) misses [g_w]x / 2 there: 5e-4 of the largest entry under these moments.
    """
    statics, model, c, r, lam, inputs = loaded_state(name, load)
    c, r = perturbed(statics, c, r, seed=3)
    lever = model.consts[kernel.LEVER]
    scale = np.where(rotation_coordinates(model), 1.0 / lever, 1.0)   # rad -> mm of lever
    _, exact = residual(model, c, r, lam, inputs)
    differences = np.empty_like(exact)
    for k in range(model.n):
        h = 1e-3 * scale[k]
        plus, minus = (residual(model, *moved(model, c, r, k, s * h), lam, inputs)[0]
                       for s in (1.0, -1.0))
        differences[:, k] = (plus - minus) / (2 * h)
    a, d = exact * scale[:, None] * scale[None, :], differences * scale[:, None] * scale[None, :]
    assert np.abs(a - d).max() <= 1e-6 * np.abs(d).max()


@pytest.mark.parametrize('name', SCENES)
def test_under_a_moment_fixed_in_space_the_matrix_is_not_symmetric_by_the_moment(name):
    """
    At equilibrium the carrier's rotation block of the matrix less its transpose is -[M]x.

    M is no potential's gradient: the rest of the carrier's rotational residual balances
    it, g_w = M, and the matrix is H - [g_w]x / 2 (kernel.py), so A - A^T = -[M]x, N mm/rad.
    """
    statics, model, c, r, lam, inputs = loaded_state(name, LOADS[1])
    _, exact = residual(model, c, r, lam, inputs)
    block = exact[3:6, 3:6]
    m0, m1, m2 = inputs.moment
    want = -np.array([[0.0, -m2, m1], [m2, 0.0, -m0], [-m1, m0, 0.0]])
    # the equilibrium's residual (1e-9 of the moment) and H's round-off leave 1e-9 of |H|
    assert np.abs((block - block.T) - want).max() <= 1e-9 * np.abs(block).max()


def newton_steps(model, c, r, lam, inputs, count=4):
    """Return the scaled step (mm) of count Newton iterations, one at a time (newton)."""
    work, steps = newton.work(model), []
    for _ in range(count):
        newton.newton(model, c, r, lam, inputs, 1, work)
        steps.append(work.steps[0])
    return steps


@pytest.mark.parametrize('name', SCENES)
@pytest.mark.parametrize('load', LOADS, ids=['cp_wrench', 'moment'])
def test_newton_steps_fall_quadratically_from_a_perturbed_pose(name, load):
    """
    Each step at most C times the square of the one before, C = 2 / lever, to round-off.

    Newton's error falls as (|A^-1| |A'| / 2) e^2. Here A's change is geometric: a rotation
    of s / L rad (s the step, rotations times the lever L, the carrier's largest point
    distance) changes the terms by their second-order part, s^2 / 2L of the first, so the
    constant is about 1 / L: the bundled scenes give 0.3 / L to 1.4 / L from 1e-2 mm and
    1e-4 rad off. A step below 64 eps x the scene's size (the round-off of its coordinates,
    continuation.py's floor) is round-off. With the matrix before issue 37 (symmetric,
    without the moment's and the pose's [g_w]x / 2) the second step is 4 / L to 130 / L
    times the first's square, and the third 1e3 / L to 5e4 / L: linear.
    """
    statics, model, c, r, lam, inputs = loaded_state(name, load)
    c, r = perturbed(statics, c, r, seed=11)
    lever = model.consts[kernel.LEVER]
    floor = ROUND_OFF * statics.scene.size
    steps = newton_steps(model, c, r, lam, inputs)
    assert steps[0] > 1e-3   # the perturbation is felt
    for before, after in zip(steps, steps[1:]):
        assert after <= max(2.0 / lever * before * before, floor), steps
