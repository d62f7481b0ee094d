# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-study fit: hardpoints fitted to target curves, checked by sweeping the written scene."""

from pathlib import Path
import subprocess
import sys
import time

from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import sweep
from linkage_ros.study.fit import fit
from linkage_ros.study.targets import load_targets
import numpy as np
import pytest
import yaml

PROG = str(Path(sys.executable).parent / 'linkage-study')
BUMP_STEER = """scene: double_wishbone
free:
  tie_rod.base: {x: [-30, 30], y: [-30, 30], z: [-30, 30]}
targets:
  - {quantity: toe_deg, travel: [-50, 50, 5], value: 0.0, weight: 1.0}
"""


def run(*args, cwd=None, timeout=600):
    """Run linkage-study; return (status, stdout, stderr)."""
    done = subprocess.run([PROG, *args], capture_output=True, text=True, timeout=timeout,
                          cwd=cwd)
    return done.returncode, done.stdout, done.stderr


def largest_toe(scene):
    """Return the largest |toe| (deg) over -50..50 mm by linkage-sweep's solver."""
    result = sweep(scene, np.arange(-50.0, 51.0, 1.0))
    assert result.success, result.message
    return float(np.degrees(np.abs(result.toe)).max())


def test_a_fitted_tie_rod_base_cuts_the_bump_steer_tenfold_within_its_bounds(tmp_path):
    (tmp_path / 'targets.yaml').write_text(BUMP_STEER)
    status, out, err = run('fit', 'targets.yaml', '-o', 'fitted.yaml', '--plot', 'fit.png',
                           cwd=tmp_path)
    assert status == 0, err
    original, fitted = load_scene('double_wishbone'), load_scene(tmp_path / 'fitted.yaml')
    before, after = largest_toe(original), largest_toe(fitted)
    assert before > 0.5 and after <= before / 10, (before, after)
    names = original.point_names
    moved = fitted.points - original.points
    tie_rod = names.index('tie_rod.base')
    assert np.all(np.abs(moved[tie_rod]) <= 30.0) and np.abs(moved[tie_rod]).max() > 1.0
    assert not np.delete(moved, tie_rod, axis=0).any()   # nothing else moved
    text = (tmp_path / 'fitted.yaml').read_text()
    assert text.startswith('# Fitted by linkage-study fit from targets.yaml')
    assert '#   tie_rod.base.z: 250 -> ' in text
    assert 'reference' not in yaml.safe_load(text)   # results for the original design only
    assert 'toe_deg at 21 travels: largest error 0.514724 -> ' in err
    assert (tmp_path / 'fit.png').read_bytes()[:4] == b'\x89PNG'


def test_springs_on_a_moved_link_keep_their_fraction_of_it(tmp_path):
    # five_link's spring sits on lower_rear: moving that link's body point moves the spring's
    # point with it, and the written scene still loads (the point stays on the link's line).
    (tmp_path / 'targets.yaml').write_text("""scene: five_link
free:
  lower_rear.base: {z: [-20, 20]}
targets:
  - {quantity: spring_length_mm, travel: [0, 0, 1], value: 300.0}
""")
    status, out, err = run('fit', 'targets.yaml', '-o', 'fitted.yaml', cwd=tmp_path)
    assert status == 0, err
    scene = load_scene(tmp_path / 'fitted.yaml')
    spring = [e for e in scene.elements if e.name == 'spring'][0]
    link = [c for c in scene.constraints if c.name == 'lower_rear'][0]
    span = link.carrier - link.base[0]
    fraction = (spring.mount.point - link.base[0]) @ span / (span @ span)
    assert fraction == pytest.approx(0.5, abs=1e-9)   # [-80, 472.5, 173.5] halfway at design
    assert link.base[0][2] != 185.0


def test_a_fit_that_strays_into_designs_that_do_not_assemble_backs_off(tmp_path):
    # Wide bounds and targets far out of reach: least squares tries steps whose designs do
    # not assemble over the travels (links that cannot reach); those come back as large
    # residuals, the steps are rejected, and the fit ends on a design that assembles.
    (tmp_path / 'wild.yaml').write_text("""scene: double_wishbone
free:
  upper_arm.carrier: {x: [-200, 200], y: [-200, 200], z: [-200, 200]}
  tie_rod.carrier: {x: [-200, 200], y: [-200, 200], z: [-200, 200]}
targets:
  - {quantity: camber_deg, travel: [-80, 80, 10], value: 5.0}
  - {quantity: toe_deg, travel: [-80, 80, 10], value: -3.0}
""")
    targets = load_targets(str(tmp_path / 'wild.yaml'))
    result = fit(targets)
    assert result.unassembled > 0
    assert result.after.assembled
    cost = [float(np.sum(e.residual ** 2)) for e in (result.before, result.after)]
    assert cost[1] < cost[0]


def test_targets_that_cannot_be_met_are_said_so_with_status_1(tmp_path):
    # toe 0 and toe 1 deg at the same travels: no design meets both within 0.01 deg
    (tmp_path / 'clash.yaml').write_text("""scene: double_wishbone
free:
  tie_rod.base: {x: [-10, 10], y: [-10, 10], z: [-10, 10]}
targets:
  - {quantity: toe_deg, travel: [-20, 20, 10], value: 0.0, tolerance: 0.01}
  - {quantity: toe_deg, travel: [-20, 20, 10], value: 1.0, tolerance: 0.01}
""")
    status, out, err = run('fit', 'clash.yaml', '-o', 'fitted.yaml', cwd=tmp_path)
    assert status == 1, err
    assert 'tolerance 0.01: NOT met' in err
    assert '2 targets cannot be met within the bounds' in err
    load_scene(tmp_path / 'fitted.yaml')   # the best design found is written, and loads


