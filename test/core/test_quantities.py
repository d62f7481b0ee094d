# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The registry of quantities (core/measure/quantities.py).

Every output names only what it declares.
"""

import csv
import json
from pathlib import Path
import re

from linkage_ros.answer.protocol import ANSWER_TYPES
from linkage_ros.core.measure import alignment, quantities as registry
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import Continuation
from linkage_ros.core.vary import available, outputs as study_quantities, variant_kernel
from linkage_ros.record import rerun_draw
from linkage_ros.ros import corner, messages
from linkage_ros.ros.parameters import PARAMETERS
from linkage_ros.study.tolerance import Tolerance
from linkage_ros.tools import axle as axle_tool, kinematic_map, sweep as sweep_tool
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
# linkage-sweep double_wishbone --rack 0 --alignment --elements, as users' scripts read it
DOUBLE_WISHBONE_HEADER = (
    'travel_mm,camber_deg,toe_deg,wheel_center_x_mm,wheel_center_y_mm,wheel_center_z_mm,qx,qy,'
    'qz,qw,residual_mm,iterations,rack_mm,camber_gain_deg_per_mm,bump_steer_deg_per_mm,'
    'wheel_center_vx_per_travel,wheel_center_vy_per_travel,caster_deg,kingpin_inclination_deg,'
    'scrub_radius_mm,mechanical_trail_mm,track_change_mm,wheelbase_change_mm,'
    'wheel_center_lateral_shift_mm,wheel_center_longitudinal_shift_mm,svic_x_mm,svic_z_mm,'
    'fvic_y_mm,fvic_z_mm,screw_axis_x,screw_axis_y,screw_axis_z,screw_pitch_mm_per_rad,'
    'caster_geometric_deg,kingpin_inclination_geometric_deg,scrub_radius_geometric_mm,'
    'mechanical_trail_geometric_mm,kingpin_offset_wheel_centre_geometric_mm,'
    'damper_length_mm,damper_ratio,spring_length_mm,spring_ratio,spring_force_N,'
    'spring_wheel_rate_N_per_mm')


def unknown(names):
    """Return the names the registry lacks."""
    return [n for n in names if not registry.known(n)]


def sweep_header(tmp_path, *argv):
    out = tmp_path / 'sweep.csv'
    assert sweep_tool.main([*argv, '-o', str(out)]) == 0
    with open(out, newline='') as f:
        return next(csv.reader(f))


# --- the registry itself ----------------------------------------------------------------------

def test_every_name_ends_in_its_table_unit_and_every_si_name_in_its_si_unit():
    for q in registry.QUANTITIES.values():
        end = registry.suffix(q.unit)
        assert not end or q.name.endswith('_' + end), q
        si_end = registry.suffix(q.si_unit)
        assert not si_end or q.si_name.endswith('_' + si_end), q
        assert q.doc and q.group and q.factor > 0, q


def test_table_to_si_factors_are_the_units_own():
    # degrees to radians, millimetres to metres: factors computed independently here
    expected = {'mm': 1e-3, 'deg': np.pi / 180, 'deg/mm': np.pi / 180 * 1e3, 'N': 1.0,
                'N/mm': 1e3, 'mm/rad': 1e-3, 'Nm': 1.0, 'Nm/deg': 180 / np.pi, '%': 1e-2,
                '1': 1.0}
    for unit, factor in expected.items():
        assert registry.UNITS[unit][1] == pytest.approx(factor, rel=1e-15)


def test_signs_are_the_conventions_of_the_package():
    signs = {'travel_mm': '+ = bump', 'camber_deg': '+ = top outboard', 'toe_deg': '+ = toe-in',
             '{side}_camber_deg': '+ = top outboard', '{side}_toe_deg': '+ = toe-in',
             'rack_mm': '+ = rack to the left', 'roll_deg': '+ = right side down'}
    assert {n: registry.quantity(n).sign for n in signs} == signs


def test_templates_find_concrete_names_and_nothing_else():
    assert registry.quantity('spring_force_N').name == '{element}_force_N'
    assert registry.quantity('right_toe_ground_deg').name == '{side}_toe_ground_deg'
    assert registry.quantity('arb_ratio_left_deg_per_mm').name == 'arb_ratio_{side}_deg_per_mm'
    assert not registry.known('middle_toe_deg') and not registry.known('camber')
    assert registry.columns_of_element('s', rate=False) == ['s_length_mm', 's_ratio']


def test_si_names_are_one_per_quantity():
    si = [q.si_name for q in registry.QUANTITIES.values()]
    assert len(si) == len(set(si))


def test_doc_quantities_md_is_the_registry():
    assert (ROOT / 'doc' / 'quantities.md').read_text() == registry.markdown_table(), (
        'doc/quantities.md is stale: '
        'python -m linkage_ros.core.measure.quantities > doc/quantities.md')


# --- the outputs ------------------------------------------------------------------------------

def test_linkage_sweep_names_only_registry_quantities_in_unchanged_order(tmp_path):
    header = sweep_header(tmp_path, 'double_wishbone', '--travel', '0:10:10', '--rack', '0',
                          '--alignment', '--elements')
    assert ','.join(header) == DOUBLE_WISHBONE_HEADER
    assert unknown(header) == []
    five_link = sweep_header(tmp_path, 'five_link', '--travel', '0:10:10',
                             '--alignment', '--elements')
    assert unknown(five_link) == [] and len(five_link) > 40


def test_linkage_axle_names_only_registry_quantities(tmp_path):
    # front: a rack, anti-dive and an anti-roll bar with a rate; rear: anti-lift, anti-squat
    headers = []
    for argv in (['--axle', 'front', '--heave=-10:10:10', '--rack', '2'],
                 ['--axle', 'rear', '--heave=-10:10:10']):
        out = tmp_path / 'axle.csv'
        assert axle_tool.main(['demo_vehicle', *argv, '-o', str(out)]) == 0
        headers += out.read_text().splitlines()[0].split(',')
    for name in ('ackermann_pct', 'arb_roll_stiffness_Nm_per_deg', 'anti_dive_pct',
                 'anti_squat_pct'):
        assert name in headers
    assert unknown(headers) == []


def test_corner_and_axle_maps_name_only_registry_quantities(tmp_path, capsys):
    for argv in (['double_wishbone', '--travel', '-10:10:10', '--rack', '-5:5:5'],
                 ['demo_vehicle', '--axle', 'front', '--travel', '-10:10:10']):
        folder = tmp_path / argv[0]
        assert kinematic_map.main([*argv, '-o', str(folder), '--format', 'npz']) == 0
        for path in folder.glob('*.npz'):
            assert unknown(np.load(path).files) == [], path.name
    capsys.readouterr()


def test_the_node_alignment_labels_are_the_registry_si_names_of_its_topic():
    cont = Continuation(load_scene('double_wishbone'))
    s = cont.solve(25.0, 8.0)
    msg = messages.alignment_array(alignment(cont.scene, cont.mech, s.wheel_center, s.rotation,
                                             s.rack))
    labels = [d.label for d in msg.layout.dim]
    assert labels == [registry.quantity(n).si_name for n in registry.TOPICS['alignment']]
    assert all(registry.known_si(label) for label in labels)


def test_the_node_topics_that_carry_quantities_are_the_registry_topics():
    params = {name: spec.default for name, spec in PARAMETERS.items()}
    params.update(alignment=True, markers=True, travel_joint='wheel')
    topics = corner.corner_topics(load_scene('double_wishbone'), params)
    carrying = set(topics) - {'markers', 'joint_states'}   # drawings; the vehicle's joints
    assert carrying == set(registry.TOPICS)
    assert list(ANSWER_TYPES) == ['wheel_carrier_pose', 'camber', 'toe']
    assert set(ANSWER_TYPES) <= set(registry.TOPICS)


@pytest.mark.parametrize('scene', ['double_wishbone', 'five_link', 'macpherson'])
def test_study_quantities_are_registry_quantities(scene):
    s = load_scene(scene)
    assert unknown(available(s)) == []
    assert unknown(study_quantities.element_names(s)) == []
    assert set(study_quantities.ALIGNMENT_COLUMNS) == set(sweep_tool.ALIGNMENT_COLUMNS)


def test_tolerance_and_variant_outputs_are_the_sweeps_wheel_quantities():
    assert variant_kernel.QUANTITIES == study_quantities.SWEEP_COLUMNS
    assert variant_kernel.OUTPUTS == len(variant_kernel.QUANTITIES)
    assert unknown(variant_kernel.QUANTITIES) == []
    assert 'quantities' in Tolerance._fields


def test_rerun_series_are_registry_quantities_titled_by_it():
    assert unknown(rerun_draw.SERIES) == []
    assert rerun_draw.SERIES['camber_deg'] == 'camber (deg)'
    assert rerun_draw.SERIES['travel_mm'] == 'travel (mm)'


def test_the_foxglove_layout_plots_registry_quantities_with_their_units_and_signs():
    layout = json.loads((ROOT / 'config' / 'foxglove_layout.json').read_text())
    plots = {k: v for k, v in layout['configById'].items() if k.startswith('Plot!')}
    assert plots
    for panel in plots.values():
        for path in panel['paths']:
            # /camber.data.@degrees, /front_left/alignment.data[2]: a corner's topic, a field;
            # /wheel_carrier_pose.pose.position.z: the pose's wheel centre, x y z in order
            match = re.fullmatch(r'/(?:\w+/)*(\w+)\.data(?:\[(\d+)\])?(\.@degrees)?',
                                 path['value'])
            pose = re.fullmatch(r'/(?:\w+/)*(wheel_carrier_pose)\.pose\.position\.([xyz])',
                                path['value'])
            assert match or pose, f'{path["value"]}: a path this test cannot read; teach it'
            if pose:
                topic, index, degrees = pose[1], 'xyz'.index(pose[2]), None
            else:
                topic, index, degrees = match.groups()
            names = registry.TOPICS[topic]
            q = registry.quantity(names[int(index or 0)])
            unit = 'deg' if degrees else q.si_unit
            assert panel['title'].startswith(f'{q.label} ({unit}'), panel['title']
            assert q.sign in panel['title']


def doc_table_names():
    """Yield (file, name) of every backticked quantity-like name in a table of the docs."""
    ends = {registry.suffix(u) for u in registry.UNITS} | {
        registry.suffix(s) for s, _, _ in registry.UNITS.values()}
    ends = '|'.join(sorted(e for e in ends if e))
    looks = re.compile(rf'[a-z]\w*_(?:{ends}|ratio|per_travel)')
    parameters = set(PARAMETERS)   # the node's parameters are settings, not quantities
    for path in [ROOT / 'README.md', *sorted((ROOT / 'doc').glob('*.md'))]:
        for line in path.read_text().splitlines():
            if not line.startswith('|'):
                continue
            for token in re.findall(r'`([^`]+)`', line):
                token = re.sub(r'<\w+>', 'x', token)   # <name>_ratio: an element's
                plain = re.sub(r'\{\w+\}', 'x', token)
                if looks.fullmatch(plain) and token not in parameters:
                    yield path.name, token


def test_doc_tables_name_only_registry_quantities():
    found = list(doc_table_names())
    # the alignment, axle and anti-roll bar docs' tables, beside the registry's own
    assert len([f for f, _ in found if f != 'quantities.md']) >= 20
    assert [(f, n) for f, n in found
            if not (registry.known(n) or registry.known_si(n))] == []


def test_the_doc_of_the_alignment_message_lists_its_fields_in_order():
    text = (ROOT / 'doc' / 'alignment.md').read_text()
    table = text[text.index('Fields of the node'):]
    listed = re.findall(r'^\| `(\w+)`(?:, `(\w+)`)? \|', table, re.M)
    labels = [n for pair in listed for n in pair if n]
    assert labels == list(messages.ALIGNMENT_FIELDS)


def test_the_alignment_doc_says_the_node_publishes_14_of_the_25_columns():
    text = ' '.join((ROOT / 'doc' / 'alignment.md').read_text().split())
    assert f'adds these {len(sweep_tool.ALIGNMENT_COLUMNS)} columns' in text
    assert f'The node publishes {len(messages.ALIGNMENT_FIELDS)} of them' in text
