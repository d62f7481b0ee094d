# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Bushings through Chrono::Vehicle JSON: what export writes, import reads back the same.

Chrono's "Bushing Data" (ChJoint::CreateBushing) is one bushing per joint: one linear
stiffness in every direction, "Stiffness Rotational" on the axes a joint would hold and
"DOF" "Stiffness Rotational" on those it frees. A scene's bushing (model/bushing.py) can be
stiffer along its axis than across it, or across than along, and an arm can hold one at each
pivot: the export writes the isotropic part as Bushing Data and the rest as linear springs
(TSDAs) at the bushing, and the import folds them back. The compliance of the corner
(linkage_ros.core.statics.compliance) is the specification: the same rates and 6x6 matrix.
"""

from pathlib import Path

from linkage_ros.chrono.files import export_file, import_file
from linkage_ros.core import load_scene
from linkage_ros.core.model.bundled import bundled_scenes
from linkage_ros.core.model.scene import parse_scene
from linkage_ros.core.statics import compliance
import numpy as np
import pytest
import yaml

BUSHED = sorted(n for n in bundled_scenes()
                if any(c.bushing is not None for c in load_scene(n).constraints))


def round_trip(name, tmp_path):
    text, summary = export_file(name)
    source = tmp_path / f'{name}.json'
    source.write_text(text)
    out = tmp_path / f'{name}.yaml'
    texts, _ = import_file(str(source), str(out))
    return parse_scene(yaml.safe_load(texts[str(out)]), source=str(out)), summary


def test_the_bundled_scenes_hold_every_kind_of_bushing():
    kinds = {(c.type, c.bushing.at if c.type == 'circle' else '',
              float(np.sign(c.bushing.axial - c.bushing.radial)))
             for n in BUSHED for c in load_scene(n).constraints if c.bushing is not None}
    # arms at the pivots softer along the axis, at the centre isotropic; links stiffer along
    assert {('circle', 'pivots', -1.0), ('circle', 'centre', 0.0), ('sphere', '', 1.0)} <= kinds


@pytest.mark.parametrize('name', BUSHED)
def test_export_then_import_gives_the_same_compliance(name, tmp_path):
    scene, (back, _) = load_scene(name), round_trip(name, tmp_path)
    before, after = compliance(scene), compliance(back)
    assert before.status == after.status == 0, (before.message, after.message)
    # Tolerance: points and rates come back within a few ulps (mm -> m -> mm, (a - r) + r),
    # which moves the rates by about 1 relative per mm of a point (measured: 0.5-0.7), so
    # 1e-13; what is left is the noise floor of the compliance itself (its Newton stops at
    # a 1e-11 mm step): changing every point at random by 1e-13 mm moves the rates by up to
    # 5e-11 relative (measured on both bushed scenes). 1e-9 keeps a margin of 20 over that.
    for key, value in before.rates.items():
        assert after.rates[key] == pytest.approx(value, rel=1e-9, abs=1e-12), key
    scale = np.abs(before.matrix).max()
    np.testing.assert_allclose(after.matrix, before.matrix, rtol=1e-9, atol=1e-9 * scale)


@pytest.mark.parametrize('name', BUSHED)
def test_every_bushing_comes_back_with_its_rates(name, tmp_path):
    scene, (back, _) = load_scene(name), round_trip(name, tmp_path)
    by_name = {c.name: c for c in back.constraints}
    for c in scene.constraints:
        if c.bushing is None:
            continue
        got = by_name[c.name].bushing
        assert got is not None, c.name
        for key in ('axial', 'radial', 'torsion', 'conical'):   # N/mm, N m/deg
            assert getattr(got, key) == pytest.approx(getattr(c.bushing, key), rel=1e-12)
        if c.type == 'circle':
            assert got.at == c.bushing.at


def _chrono_stiffness(data, body, point):
    """
    Return the translational stiffness (3, 3) N/m that Chrono puts at a bushing's point.

    Read from the JSON alone: ChJoint::CreateBushing's K_lin on every axis of each joint of
    body at point, plus each TSDA from a fixed body to body ending there, k e e^T at design.
    """
    stiff = np.zeros((3, 3))
    for joint in data['Joints']:
        if joint['Body2'] == body and np.allclose(joint['Position'], point, atol=1e-15):
            stiff += joint['Bushing Data']['Stiffness Linear'] * np.eye(3)
    for tsda in data['TSDAs']:
        if tsda['Body2'] == body and np.allclose(tsda['Point2'], point, atol=1e-15):
            e = np.subtract(tsda['Point1'], tsda['Point2'])
            assert np.linalg.norm(e) == pytest.approx(tsda['Free Length'], rel=1e-15)
            e /= np.linalg.norm(e)
            stiff += tsda['Spring Coefficient'] * np.outer(e, e)
    return stiff


@pytest.mark.parametrize('name', ['double_wishbone_bushings', 'five_link_bushings'])
def test_chrono_holds_each_bushing_with_the_scenes_rates_at_its_place(name):
    import json
    data = json.loads(export_file(name)[0])
    scene = load_scene(name)
    for c in scene.constraints:
        if c.bushing is None:
            continue
        if c.type == 'circle':
            axis, points = c.base[1] - c.base[0], c.base   # at: pivots, both bundled
        else:
            axis, points = c.carrier - c.base[0], c.base[:1]
        a = np.outer(axis, axis) / (axis @ axis)
        want = 1000.0 * (c.bushing.axial * a + c.bushing.radial * (np.eye(3) - a))   # N/m
        for point in points:
            got = _chrono_stiffness(data, c.name, [float(v) / 1000.0 for v in point])
            np.testing.assert_allclose(got, want, rtol=0.0, atol=1e-9 * np.abs(want).max())
        if c.type == 'circle':   # ReadBushingDataJSON: N m/rad, "DOF" the revolute's own turn
            joints = [j for j in data['Joints'] if j['Body2'] == c.name]
            assert len(joints) == 2
            for joint in joints:
                bushing = joint['Bushing Data']
                assert bushing['Stiffness Rotational'] == pytest.approx(
                    np.degrees(c.bushing.conical), rel=1e-15)
                assert bushing['DOF']['Stiffness Rotational'] == pytest.approx(
                    np.degrees(c.bushing.torsion), rel=1e-15)


def test_every_bushing_data_has_the_keys_chronos_reader_asks_for(tmp_path):
    import json
    for name in BUSHED:
        data = json.loads(export_file(name)[0])
        found = [j['Bushing Data'] for j in data.get('Joints', []) if 'Bushing Data' in j] + [
            data[k]['Bushing Data'] for k in data if isinstance(data[k], dict)
            and 'Bushing Data' in data[k]]
        assert found, name
        keys = {'Stiffness Linear', 'Damping Linear', 'Stiffness Rotational',
                'Damping Rotational'}   # ReadBushingDataJSON, GetDouble on each
        for bushing in found:
            assert set(bushing) == keys | {'DOF'} and set(bushing['DOF']) == keys


def test_like_a_named_template_that_cannot_hold_a_bushing_is_refused(tmp_path):
    import subprocess
    import sys
    out = tmp_path / 'dw.json'
    program = Path(sys.executable).parent / 'linkage-chrono'
    like = Path(load_scene('double_wishbone').source).parents[1] / 'chrono' / 'generic' \
        / 'suspension' / 'DoubleWishbone.json'
    run = subprocess.run([str(program), 'export', 'double_wishbone_bushings', '-o', str(out),
                          '--like', str(like)], capture_output=True, text=True)
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
    assert 'upper_arm: its bushing' in run.stderr and 'at: pivots' in run.stderr
    assert not out.exists()


def test_a_strut_scene_with_a_bushing_no_template_holds_is_refused(tmp_path):
    from linkage_ros.chrono.reader import ChronoError
    path = Path(load_scene('macpherson').source)
    data = yaml.safe_load(path.read_text())
    arm = next(c for c in data['constraints'] if c['type'] == 'circle')
    arm['bushing'] = {'axial': 3.0e5, 'radial': 1.0e6, 'at': 'centre'}   # N/m: units m
    scene = tmp_path / 'strut.yaml'
    scene.write_text(yaml.safe_dump(data))
    with pytest.raises(ChronoError, match=f"{arm['name']}: its bushing cannot go into a "
                       'MacPhersonStrut file: axial 300 and radial 1000 N/mm'):
        export_file(str(scene))


def test_like_writes_the_scenes_arm_bushing_and_keeps_the_originals_damping(tmp_path):
    import json
    from linkage_ros.chrono.reader import read_chrono
    original = Path(load_scene('double_wishbone').source).parents[1] / 'chrono' / 'hmmwv' \
        / 'suspension' / 'HMMWV_DoubleWishboneFront_bushings.json'
    out = tmp_path / 'b.yaml'
    text = import_file(str(original), str(out))[0][str(out)]
    before = read_chrono(original)['Lower Control Arm']['Bushing Data']
    stiffer = text.replace(f"axial: {before['Stiffness Linear']!r}", 'axial: 9.0e+7', 1) \
        .replace(f"radial: {before['Stiffness Linear']!r}", 'radial: 9.0e+7', 1)
    assert stiffer != text
    out.write_text(stiffer)
    data = json.loads(export_file(str(out), str(original))[0])
    ours = data['Upper Control Arm']['Bushing Data']   # the upper arm comes first in the file
    assert ours['Stiffness Linear'] == 9.0e7
    assert ours['Damping Linear'] == before['Damping Linear']
    unchanged = data['Lower Control Arm']['Bushing Data']
    assert unchanged == before   # equal to 1e-12 after N/m -> N/mm -> N/m: the original's bytes


def test_springs_named_as_bushing_parts_but_of_another_shape_stay_springs(tmp_path):
    import json
    data = json.loads(export_file('five_link_bushings')[0])
    for tsda in data['TSDAs']:
        if tsda['Name'] == 'tie_rod_bushing_base_axial':
            tsda['Point1'][2] += 0.01   # no longer along the link
    source = tmp_path / 'x.json'
    source.write_text(json.dumps(data))
    texts, summary = import_file(str(source), str(tmp_path / 'x.yaml'))
    scene = yaml.safe_load(texts[str(tmp_path / 'x.yaml')])
    assert "tie_rod: springs named as its bushing's parts but not of their shape" in summary
    assert 'tie_rod_bushing_base_axial' in {e['name'] for e in scene['elements']}
    rod = next(c for c in scene['constraints'] if c['name'] == 'tie_rod')
    assert rod['bushing']['axial'] == rod['bushing']['radial'] == 1.0e6   # the isotropic part


def test_like_a_generic_original_takes_the_scenes_new_bushing_rates(tmp_path):
    original = tmp_path / 'five.json'
    original.write_text(export_file('five_link_bushings')[0])
    out = tmp_path / 'five.yaml'
    text = import_file(str(original), str(out))[0][str(out)]
    rod = next(line for line in text.splitlines() if line.startswith('  - {name: tie_rod'))
    softer = rod.replace('axial: 5000000.0', 'axial: 2500000.0')
    assert softer != rod
    out.write_text(text.replace(rod, softer))
    again = tmp_path / 'again.json'
    again.write_text(export_file(str(out), str(original))[0])
    back, _ = import_file(str(again), str(tmp_path / 'back.yaml'))
    scene = parse_scene(yaml.safe_load(back[str(tmp_path / 'back.yaml')]), source='back')
    bushing = next(c for c in scene.constraints if c.name == 'tie_rod').bushing
    assert (bushing.axial, bushing.radial) == pytest.approx((2500.0, 1000.0), rel=1e-12)


def test_like_takes_out_the_bushing_of_an_arm_the_scene_has_rigid(tmp_path):
    import json
    original = Path(load_scene('double_wishbone').source).parents[1] / 'chrono' / 'hmmwv' \
        / 'suspension' / 'HMMWV_DoubleWishboneFront_bushings.json'
    out = tmp_path / 'b.yaml'
    text = import_file(str(original), str(out))[0][str(out)]
    lines = text.splitlines()
    upper = next(i for i, line in enumerate(lines) if 'name: UpperControlArm' in line)
    lines[upper] = lines[upper][:lines[upper].index(', bushing:')] + '}'
    out.write_text('\n'.join(lines) + '\n')
    text, summary = export_file(str(out), str(original))
    assert 'Bushing Data' not in json.loads(text)['Upper Control Arm']
    assert 'Bushing Data' in json.loads(text)['Lower Control Arm']
    assert 'UpperControlArm: the original\'s "Bushing Data" is taken out' in summary


@pytest.mark.parametrize('mass', [True, False])
def test_a_named_templates_tie_rod_bushing_is_named_not_taken(mass, tmp_path):
    import json
    from linkage_ros.chrono.reader import read_chrono
    original = Path(load_scene('double_wishbone').source).parents[1] / 'chrono' / 'hmmwv' \
        / 'suspension' / 'HMMWV_DoubleWishboneFront_bushings.json'
    data = read_chrono(original)
    data['Tierod']['Bushing Data'] = data['Upper Control Arm']['Bushing Data']
    if not mass:   # DoubleWishbone.cpp reads a tie rod's "Bushing Data" only with its "Mass"
        for key in ('Mass', 'Inertia', 'Radius'):
            data['Tierod'].pop(key)
    source = tmp_path / 'rod.json'
    source.write_text(json.dumps(data))
    texts, summary = import_file(str(source), str(tmp_path / 'rod.yaml'))
    scene = yaml.safe_load(texts[str(tmp_path / 'rod.yaml')])
    rod = next(c for c in scene['constraints'] if c['name'] == 'Tierod')
    assert 'bushing' not in rod
    assert 'Tierod: its "Bushing Data" is not imported: ' + (
        'Chrono bushes the link body at both ends' if mass else 'Chrono uses it only') in summary
