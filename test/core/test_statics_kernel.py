# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The compiled statics (core/statics/kernel.py) against its numpy twin (system.py, newton.py)."""

from pathlib import Path

from linkage_ros.core.base import Status
from linkage_ros.core.model import load_scene
from linkage_ros.core.statics import compliance, Load, rotation, solve_loaded
import numpy as np
import pytest

BUSHED = str(Path(__file__).resolve().parents[1] / 'data' / 'double_wishbone_bushings.yaml')


@pytest.mark.parametrize('scene_name, load', [
    (BUSHED, Load((300.0, 2000.0, -500.0), 'cp', (40.0, -20.0, 150.0))),
    ('five_link_bushings', Load((-800.0, 1500.0, 0.0), 'cp', (0.0, 0.0, 30.0))),
    ('macpherson', Load((0.0, 1000.0, 0.0), 'wc'))])
def test_the_compiled_loaded_solve_equals_the_numpy_one(scene_name, load):
    """Same equations, same Newton: poses to 1e-9 mm, forces to 1e-9 of the largest."""
    scene = load_scene(scene_name)
    fast, slow = (solve_loaded(scene, 25.0, load, compiled=c) for c in (True, False))
    assert fast.status == slow.status == Status.OK
    assert np.abs(fast.wheel_center_mm - slow.wheel_center_mm).max() < 1e-9
    assert abs(fast.toe_deg - slow.toe_deg) < 1e-9 and abs(fast.camber_deg - slow.camber_deg) \
        < 1e-9
    scale = max(np.linalg.norm(f) for f in slow.body_forces_n.values())
    for key, force in slow.body_forces_n.items():
        assert np.abs(fast.body_forces_n[key] - force).max() < 1e-9 * scale, key
    assert abs(fast.holding_force_n - slow.holding_force_n) < 1e-9 * scale


def test_the_compiled_rates_equal_the_numpy_ones():
    scene = load_scene(BUSHED)
    fast, slow = (compliance(scene, 30.0, compiled=c) for c in (True, False))
    assert fast.rates.keys() == slow.rates.keys()
    for key, value in slow.rates.items():
        assert fast.rates[key] == pytest.approx(value, rel=1e-9, abs=1e-12), key
    assert np.abs(fast.matrix_si - slow.matrix_si).max() <= 1e-9 * np.abs(slow.matrix_si).max()


def test_the_rotational_energy_has_exact_derivatives_in_the_left_increment():
    """
    The bushing's rotational energy has its gradient and Hessian exact.

    E(exp(w) R) = phi.K phi / 2, phi = log(exp(w) R): gradient and Hessian at w = 0 against
    central differences (h = 1e-4 rad: h^2 truncation 1e-8, round-off 1e-12 / h^2 = 1e-4 of
    the Hessian's own finite difference; gradient to 1e-7, Hessian to 1e-5 relative).
    """
    from linkage_ros.core.base import exp_so3
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
