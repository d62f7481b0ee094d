# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Statics with bushings (issue 29): equilibrium, forces, rates, as doc/kc.md says."""

from dataclasses import replace
from pathlib import Path

from hypothesis import given, settings, strategies as st
from linkage_ros.core.base import LinkageError, Status
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import Continuation
from linkage_ros.core.solve.mechanism import compile_scene
from linkage_ros.core.statics import compliance, Load, solve_loaded
import numpy as np
import pytest
import statics_reference as reference   # beside this file (pytest's path)

DATA = Path(__file__).resolve().parents[1] / 'data'
BUSHED = str(DATA / 'double_wishbone_bushings.yaml')
TRAVELS = (0.0, 40.0)


def stiffer(scene, factor):
    """Return the scene with translational and conical rates times factor (torsion kept)."""
    constraints = tuple(c if c.bushing is None else replace(c, bushing=replace(
        c.bushing, axial=c.bushing.axial * factor, radial=c.bushing.radial * factor,
        conical=c.bushing.conical * factor)) for c in scene.constraints)
    return replace(scene, constraints=constraints)


def rigid(name):
    """Return a bundled scene with its bushings taken out (every constraint rigid)."""
    scene = load_scene(name)
    return replace(scene, constraints=tuple(replace(c, bushing=None)
                                            for c in scene.constraints))


def balance(res, load):
    """Return (force sum, moment sum about the origin, scale) of body forces less the loads."""
    force = np.array(load.force_n, dtype=float)
    up = np.array([0.0, 0.0, res.holding_force_n])
    net_f = sum(res.body_forces_n.values()) - force - up
    net_m = sum(np.cross(res.body_points_mm[k], f) for k, f in res.body_forces_n.items()) \
        + 1000.0 * sum(res.body_moments_nm.values(), np.zeros(3)) \
        - np.cross(res.load_point_mm, force) - 1000.0 * np.array(load.moment_nm) \
        - np.cross(res.wheel_center_mm, up)
    scale = max(np.linalg.norm(f) for f in res.body_forces_n.values())
    return net_f, net_m, scale


@pytest.mark.parametrize('travel', TRAVELS)
def test_stiff_bushings_approach_the_kinematic_pose_as_one_over_k(travel):
    """
    Rates x1e6 (translational, conical) move the pose from the kinematic one 1e6 times less.

    Torsion is kept: its wind-up with travel is a preload, a torque on the arm that does not
    vanish as the bushing stiffens (scaled, it would grow with it and deflect the stiff
    bushings by a finite amount). The spring's preload (kN) deflects the bushings by force
    over rate: 0.05 deg of camber at x1, 5e-8 deg at x1e6, ten times less at x1e7 (the
    deflection's second-order part is 1e-6 of it there), to the round-off of the angles.
    """
    scene = load_scene(BUSHED)
    kin = Continuation(scene).solve(travel)
    gaps = []
    for factor in (1e6, 1e7):
        res = solve_loaded(stiffer(scene, factor), travel, Load())
        assert res.status == Status.OK
        gaps.append(np.array([res.camber_deg - np.degrees(kin.camber),
                              res.toe_deg - np.degrees(kin.toe)]))
    # Round-off: each gap is an angle read from a converged pose less the kinematic one. The
    # pose's coordinates (up to R mm, the scene's largest) carry R*eps each, a rotation is
    # their difference over the carrier's lever L (its shortest pickup offset), and the
    # residual and the angle's formula add a few tens of such terms: 50*eps*R/L rad an angle
    # (5.5e-14 rad here; the BLAS kernels give angles 30 eps apart). gaps[0] - 10*gaps[1]
    # holds 1 + 10 + 9 of them (x1e6, x1e7, kinematic): 1e-3 of the camber gap, 1e-2 of the
    # toe gap at 0 mm (6e-9 deg), whose relative round-off failed rel=1e-4 under Sandybridge.
    reach = np.abs(scene.points).max() / np.linalg.norm(scene.carrier_offsets, axis=1).min()
    angle_deg = np.degrees(50 * np.finfo(float).eps * reach)
    assert gaps[1] * 10 == pytest.approx(gaps[0], rel=1e-5, abs=20 * angle_deg)


