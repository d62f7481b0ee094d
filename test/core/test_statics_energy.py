# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The statics against an independent formulation: minimum potential energy over 6-DOF bodies.

energy_reference.py (next to this file) reads the scene file itself and solves the model of
doc/kc.md ("The model") with its own bodies, constraints and Newton; it shares no code with
linkage_ros.core.statics. Its own checks come first (they need no statics), then the comparison
on every bundled scene with bushings.
"""

from dataclasses import replace

from energy_reference import EnergyModel, stiffness     # beside this file (pytest's path)
from linkage_ros.core.model import bundled_scenes, load_scene, scene_dir
from linkage_ros.core.solve import sweep
import numpy as np
import pytest
from scipy.spatial.transform import Rotation
import yaml


def scene_data(name):
    """Return the bundled scene file's mapping, read as it is written."""
    return yaml.safe_load((scene_dir() / f'{name}.yaml').read_text())


def has_bushings(name):
    """Whether a bundled scene declares any bushing."""
    return any('bushing' in c for c in scene_data(name)['constraints'])


BUSHED = [name for name in bundled_scenes() if has_bushings(name)]
# Loads of a K&C rig (N, N m): cornering and braking at the contact patch, and a mixed
# force with a moment at the wheel centre.
LOADS = [((0.0, 1500.0, 0.0), 'cp', (0.0, 0.0, 0.0)),
         ((-2000.0, 0.0, 0.0), 'cp', (0.0, 0.0, 0.0)),
         ((800.0, -500.0, 300.0), 'wc', (30.0, -20.0, 80.0))]
TRAVELS = (-30.0, 40.0)
# A converged equilibrium is exact to the round-off of the Newton residual (about 1e-8 N
# on forces of 1e3-1e4 N here, 1e-12 relative); the bounds below leave room for the two
# solvers' different round-off and stop rules.
ANGLE_DEG, POSITION_MM, FORCE_REL = 1e-6, 1e-6, 1e-6


def test_the_bundled_scenes_with_bushings_are_the_three_of_issue_29():
    assert {'double_wishbone_bushings', 'five_link_bushings',
            'chrono_sedan_doublewishbone_bushings'} <= set(BUSHED)


@pytest.mark.parametrize('name', BUSHED)
def test_reference_without_load_and_springs_is_the_kinematic_pose(name):
    data = scene_data(name)
    data.pop('elements', None)      # no springs, and no torsion that travel would wind up:
    for item in data['constraints']:     # the bushings are then unloaded at the kinematic pose
        item.get('bushing', {}).pop('torsion', None)
    model, travels = EnergyModel(data), np.array([-30.0, 0.0, 40.0])
    kin = sweep(load_scene(name), travels)
    for i, travel in enumerate(travels):
        res = model.solve(travel)
        assert res.camber_deg == pytest.approx(np.degrees(kin.camber[i]), abs=1e-9)
        assert res.toe_deg == pytest.approx(np.degrees(kin.toe[i]), abs=1e-9)
        np.testing.assert_allclose(res.wheel_center_mm, kin.wheel_center[i], atol=1e-9)
        assert abs(res.holding_force_n) < 1e-6


def test_reference_link_bushing_deflection_is_the_link_force_over_its_rate():
    # A link is a two-force member: at equilibrium its body end, held only by the link and
    # its bushing, has K d = T u (u the link's loaded direction). T here comes from the
    # carrier's own balance at the loaded pose (five link forces and the holding force: six
    # equations), not from the reference's multipliers.
    model = EnergyModel(scene_data('five_link_bushings'))
    model.springs = []
    force = np.array([500.0, 1500.0, 0.0])
    res = model.solve(20.0, force_n=force, at='wc')
    q, parts = res.q, model.parts
    ends = [model.carrier_point(q, p.carrier) for p in parts]
    dirs = [(e - model.link_base(q, p, 0.0)) / np.linalg.norm(e - model.link_base(q, p, 0.0))
            for p, e in zip(parts, ends)]
    wc = res.wheel_center_mm
    rows = np.array([np.r_[-u, np.cross(e - wc, -u)] for u, e in zip(dirs, ends)]
                    + [np.r_[0, 0, 1, 0, 0, 0]]).T
    tension = np.linalg.solve(rows, -np.r_[force, 0, 0, 0])
    for part, u, t in zip(parts, dirs, tension):
        b = part.bushing
        axis = (part.carrier - part.base[0]) / np.linalg.norm(part.carrier - part.base[0])
        d = q[part.index:part.index + 3]
        np.testing.assert_allclose(stiffness(axis, b['axial'], b['radial']) @ d, t * u,
                                   atol=1e-9 * abs(tension).max())
        assert res.link_forces_n[part.name] == pytest.approx(t, abs=1e-9 * abs(tension).max())