@pytest.mark.parametrize('targets, says', [
    (BUMP_STEER.replace('tie_rod.base:', 'tie_rod.bsae:'),
     'free.tie_rod.bsae: not a hardpoint of the scene double_wishbone'),
    (BUMP_STEER.replace('x: [-30, 30]', 'x: [30, -30]'),
     'free.tie_rod.base.x: min 30 is above max -30'),
    (BUMP_STEER.replace('y: [-30, 30]', 'y: [5, 5]'),
     'free.tie_rod.base.y: min and max are both 5: leave the axis out'),
    (BUMP_STEER.replace('scene: double_wishbone', 'scene: nowhere'),
     'nowhere: scene: no such file'),
    (BUMP_STEER.replace('scene: double_wishbone', 'scene: five_link')
     .replace('quantity: toe_deg', 'quantity: caster_deg'),
     "targets[0].quantity: 'caster_deg' is not a quantity of the scene five_link"),
    (BUMP_STEER.replace('value: 0.0', 'value: [0, 1]'),
     'targets[0].value: 2 values for 21 travels'),
    (BUMP_STEER + 'starts: 3\n', 'starts: unknown key'),
])
def test_a_mistake_in_a_targets_file_is_one_line_with_status_2(targets, says, tmp_path):
    (tmp_path / 'targets.yaml').write_text(targets)
    status, out, err = run('fit', 'targets.yaml', '-o', 'fitted.yaml', cwd=tmp_path)
    assert status == 2 and out == '', (out, err)
    assert err.count('\n') == 1 and err.startswith('linkage-study: '), err
    assert says in err and 'Traceback' not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ['targets.yaml']


def test_an_unreachable_scheduler_is_said_within_seconds_with_status_2(tmp_path):
    (tmp_path / 'targets.yaml').write_text(BUMP_STEER)
    start = time.monotonic()
    # port 9 (discard) on this machine: nothing listens there
    status, out, err = run('fit', 'targets.yaml', '-o', 'fitted.yaml', '--scheduler',
                           'tcp://127.0.0.1:9', cwd=tmp_path, timeout=120)
    took = time.monotonic() - start
    assert status == 2 and out == '', (out, err)
    assert err.count('\n') == 1 and 'cannot reach the Dask scheduler tcp://127.0.0.1:9' in err
    assert took < 60, took   # 5 s to connect, plus starting Python on a busy machine
    assert sorted(p.name for p in tmp_path.iterdir()) == ['targets.yaml']


METRE_SCENE = """scene: chrono_generic_doublewishbone
free:
  LowerControlArm.axis0: {z: [-1.0e1, 10]}
targets:
  - {quantity: toe_deg, travel: [-20, 20, 10], value: 0.0}
"""


def test_travels_and_bounds_of_targets_are_mm_in_a_metre_scene(tmp_path):
    # Before, they were read in the scene's units: travel [-20, 20, 10] m, bounds +-10 m;
    # and -1.0e1 was text to YAML 1.1.
    (tmp_path / 'targets.yaml').write_text(METRE_SCENE)
    targets = load_targets(tmp_path / 'targets.yaml')
    assert targets.design.scene.units == 'm'
    assert targets.targets[0].travel.tolist() == [-20.0, -10.0, 0.0, 10.0, 20.0]
    assert (targets.lower.tolist(), targets.upper.tolist()) == ([-10.0], [10.0])


def test_the_bundled_targets_keep_the_camber_gain_of_the_design():
    # Its comment says the fit keeps the camber gain: the value asked is the design's.
    from linkage_ros.core.vary import sensitivities
    targets = load_targets(Path(__file__).parents[2] / 'config' / 'study'
                           / 'bump_steer_targets.yaml')
    gain = targets.targets[1]
    assert gain.quantity == 'camber_gain_deg_per_mm' and gain.travel.tolist() == [0.0]
    design = sensitivities(targets.design.scene, [0.0], wanted=(gain.quantity,))
    # the file gives it to 5 significant digits: within half a unit of the 5th
    assert abs(gain.value[0] - design.nominal[0, 0]) <= 5e-7


def test_fit_does_not_write_over_the_scene_its_targets_name(tmp_path):
    scene = tmp_path / 'mine.yaml'
    scene.write_text((Path(__file__).parents[2] / 'config' / 'scenes'
                      / 'double_wishbone.yaml').read_text())
    before = scene.read_text()
    (tmp_path / 'targets.yaml').write_text(BUMP_STEER.replace('double_wishbone', 'mine.yaml'))
    status, out, err = run('fit', 'targets.yaml', '-o', 'mine.yaml', cwd=tmp_path)
    assert status == 2 and out == '', err
    assert err == f'linkage-study: -o: mine.yaml is the input {scene}; give another file name\n'
    assert scene.read_text() == before


def test_fit_plot_and_scene_cannot_be_one_file(tmp_path):
    (tmp_path / 'targets.yaml').write_text(BUMP_STEER)
    status, out, err = run('fit', 'targets.yaml', '-o', 'a.yaml', '--plot', 'a.yaml',
                           cwd=tmp_path)
    assert (status, err) == (2, 'linkage-study: -o: a.yaml is also the output of --plot; '
                                'give another file name\n')
