# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The one bound on a wheel's wrench (core.base.limits, issue 36 item 1).

Each force component at most FORCE_LIMIT_N, each moment component at most MOMENT_LIMIT_NM,
finite: what the node's contact_wrench, its solve service, linkage-kc and linkage-replay read.
A wrench is refused exactly when one component is beyond its bound or not finite, in one line
naming that component and the bound; over every magnitude a float holds, on every axis and
sign (hypothesis).
"""

import math
from pathlib import Path

from hypothesis import example, given, settings, strategies as st
from linkage_ros.answer.protocol import wrench_problem as node_problem
from linkage_ros.core.base import FORCE_LIMIT_N, MOMENT_LIMIT_NM, wrench_problem

MAGNITUDES = (st.floats(min_value=0.0, max_value=1.7e308) | st.floats(0.0, 2e7)
              | st.sampled_from([0.0, 5e-324, 2.2e-308, 1e6, 1e7, 1e7 + 2.0, 1.0000001e6,
                                 1e150, 1e307, 1.7e308, math.inf, math.nan]))
ROOT = Path(__file__).resolve().parents[2]
AXES = ['force.x', 'force.y', 'force.z', 'moment.x', 'moment.y', 'moment.z']


def wrench_with(axis, value, rest=0.0):
    """Return (force, moment) with value on axis and rest on every other component."""
    values = [rest] * 6
    values[AXES.index(axis)] = value
    return tuple(values[:3]), tuple(values[3:])


@settings(deadline=None, database=None, max_examples=400)
@given(axis=st.sampled_from(AXES), magnitude=MAGNITUDES, sign=st.sampled_from([1.0, -1.0]))
@example(axis='force.y', magnitude=1.7e308, sign=1.0)     # the value
@example(axis='moment.z', magnitude=1e308, sign=-1.0)
def test_a_component_is_refused_exactly_beyond_its_bound_naming_it(axis, magnitude, sign):
    value = sign * magnitude
    limit = FORCE_LIMIT_N if axis.startswith('force') else MOMENT_LIMIT_NM
    problem = wrench_problem(*wrench_with(axis, value))
    if math.isfinite(value) and abs(value) <= limit:
        assert problem == ''
    else:
        assert problem.startswith(f'{axis} ') and '\n' not in problem
        assert f'{limit:g}' in problem if math.isfinite(value) else 'not finite' in problem


@settings(deadline=None, database=None, max_examples=200)
@given(force=st.tuples(*[st.floats(-FORCE_LIMIT_N, FORCE_LIMIT_N)] * 3),
       moment=st.tuples(*[st.floats(-MOMENT_LIMIT_NM, MOMENT_LIMIT_NM)] * 3))
def test_every_wrench_within_the_bounds_is_taken(force, moment):
    assert wrench_problem(force, moment) == ''
    assert node_problem('base_link', force, moment, 'base_link') == ''


@settings(deadline=None, database=None, max_examples=200)
@given(axis=st.sampled_from(AXES), magnitude=st.floats(1e7 + 2.0, 1.7e308))
def test_the_node_refuses_a_wrench_beyond_the_bound_in_one_line_keeping_the_last(
        axis, magnitude):
    force, moment = wrench_with(axis, magnitude)
    said = node_problem('base_link', force, moment, 'base_link')
    assert f'{axis} ' in said and 'beyond the bound' in said
    assert said.endswith('(the last good wrench is kept)') and '\n' not in said


def test_the_bounds_the_documents_state_are_the_code_s():
    # doc/node.md (contact_wrench, the solve service) and doc/kc.md (--load, --moment)
    force, moment = (f'{v:.0e}'.replace('e+0', 'e') for v in (FORCE_LIMIT_N, MOMENT_LIMIT_NM))
    for doc in ('node.md', 'kc.md'):
        text = (ROOT / 'doc' / doc).read_text()
        assert f'{force} N' in text and f'{moment} N m' in text, doc