def test_stiff_bushings_without_preload_give_the_kinematic_pose_to_1e9_deg():
    """Without the spring, only the torsion wind-up deflects: x1e6 leaves < 1e-9 deg at 20 mm."""
    scene = stiffer(replace(load_scene(BUSHED), elements=()), 1e6)
    for travel in (0.0, 20.0):
        kin = Continuation(scene).solve(travel)
        res = solve_loaded(scene, travel, Load())
        assert abs(res.camber_deg - np.degrees(kin.camber)) < 1e-9
        assert abs(res.toe_deg - np.degrees(kin.toe)) < 1e-9


@pytest.mark.parametrize('travel', TRAVELS)
def test_stiff_bushings_scale_the_rates_as_one_over_k(travel):
    """
    x1e6 and x1e7: the rates times k agree to 1e-3.

    The preload's geometry is 1e-6 off between the two; the KKT matrix's condition grows
    with k (1e10 N/mm against constraint rows of 1 at x1e7), which leaves the smallest rates
    (camber per Mz) about 5 digits.
    """
    scene = load_scene(BUSHED)
    hard = compliance(stiffer(scene, 1e6), travel)
    harder = compliance(stiffer(scene, 1e7), travel)
    for key, value in hard.rates.items():
        if key.startswith('jacking'):   # a force ratio: it tends to the rigid one
            continue
        # a rate that nearly cancels (the wheel centre's lateral move, 1e-4 of the patch's)
        # is held to 1e-3 of the largest rate of its unit
        biggest = max(abs(v) for k, v in hard.rates.items() if k.split('_')[-3:] ==
                      key.split('_')[-3:]) * 1e6
        assert harder.rates[key] * 1e7 == pytest.approx(value * 1e6, rel=1e-3,
                                                        abs=1e-3 * biggest), key


LOADS = [('toe_per_fy_cp_deg_per_kN', 'toe_deg', (0, 1, 0), 'cp', (0, 0, 0)),
         ('camber_per_fy_cp_deg_per_kN', 'camber_deg', (0, 1, 0), 'cp', (0, 0, 0)),
         ('wc_dy_per_fy_cp_mm_per_kN', 'wc_y', (0, 1, 0), 'cp', (0, 0, 0)),
         ('jacking_per_fy_cp', 'holding_force_n', (0, 1, 0), 'cp', (0, 0, 0)),
         ('toe_per_fx_cp_deg_per_kN', 'toe_deg', (1, 0, 0), 'cp', (0, 0, 0)),
         ('wc_dx_per_fx_wc_mm_per_kN', 'wc_x', (1, 0, 0), 'wc', (0, 0, 0)),
         ('toe_per_mz_deg_per_kNm', 'toe_deg', (0, 0, 0), 'wc', (0, 0, 1))]


def _read(res, what):
    if what == 'wc_x':
        return res.wheel_center_mm[0]
    if what == 'wc_y':
        return res.wheel_center_mm[1]
    return getattr(res, what)


@pytest.mark.parametrize('travel', TRAVELS)
@pytest.mark.parametrize('key, what, force, at, moment', LOADS)
def test_rates_equal_central_differences_of_loaded_solves(travel, key, what, force, at, moment):
    """
    Exact rates against central differences of loaded solves at +-10 N (+-10 N m): 1e-6.

    A central difference errs by h^2 f3 / 6 (f3 the third derivative): 4e-8 of the toe rate
    here at +-10 N (4e-9 at +-1 N: the exact rate is the limit).
    """
    scene = load_scene(BUSHED)
    step = 10.0
    ends = [solve_loaded(scene, travel, Load(tuple(s * step * f for f in force), at,
                                             tuple(s * step * m for m in moment)))
            for s in (1.0, -1.0)]
    assert all(e.status == Status.OK for e in ends)
    per = (_read(ends[0], what) - _read(ends[1], what)) / (2 * step)   # per N or per N m
    scale = 1.0 if key.startswith('jacking') else 1000.0   # per kN, per kN m
    exact = compliance(scene, travel).rates[key]
    # a rate that nearly cancels (the wheel centre's lateral move, 4e-5 mm/kN) has the
    # solves' own precision, 1e-11 mm over 10 N, as its floor: 1e-9 in its units
    assert per * scale == pytest.approx(exact, rel=1e-6, abs=1e-9), (per * scale, exact)