@pytest.mark.parametrize('name', BUSHED)
def test_reference_equilibrium_is_a_minimum_of_the_potential(name):
    # The stationary point Newton finds is the minimum the method is named for: the Hessian
    # of the Lagrangian is positive definite on the constraints' tangent space.
    res = EnergyModel(scene_data(name)).solve(-20.0, force_n=(0.0, 1500.0, 0.0), at='cp')
    assert res.min_curvature > 0.0


@pytest.mark.parametrize('name', BUSHED)
def test_reference_forces_on_the_body_balance_the_load(name):
    model = EnergyModel(scene_data(name))
    force, moment = np.array([800.0, -500.0, 300.0]), np.array([30.0, -20.0, 80.0])
    res = model.solve(25.0, force_n=force, at='wc', moment_nm=moment)
    total = sum(res.body_forces_n.values())
    turning = sum(np.cross(res.body_points_mm[k], f) for k, f in res.body_forces_n.items())
    up = np.array([0.0, 0.0, res.holding_force_n])
    scale = max(np.abs(f).max() for f in res.body_forces_n.values())
    np.testing.assert_allclose(total, force + up, atol=1e-9 * scale)
    wc = res.wheel_center_mm
    expected = np.cross(wc, force + up) + moment * 1000.0
    np.testing.assert_allclose(turning + res.body_couples_nmm, expected,
                               atol=1e-9 * scale * np.abs(wc).max())


@pytest.mark.parametrize('name', BUSHED)
def test_reference_ball_joint_forces_balance_the_load_on_the_carrier(name):
    # The carrier is held by its ball joints and the held height only (no spring is mounted
    # on a bundled bushed scene's carrier), so their forces on it and the load sum to zero.
    model = EnergyModel(scene_data(name))
    assert all(sp.on != 'carrier' for sp in model.springs)
    force, moment = np.array([800.0, -500.0, 300.0]), np.array([30.0, -20.0, 80.0])
    res = model.solve(-25.0, force_n=force, at='wc', moment_nm=moment)
    wc, up = res.wheel_center_mm, np.array([0.0, 0.0, res.holding_force_n])
    joints = {p.name: model.carrier_point(res.q, p.carrier) for p in model.parts
              if p.kind != 'line'}
    scale = max(np.abs(f).max() for f in res.ball_joint_forces_n.values())
    np.testing.assert_allclose(sum(res.ball_joint_forces_n.values()) + force + up, 0.0,
                               atol=1e-9 * scale)
    turning = sum(np.cross(joints[k] - wc, f) for k, f in res.ball_joint_forces_n.items())
    np.testing.assert_allclose(turning + moment * 1000.0, 0.0, atol=1e-9 * scale * 1000.0)


# --- the comparison with linkage_ros.core.statics --------------------------------------------

def statics():
    """Return the statics face, or skip while it is not there."""
    return pytest.importorskip('linkage_ros.core.statics')


def assert_forces_agree(got, want, what):
    """Each force (float or (3,)) within FORCE_REL of the largest of its kind."""
    assert set(want) <= set(got), f'{what}: missing {sorted(set(want) - set(got))}'
    scale = max(np.abs(v).max() for v in want.values()) if want else 1.0
    for key, value in want.items():
        np.testing.assert_allclose(got[key], value, atol=FORCE_REL * scale, rtol=FORCE_REL,
                                   err_msg=f'{what}[{key}]')


@pytest.mark.parametrize('name', BUSHED)
@pytest.mark.parametrize('load', LOADS, ids=['fy_cp', 'fx_cp', 'wrench_wc'])
def test_loaded_pose_and_forces_agree_with_the_energy_reference(name, load):
    core = statics()
    force, at, moment = load
    scene, model = load_scene(name), EnergyModel(scene_data(name))
    for travel in TRAVELS:
        got = core.solve_loaded(scene, travel_mm=travel,
                                load=core.Load(force_n=force, at=at, moment_nm=moment))
        want = model.solve(travel, force_n=force, at=at, moment_nm=moment)
        assert got.camber_deg == pytest.approx(want.camber_deg, abs=ANGLE_DEG)
        assert got.toe_deg == pytest.approx(want.toe_deg, abs=ANGLE_DEG)
        np.testing.assert_allclose(got.wheel_center_mm, want.wheel_center_mm, atol=POSITION_MM)
        scale = max(abs(want.holding_force_n), *np.abs(force))
        assert got.holding_force_n == pytest.approx(want.holding_force_n, abs=FORCE_REL * scale)
        assert_forces_agree(got.link_forces_n, want.link_forces_n, 'link_forces_n')
        assert_forces_agree(got.pivot_forces_n, want.pivot_forces_n, 'pivot_forces_n')
        assert_forces_agree(got.ball_joint_forces_n, want.ball_joint_forces_n,
                            'ball_joint_forces_n')
        assert_forces_agree(got.spring_forces_n, want.spring_forces_n, 'spring_forces_n')
        assert_forces_agree(got.body_forces_n, want.body_forces_n, 'body_forces_n')


