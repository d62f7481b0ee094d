# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Error lines that say the right thing, briefly (issue 36, item 12).

A line names the first few offenders of a list and counts the rest; a long name or path is
cut in the middle; a travel beyond the float range in mm is said as outside the range of a
length, after the value as sent; an empty bushing is refused, not taken as rigid.
"""

import copy
from pathlib import Path

from hypothesis import given, settings, strategies as st
from linkage_ros.answer.protocol import Responder
from linkage_ros.core.base import LinkageError, listed, Status
from linkage_ros.core.base.errors import PROBLEM_LIMIT, WHERE_LIMIT
from linkage_ros.core.model import load_scene, parse_scene, SceneError
from linkage_ros.core.solve import Continuation
from linkage_ros.tools.sweep import main
import pytest
import yaml

BUSHED = yaml.safe_load((Path(__file__).resolve().parents[1] / 'data'
                         / 'double_wishbone_bushings.yaml').read_text())


def test_a_scene_of_2005_constraints_is_refused_in_a_line_that_counts_them(tmp_path, capsys):
    # The line listed every constraint: 45 KB for 2005 of them.
    data = yaml.safe_load(Path(load_scene('five_link').source).read_text())
    link = data['constraints'][0]
    data['constraints'] = [dict(link, name=f'link_{i}') for i in range(2005)]
    path = tmp_path / 'many.yaml'
    path.write_text(yaml.safe_dump(data))
    assert main([str(path), '--travel', '0']) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and len(err) < 400, (len(err), err[:500])
    assert (f'{path}: constraints: give 2005 equations from 2005 constraints (link_0 (sphere) '
            '1, link_1 (sphere) 1, link_2 (sphere) 1, link_3 (sphere) 1 and 2001 more)') in err


def test_a_list_names_the_first_four_and_counts_the_rest():
    assert listed([]) == '' and listed(['a']) == 'a'
    assert listed('abcde') == 'a, b, c, d, e'            # one more is named, not counted
    assert listed('abcdef') == 'a, b, c, d and 2 more'


@settings(deadline=None, database=None, max_examples=60)
@given(where=st.text(max_size=5000), problem=st.text(max_size=20000))
def test_every_error_line_is_bounded_whatever_it_holds(where, problem):
    text = str(LinkageError(where, problem))
    assert len(text) <= WHERE_LIMIT + PROBLEM_LIMIT + 2
    if len(where) <= WHERE_LIMIT and len(problem) <= PROBLEM_LIMIT:
        assert text == f'{where}: {problem}'


def test_a_source_of_a_megabyte_is_cut_in_the_middle_saying_how_much():
    source = 'scenes/' + 'x' * 1_000_000 + '.yaml'
    data = copy.deepcopy(BUSHED)
    data['constraints'][0]['bushing']['axial'] = -1.0
    with pytest.raises(SceneError) as info:
        parse_scene(data, source)
    text = str(info.value)
    assert len(text) < WHERE_LIMIT + PROBLEM_LIMIT and 'characters left out' in text
    assert text.startswith('scenes/xxx') and text.endswith(
        '.yaml: constraints[0] (upper_arm).bushing.axial: -1.0 N/mm is outside 0.001 to 1e+11 '
        'N/mm (doc/scenes.md#ranges)')
    assert info.value.source == source   # kept whole for a caller


@pytest.mark.parametrize('written', ['bushing: null', 'bushing:'])
def test_an_empty_bushing_is_refused_not_taken_as_rigid(tmp_path, capsys, written):
    # `bushing:` and `bushing: null` were taken as rigid without a word
    data = copy.deepcopy(BUSHED)
    data['constraints'][0]['bushing'] = None
    path = tmp_path / 'empty.yaml'
    path.write_text(yaml.safe_dump(data).replace('bushing: null', written))
    assert written in path.read_text()
    assert main([str(path), '--travel', '0']) == 2
    assert capsys.readouterr().err == (
        f'linkage-sweep: {path}: constraints[0] (upper_arm).bushing: empty (null): give '
        '{axial, radial} (an arm also torsion, conical, at), or leave the key out for a rigid '
        'joint\n')


def test_a_rigid_joint_leaves_the_key_out():
    data = copy.deepcopy(BUSHED)
    del data['constraints'][0]['bushing']
    assert parse_scene(data, 'scene.yaml').constraints[0].bushing is None


def test_a_travel_of_1e308_m_is_said_as_sent_and_as_outside_the_range_of_a_length():
    # 1e308 m is finite; in mm, the core's unit, it is beyond the float range. The node's line
    # starts with the value as sent (its unit included); the core's part said "inf mm is not
    # a finite number".
    responder = Responder(load_scene('five_link'), method='fast', max_step_mm=5.0,
                          condition_warn=1e4, frame_id='base_link', status_name='s',
                          period_ns=10**9)
    reply = responder.answer(1e308 * 1000.0, None, (0, 0), '/wheel_travel 1e+308 m')
    assert reply.solution.status == Status.NOT_FINITE and reply.outputs == []
    assert responder.health.message == (
        '/wheel_travel 1e+308 m: travel outside -1e+09 to 1e+09 m (-1e+12 to 1e+12 mm), the '
        'range of a length: not a finite number of mm')
    assert 'inf' not in responder.health.message


def test_a_nan_travel_is_still_said_as_not_a_finite_number():
    solution = Continuation(load_scene('five_link')).solve(float('nan'))
    assert solution.message == 'travel nan mm is not a finite number'


def test_a_walk_too_long_says_its_substeps_in_a_few_digits_not_300():
    solution = Continuation(load_scene('five_link')).solve(1e300)
    assert solution.status == Status.SUBSTEP_LIMIT
    assert 'needs 2e+299 substeps of max_step 5 mm' in solution.message
    assert len(solution.message) < 200