@pytest.mark.parametrize('travel', TRAVELS)
def test_the_wheel_centre_compliance_is_symmetric_in_si(travel):
    """Maxwell-Betti: the SI matrix equals its transpose to 1e-9 of its largest entry."""
    comp = compliance(load_scene(BUSHED), travel)
    si = comp.matrix_si
    assert np.abs(si - si.T).max() <= 1e-9 * np.abs(si).max()
    held = np.abs(comp.matrix).max() * 1e-12   # the travel is held: round-off only
    assert np.all(np.abs(comp.matrix[2]) < held) and np.all(np.abs(comp.matrix[:, 2]) < held)


@pytest.mark.parametrize('travel', TRAVELS)
@pytest.mark.parametrize('load', [Load((300.0, 2000.0, -500.0), 'cp', (40.0, -20.0, 150.0)),
                                  Load((-200.0, 0.0, 0.0), 'wc')])
def test_body_forces_balance_the_load_and_the_holding_force(travel, load):
    """Pivots, link bases, spring ends and bushing moments balance load + holding force."""
    res = solve_loaded(load_scene(BUSHED), travel, load)
    assert res.status == Status.OK
    net_f, net_m, scale = balance(res, load)
    assert np.abs(net_f).max() < 1e-9 * scale
    assert np.abs(net_m).max() < 1e-9 * scale * 1000.0   # N mm; lever about 1 m


@pytest.mark.parametrize('scene_name', ['double_wishbone', 'five_link', 'macpherson'])
def test_a_rigid_scene_keeps_its_kinematic_pose_and_its_forces_balance(scene_name):
    scene = rigid(scene_name)
    load = Load((200.0, 1500.0, 0.0), 'cp' if scene.wheel_radius else 'wc', (0.0, 0.0, 50.0))
    res = solve_loaded(scene, 20.0, load)
    kin = Continuation(scene).solve(20.0)
    assert res.status == Status.OK
    assert np.abs(res.wheel_center_mm - kin.wheel_center).max() < 1e-9
    assert abs(res.toe_deg - np.degrees(kin.toe)) < 1e-9
    net_f, net_m, scale = balance(res, load)
    assert np.abs(net_f).max() < 1e-9 * scale and np.abs(net_m).max() < 1e-9 * scale * 1000
    for c in scene.constraints:   # a rigid revolute shares its axial force equally
        if c.type == 'circle':
            along = (c.base[1] - c.base[0]) / np.linalg.norm(c.base[1] - c.base[0])
            shares = [res.pivot_forces_n[f'{c.name}_{end}'] @ along for end in ('axis0', 'axis1')]
            assert shares[0] == pytest.approx(shares[1], rel=1e-9, abs=1e-9 * scale)