def test_a_link_carrying_a_spring_gives_the_carrier_its_share_of_the_spring_force():
    # five_link's spring sits half-way along lower_rear: the link's ball joint passes the
    # carrier its axial force and half the spring's push (the reference's carrier balances
    # to 1e-13 N with it; test_reference_ball_joint_forces_balance_the_load_on_the_carrier).
    core = statics()
    force = (0.0, 1500.0, 0.0)
    got = core.solve_loaded(load_scene('five_link_bushings'), travel_mm=-30.0,
                            load=core.Load(force_n=force, at='wc'))
    want = EnergyModel(scene_data('five_link_bushings')).solve(-30.0, force_n=force, at='wc')
    assert_forces_agree(got.ball_joint_forces_n, want.ball_joint_forces_n,
                        'ball_joint_forces_n')


# Central differences of the reference's solves: +-2.5 N (N m) leaves a truncation error of
# at most 3e-8 relative on the bundled scenes (it falls 4x per halving: 5e-7 at 10 N).
STEP_N = 2.5


def reference_rates(model, travel, step=STEP_N):
    """Return the issue's rates by central differences of the reference's solves (+-step N)."""
    def diff(force=(0.0, 0.0, 0.0), at='wc', moment=(0.0, 0.0, 0.0)):
        plus, minus = (model.solve(travel, force_n=np.multiply(force, s), at=at,
                                   moment_nm=np.multiply(moment, s)) for s in (step, -step))
        per = 1000.0 / (2.0 * step)   # per kN (or kN m)
        return {'toe': (plus.toe_deg - minus.toe_deg) * per,
                'camber': (plus.camber_deg - minus.camber_deg) * per,
                'wc': (plus.wheel_center_mm - minus.wheel_center_mm) * per,
                'cp': (plus.load_point_mm - minus.load_point_mm) * per,
                'jacking': (plus.holding_force_n - minus.holding_force_n) / (2.0 * step)}
    fy, fx = diff((0, 1, 0), 'cp'), diff((1, 0, 0), 'cp')
    fx_wc, mz = diff((1, 0, 0)), diff(moment=(0, 0, 1))
    return {'toe_per_fy_cp_deg_per_kN': fy['toe'], 'camber_per_fy_cp_deg_per_kN': fy['camber'],
            'wc_dy_per_fy_cp_mm_per_kN': fy['wc'][1], 'cp_dy_per_fy_cp_mm_per_kN': fy['cp'][1],
            'jacking_per_fy_cp': fy['jacking'], 'toe_per_fx_cp_deg_per_kN': fx['toe'],
            'camber_per_fx_cp_deg_per_kN': fx['camber'], 'wc_dx_per_fx_cp_mm_per_kN': fx['wc'][0],
            'toe_per_fx_wc_deg_per_kN': fx_wc['toe'], 'wc_dx_per_fx_wc_mm_per_kN': fx_wc['wc'][0],
            'toe_per_mz_deg_per_kNm': mz['toe'], 'camber_per_mz_deg_per_kNm': mz['camber']}


@pytest.mark.parametrize('name', BUSHED)
def test_compliance_rates_agree_with_differences_of_the_energy_reference(name):
    core = statics()
    got = core.compliance(load_scene(name), travel_mm=20.0)
    want = reference_rates(EnergyModel(scene_data(name)), 20.0)
    assert set(got.rates) == set(want)
    scale = max(abs(v) for k, v in want.items() if k.endswith('deg_per_kN'))
    for key, value in want.items():
        assert got.rates[key] == pytest.approx(value, rel=1e-6, abs=1e-7 * scale), key


@pytest.mark.parametrize('name', BUSHED)
def test_compliance_matrix_agrees_with_differences_of_the_energy_reference(name):
    core = statics()
    got = core.compliance(load_scene(name), travel_mm=-20.0).matrix
    model, want = EnergyModel(scene_data(name)), np.zeros((6, 6))
    for j, unit in enumerate(np.eye(3)):     # per kN at the wheel centre, then per kN m
        for col, kwargs in ((j, {'force_n': unit}), (j + 3, {'moment_nm': unit})):
            plus, minus = (model.solve(-20.0, **{k: v * s for k, v in kwargs.items()})
                           for s in (STEP_N, -STEP_N))
            per = 1000.0 / (2.0 * STEP_N)
            want[:3, col] = (plus.wheel_center_mm - minus.wheel_center_mm) * per
            want[3:, col] = np.degrees(Rotation.from_matrix(
                plus.rotation @ minus.rotation.T).as_rotvec()) * per
    np.testing.assert_allclose(got, want, rtol=1e-6, atol=1e-7 * np.abs(want).max())


