# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The compiled statics (core/statics) against its numpy twin (statics_reference.py here)."""

from pathlib import Path

from linkage_ros.core.base import camber_toe, exp_so3, Status
from linkage_ros.core.model import load_scene
from linkage_ros.core.statics import command, kernel, kkt, Load, newton, rotation, Statics
import numpy as np
import pytest
import statics_reference as reference   # beside this file (pytest's path)

BUSHED = str(Path(__file__).resolve().parents[1] / 'data' / 'double_wishbone_bushings.yaml')
CASES = [(BUSHED, Load((300.0, 2000.0, -500.0), 'cp', (40.0, -20.0, 150.0)), 0.0),
         ('five_link_bushings', Load((-800.0, 1500.0, 0.0), 'cp', (0.0, 0.0, 30.0)), 0.0),
         ('chrono_sedan_doublewishbone_bushings', Load((0.0, 2500.0, 0.0), 'cp'), 8.0),
         ('macpherson', Load((0.0, 1000.0, 0.0), 'wc'), 0.0),
         ('double_wishbone', Load((-1500.0, 1000.0, 0.0), 'cp', (0.0, 0.0, 40.0)), 6.0)]
IDS = ['double_wishbone_bushings', 'five_link_bushings', 'chrono_sedan_at_rack',
       'macpherson', 'double_wishbone_at_rack']


@pytest.mark.parametrize('name, load, rack', CASES, ids=IDS)
def test_the_compiled_loaded_solve_equals_the_numpy_one(name, load, rack):
    """
    Same equations, solved apart: poses to 1e-9 mm, forces to 1e-9 of the largest.

    Both converge to a step below 1e-11 mm (times the lever: 2e-9 mm), their answers to
    the round-off of the residual, 1e-10 mm here.
    """
    scene = load_scene(name)
    fast = Statics(scene).solve(25.0, load, rack)
    solved = reference.Solved(scene, 25.0, rack)
    pose, lam, _, _, _ = solved.loaded(load)
    slow = reference.pickup_forces(scene, solved.system, pose, lam, rack)
    assert fast.status == Status.OK
    assert np.abs(fast.wheel_center_mm - pose.c[0]).max() < 1e-9
    assert np.abs(fast.rotation - pose.r[0]).max() < 1e-11   # rad: 1e-9 mm at the lever
    scale = max(np.linalg.norm(f) for f in slow['body_forces_n'].values())
    assert abs(fast.holding_force_n + lam[-1]) < 1e-9 * scale
    for what in ('body_forces_n', 'body_points_mm', 'body_moments_nm', 'ball_joint_forces_n',
                 'pivot_forces_n'):
        got = getattr(fast, what)
        assert list(got) == list(slow[what]), what   # the same pickups, in the same order
        for key, value in slow[what].items():
            assert np.abs(got[key] - value).max() < 1e-9 * scale, (what, key)
    assert fast.spring_forces_n == pytest.approx(slow['spring_forces_n'], abs=1e-9 * scale)


def test_the_compiled_rates_equal_the_numpy_ones():
    """
    The 6x6 matrix and the rates against the numpy KKT solve (np.linalg.solve), 1e-9.

    Toe and camber per turn of the carrier by central differences of camber_toe (+-1e-6
    rad: truncation 1e-12, round-off 1e-10 of the gradient), independent of the kernel's
    closed form.
    """
    scene = load_scene(BUSHED)
    fast = Statics(scene).rates(30.0)
    solved = reference.Solved(scene, 30.0)
    dm, w, held, patch = solved.rates()
    si = np.vstack((dm[:, :6] * 1e-3, w[:, :6]))
    si[:, 3:] *= 1e3
    assert np.abs(fast.matrix_si - si).max() <= 1e-9 * np.abs(si).max()
    spin = solved.pose0.r[0] @ solved.mech.spin_axis
    h = 1e-6

    def angles(turn):   # camber and toe of the spin axis turned by turn (3,) rad
        return np.array(camber_toe(exp_so3(turn) @ spin, scene.side_sign))

    gradient = np.array([(angles(h * e) - angles(-h * e)) / (2 * h) for e in np.eye(3)])
    d_camber, d_toe = gradient[:, 0], gradient[:, 1]
    deg = 180.0 / np.pi
    want = {'toe_per_fy_cp_deg_per_kN': d_toe @ w[:, 6] * deg * 1e3,
            'camber_per_fy_cp_deg_per_kN': d_camber @ w[:, 6] * deg * 1e3,
            'cp_dy_per_fy_cp_mm_per_kN': reference.patch_move(dm[:, 6], w[:, 6], patch)[1] * 1e3,
            'jacking_per_fy_cp': held[6],
            'toe_per_mz_deg_per_kNm': d_toe @ w[:, 5] * deg * 1e6}
    for key, value in want.items():
        assert fast.rates[key] == pytest.approx(value, rel=1e-9), key


