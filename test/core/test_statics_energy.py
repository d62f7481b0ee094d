"""
The statics against an independent formulation: minimum potential energy over 6-DOF bodies.

energy_reference.py (next to this file) reads the scene file itself and solves the model of
STATICS_SPEC.md with its own bodies, constraints and Newton; it shares no code with
linkage_ros.core.statics. Its own checks come first (they need no statics), then the
comparison on every bundled scene with bushings.
"""

from energy_reference import EnergyModel, stiffness     # beside this file (pytest's path)
from linkage_ros.core.model import bundled_scenes, load_scene, scene_dir
from linkage_ros.core.solve import sweep
import numpy as np
import pytest
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
    assert {'double_wishbone', 'five_link', 'chrono_sedan_doublewishbone_bushings'} <= set(BUSHED)


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
    model = EnergyModel(scene_data('five_link'))
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