@pytest.mark.parametrize('name', ['double_wishbone', 'chrono_sedan_doublewishbone_bushings'])
def test_loaded_pose_at_a_steered_rack_agrees_with_the_energy_reference(name):
    core = statics()
    scene, model = load_scene(name), EnergyModel(scene_data(name))
    force = (0.0, 1500.0, 0.0)
    got = core.solve_loaded(scene, travel_mm=10.0, rack_mm=8.0,
                            load=core.Load(force_n=force, at='cp'))
    want = model.solve(10.0, rack_mm=8.0, force_n=force, at='cp')
    assert got.camber_deg == pytest.approx(want.camber_deg, abs=ANGLE_DEG)
    assert got.toe_deg == pytest.approx(want.toe_deg, abs=ANGLE_DEG)
    assert_forces_agree(got.link_forces_n, want.link_forces_n, 'link_forces_n')
    assert_forces_agree(got.pivot_forces_n, want.pivot_forces_n, 'pivot_forces_n')


def test_a_strut_scene_with_bushings_agrees_with_the_energy_reference(tmp_path):
    # No bundled strut scene has bushings: macpherson with a bushed lower arm and tie rod
    # and a spring along the strut checks the line constraint and the along mount.
    core = statics()
    data = scene_data('macpherson')
    data['constraints'][0]['bushing'] = {'axial': 1.0e6, 'radial': 3.0e6, 'torsion': 1.0,
                                         'conical': 20.0}
    data['constraints'][1]['bushing'] = {'axial': 5.0e6, 'radial': 1.0e6}
    data['elements'] = [{'name': 'coil', 'type': 'spring', 'along': 'strut',
                         'rate': 3.0e4, 'free_length': 0.40}]
    path = tmp_path / 'strut.yaml'
    path.write_text(yaml.safe_dump(data))
    force, moment = (300.0, 1500.0, 0.0), (0.0, 0.0, 50.0)
    got = core.solve_loaded(load_scene(str(path)), travel_mm=25.0,
                            load=core.Load(force_n=force, at='cp', moment_nm=moment))
    want = EnergyModel(data).solve(25.0, force_n=force, at='cp', moment_nm=moment)
    assert got.camber_deg == pytest.approx(want.camber_deg, abs=ANGLE_DEG)
    assert got.toe_deg == pytest.approx(want.toe_deg, abs=ANGLE_DEG)
    np.testing.assert_allclose(got.wheel_center_mm, want.wheel_center_mm, atol=POSITION_MM)
    assert got.holding_force_n == pytest.approx(want.holding_force_n, rel=FORCE_REL)
    assert_forces_agree(got.link_forces_n, want.link_forces_n, 'link_forces_n')
    assert_forces_agree(got.pivot_forces_n, want.pivot_forces_n, 'pivot_forces_n')
    assert_forces_agree(got.spring_forces_n, want.spring_forces_n, 'spring_forces_n')


@pytest.mark.parametrize('name', ['double_wishbone_bushings', 'chrono_sedan_doublewishbone'])
def test_rigid_arms_pivot_forces_agree_with_the_energy_reference(name):
    # A rigid revolute's pivots share its axial force equally (the least-norm pair): a
    # convention both sides take; the rest follows from the arm's balance. double_wishbone
    # without its bushings keeps its spring on the lower arm.
    core = statics()
    data = scene_data(name)
    for item in data['constraints']:
        item.pop('bushing', None)
    scene = load_scene(name)
    scene = replace(scene, constraints=tuple(replace(c, bushing=None)
                                             for c in scene.constraints))
    force, moment = (-1500.0, 1000.0, 0.0), (0.0, 0.0, 40.0)
    got = core.solve_loaded(scene, travel_mm=15.0,
                            load=core.Load(force_n=force, at='cp', moment_nm=moment))
    want = EnergyModel(data).solve(15.0, force_n=force, at='cp', moment_nm=moment)
    assert got.toe_deg == pytest.approx(want.toe_deg, abs=ANGLE_DEG)
    assert_forces_agree(got.pivot_forces_n, want.pivot_forces_n, 'pivot_forces_n')
    assert_forces_agree(got.body_forces_n, want.body_forces_n, 'body_forces_n')