def test_a_rigid_double_wishbone_holds_a_lateral_load_as_virtual_work_says():
    """
    A rigid double wishbone's holding and rack forces equal virtual work's.

    Virtual work: with the travel free, a force F at the wheel centre and the holding force
    H do no work along the mechanism's one motion, so H = -F . dM/dtravel; moving the rack
    (the tie rod's base along y) at held travel, F . dM/drack is the work of the body's
    reaction at the tie rod's base, its y component (central differences of kinematic solves,
    +-1e-3 mm).
    """
    scene = replace(rigid('double_wishbone'), elements=())   # no spring: the load alone
    force = np.array([0.0, 1000.0, 0.0])
    res = solve_loaded(scene, 10.0, Load(tuple(force), 'wc'))
    h = 1e-3
    up, down = (Continuation(scene).solve(10.0 + s * h) for s in (1.0, -1.0))
    dm = (up.wheel_center - down.wheel_center) / (2 * h)   # per mm of travel
    assert res.holding_force_n == pytest.approx(-force @ dm, rel=1e-6)
    rack = [Continuation(scene).solve(10.0, s * h).wheel_center for s in (1.0, -1.0)]
    dm_dr = (rack[0] - rack[1]) / (2 * h)   # per mm of rack, travel held
    # the rack moves the tie rod's base along y: the body's reaction there does the work
    assert res.body_forces_n['tie_rod_base'][1] == pytest.approx(force @ dm_dr, rel=1e-6)


def test_a_load_at_the_contact_patch_needs_a_wheel_radius():
    scene = replace(load_scene(BUSHED), wheel_radius=0.0)
    with pytest.raises(LinkageError, match='needs wheel_radius'):
        solve_loaded(scene, 0.0, Load((0.0, 100.0, 0.0), 'cp'))


def test_a_load_too_big_is_not_carried_and_names_the_load_and_residual():
    res = solve_loaded(load_scene(BUSHED), 0.0, Load((0.0, 2e6, 0.0), 'cp'))
    assert res.status == Status.NOT_CARRIED and res.wheel_center_mm is None
    assert '(0.0, 2000000.0, 0.0) N at cp' in res.message and 'residual' in res.message
    assert len(res.message.splitlines()) == 1


def test_a_kept_zero_load_equilibrium_gives_what_a_fresh_solve_gives():
    """The last zero-load equilibrium kept on the Scene: travel 30, 0, 30 as a fresh scene."""
    scene = load_scene(BUSHED)
    load = Load((0.0, 1500.0, 0.0), 'cp')
    first = solve_loaded(scene, 30.0, load)
    solve_loaded(scene, 0.0, load)
    again, kept = solve_loaded(scene, 30.0, load), solve_loaded(scene, 30.0, load)
    fresh = solve_loaded(load_scene(BUSHED), 30.0, load)
    for res in (first, again, kept):
        assert np.abs(res.wheel_center_mm - fresh.wheel_center_mm).max() < 1e-12
        tie_rod = fresh.link_forces_n['tie_rod']
        assert res.link_forces_n['tie_rod'] == pytest.approx(tie_rod, rel=1e-12)


def test_a_link_carrying_a_spring_reports_both_ends_which_differ_by_its_push():
    """
    The link of five_link that carries the spring (issue 36 item 18): both ends reported.

    lower_rear carries the spring half-way along it.

    At travel 0 under 4 kN lateral at the patch its body end carries 3707.2 N and its carrier
    end 3111.9 N (the issue's numbers; before, the table gave their mean, 3409.6 N). The
    difference is the spring's push along the link, from the positions and the spring's
    force of the numpy reference (statics_reference: no code of the package's forces).
    """
    scene = rigid('five_link')
    res = solve_loaded(scene, 0.0, Load((0.0, 4000.0, 0.0), 'cp'))
    ends = res.link_forces_n
    assert 'lower_rear' not in ends
    assert ends['lower_rear_body_end'] == pytest.approx(3707.2, abs=0.05)
    assert ends['lower_rear_carrier_end'] == pytest.approx(3111.9, abs=0.05)
    solved = reference.Solved(scene, 0.0)
    pose, lam, _, _, _ = solved.loaded(Load((0.0, 4000.0, 0.0), 'cp'))
    old = reference.pickup_forces(scene, solved.system, pose, lam, 0.0)['link_forces_n']
    link = next(c for c in scene.constraints if c.name == 'lower_rear')
    spring = next(e for e in scene.elements if e.type == 'spring')
    carrier = pose.c[0] + pose.r[0] @ (link.carrier - solved.mech.design_center)
    along = (carrier - link.base[0]) / np.linalg.norm(carrier - link.base[0])
    s = (spring.mount.point - link.base[0]) @ (link.carrier - link.base[0]) / np.linalg.norm(
        link.carrier - link.base[0]) ** 2
    mount = link.base[0] + s * (carrier - link.base[0])
    push = res.spring_forces_n[spring.name] * (mount - spring.body) / np.linalg.norm(
        mount - spring.body)   # on the link, + compressed: away from the body point
    body, carried = ends['lower_rear_body_end'], ends['lower_rear_carrier_end']
    assert body - carried == pytest.approx(push @ along, rel=1e-9)
    assert 0.5 * (body + carried) == pytest.approx(old['lower_rear'], rel=1e-9)