def test_the_compiled_assembly_equals_the_numpy_one_off_the_equilibrium():
    """Gradient, symmetric Hessian, constraint values and rows at any pose, to 1e-12."""
    scene = load_scene('five_link')   # a spring on a link: weighted moving items
    statics = Statics(scene)
    statics.rates(20.0)
    model = kernel.unpack(statics.packed.ints, statics.packed.reals)
    bodies, m = len(statics.system.bodies), len(statics.system.constraints)
    zero = command.views(statics._state, bodies, m, 0)
    c, r = zero.c.copy(), zero.r.copy()
    c[0] += (0.3, -0.2, 0.1)
    r[0] = exp_so3(np.array([1e-3, -2e-3, 5e-4])) @ r[0]
    lam = zero.lam + 10.0
    x_load, force, moment = model.consts[:3] + (5.0, 300.0, -200.0), np.array(
        [100.0, 2000.0, -300.0]), np.array([1e4, -2e4, 3e4])
    work = newton.work(model)
    kernel.assemble(model, c, r, lam, kernel.Inputs(zero.head[0], 0.0, x_load, force, moment),
                    kernel.SYMMETRIC, work)
    want = reference.assemble(statics.system, reference.Pose(c, r), lam, zero.head[0], 0.0,
                              x_load, force, moment)
    for got, value in zip((work.grad, work.hess, work.values, work.rows), want):
        assert np.abs(got - value).max() <= 1e-12 * max(1.0, np.abs(value).max())


def test_the_packed_model_reads_back_as_the_arrays_packed():
    """kernel.unpack gives each field of pack's arrays, shape and values (FIELDS' layout)."""
    statics = Statics(load_scene('chrono_sedan_doublewishbone_bushings'))
    model = kernel.unpack(statics.packed.ints, statics.packed.reals)
    assert len(model) == len(kernel.FIELDS) + 2
    assert model.n == statics.system.size and model.m == len(statics.system.constraints)
    assert model.b_start.tolist() == [b.start for b in statics.system.bodies]
    assert np.array_equal(model.b_ref0, [b.ref0 for b in statics.system.bodies])
    last = len(model.t_kind) - 1
    assert model.t_kind[last] == kernel.LOAD and model.t_kind[model.m - 1] == kernel.TRAVEL
    assert sorted(model.perm) == sorted(set(range(model.n + model.m)) - {2, model.n + model.m
                                                                         - 1})
    for (kind, dims), value in zip(kernel.FIELDS, model):
        assert value.ndim == dims and value.dtype == (np.int64 if kind == 'i' else float)


def test_a_singular_cluster_is_factorised_densely_and_gives_the_same_solution():
    """kkt.factor FAILED on a cluster whose pivot is zero; the dense way solves it."""
    rng = np.random.default_rng(5)
    a = rng.normal(size=(6, 6))
    a[0, 0] = a[1, 0] = 0.0   # the cluster's first column, within it: zero
    bounds = np.array([0, 2, 6, -1])
    piv = np.empty(12, dtype=np.int64)
    assert kkt.factor(a.copy(), piv, bounds) == kkt.FAILED
    lu, rhs = a.copy(), rng.normal(size=6)
    mode = kkt.factor(lu, piv, kkt.dense_bounds(6))
    x = rhs.copy()
    kkt.solve(lu, piv, kkt.dense_bounds(6), mode, x, np.empty(6))
    assert np.abs(a @ x - rhs).max() < 1e-12 * np.abs(rhs).max() * np.linalg.cond(a)


def test_the_rotational_energy_has_exact_derivatives_in_the_left_increment():
    """
    The bushing's rotational energy has its gradient and Hessian exact.

    E(exp(w) R) = phi.K phi / 2, phi = log(exp(w) R): gradient and Hessian at w = 0 against
    central differences (h = 1e-4 rad: h^2 truncation 1e-8, round-off 1e-12 / h^2 = 1e-4 of
    the Hessian's own finite difference; gradient to 1e-7, Hessian to 1e-5 relative).
    """
    phi0 = np.array([0.3, -0.2, 0.4])   # 30 deg: an arm's wind-up at full travel, and more
    stiff = np.diag([5e4, 1e5, 3e5]) + 1e4   # N mm/rad, symmetric
    start = exp_so3(phi0)

    def energy(w):
        return rotation.energy_terms(rotation.log_so3(exp_so3(w) @ start), stiff)[0]

    _, grad, hess = rotation.energy_terms(phi0, stiff)
    h, eye = 1e-4, np.eye(3)
    fd_grad = np.array([(energy(h * e) - energy(-h * e)) / (2 * h) for e in eye])
    fd_hess = np.array([[(energy(h * (a + b)) - energy(h * (a - b)) - energy(h * (b - a))
                          + energy(-h * (a + b))) / (4 * h * h) for b in eye] for a in eye])
    assert np.abs(grad - fd_grad).max() < 1e-7 * np.abs(grad).max()
    assert np.abs(hess - fd_hess).max() < 1e-5 * np.abs(hess).max()