@pytest.mark.parametrize('name', ['double_wishbone', 'five_link', 'macpherson'])
def test_a_rigid_scene_s_pose_rates_are_exactly_zero(name):
    """Nothing moves with the travel held: 0.0, not round-off (issue 36 item 18)."""
    comp = compliance(rigid(name), 20.0)
    assert comp.status == Status.OK
    for key, value in comp.rates.items():
        if not key.startswith('jacking'):
            assert value == 0.0, key
    assert not comp.matrix.any() and not comp.matrix_si.any()


@pytest.mark.parametrize('travel', TRAVELS)
def test_the_held_travel_s_row_and_column_of_the_matrix_are_exactly_zero(travel):
    """Any load's dz and any response to Fz at the wheel centre: 0.0, by construction."""
    comp = compliance(load_scene(BUSHED), travel)
    assert not comp.matrix[2].any() and not comp.matrix[:, 2].any()
    assert not comp.matrix_si[2].any() and not comp.matrix_si[:, 2].any()
    assert np.abs(comp.matrix).max() > 0.1   # the rest is there


@given(st.one_of(st.floats(-1e7, 1e7), st.sampled_from([5e-324, -1e-300, 1e30, 1e300])))
@settings(max_examples=25, deadline=None)
def test_a_vertical_force_at_the_wheel_centre_moves_nothing_and_is_held_whole(fz):
    """
    The travel is held (doc/kc.md): Fz at the wheel centre goes to the holding force alone.

    The pose does not depend on Fz by construction (the held row leaves the system,
    kkt.py): it is the unloaded one bit for bit. The holding force is the unloaded one less
    Fz, to the round-off of the sum (4 eps of its terms).
    """
    scene = load_scene('five_link_bushings')
    free = solve_loaded(scene, 10.0, Load())
    res = solve_loaded(scene, 10.0, Load((0.0, 0.0, fz), 'wc'))
    assert res.status == Status.OK, res.message
    assert np.array_equal(res.wheel_center_mm, free.wheel_center_mm)
    assert np.array_equal(res.rotation, free.rotation)
    eps = np.finfo(float).eps
    assert res.holding_force_n == pytest.approx(free.holding_force_n - fz, rel=0, abs=4 * eps * (
        abs(fz) + abs(free.holding_force_n)))


def test_a_moment_too_large_names_its_real_last_residual():
    """
    1e300 N m (issue 36 item 12): not carried, and the message says its residual, not 0 N.

    The last attempt splits the moment in 64 and fails at its first increment, from the
    unloaded pose: its residual is that increment's moment over the lever, 1e303 N mm / 64 /
    lever (the unloaded residual, 1e-10 N, is lost in it).
    """
    scene = load_scene('five_link_bushings')
    res = solve_loaded(scene, 0.0, Load(moment_nm=(1e300, 0.0, 0.0)))
    lever = compile_scene(scene).lever
    assert res.status == Status.NOT_CARRIED
    assert res.residual == pytest.approx(1e303 / 64 / lever, rel=1e-12)
    assert f'(last residual {res.residual:.3g} N)' in res.message
