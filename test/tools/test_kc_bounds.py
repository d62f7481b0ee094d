# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-kc --load and --moment beyond the stated bound of a wheel's wrench (issue 36, item 1).

Before: --load 0,1e307,0 (or --moment 0,0,1e308) was a LinAlgError traceback, status 1. Now a
component beyond core.base.FORCE_LIMIT_N (--load) or MOMENT_LIMIT_NM (--moment) is one line
naming the option, the component and the bound, status 2, nothing written; within the bound
the solve runs (a load not carried is its own line, status 1). Over every magnitude a float
holds, on every axis and sign (hypothesis, main() in process), and as a user runs it.
"""

from pathlib import Path
import subprocess
import sys

from hypothesis import assume, example, given, HealthCheck, settings, strategies as st
from linkage_ros.core.base import FORCE_LIMIT_N, MOMENT_LIMIT_NM
from linkage_ros.tools.kc import main
import pytest

KC = str(Path(sys.executable).parent / 'linkage-kc')
SCENE = 'double_wishbone_bushings'


@settings(deadline=None, database=None, max_examples=150,
          suppress_health_check=[HealthCheck.function_scoped_fixture])   # capsys: read each
@given(option=st.sampled_from(['--load', '--moment']), axis=st.sampled_from([0, 1, 2]),
       magnitude=st.floats(min_value=1.0, max_value=1.7e308) | st.sampled_from(
           [1e7 + 2.0, 1.0000001e6, 1e150, 1e307, 1.7e308]),
       sign=st.sampled_from(['', '-']))
@example(option='--load', axis=1, magnitude=1e307, sign='')
@example(option='--moment', axis=2, magnitude=1e308, sign='')
def test_a_load_or_moment_beyond_the_bound_is_one_line_and_status_2(
        option, axis, magnitude, sign, capsys, tmp_path):
    limit = FORCE_LIMIT_N if option == '--load' else MOMENT_LIMIT_NM
    assume(magnitude > limit)   # within it: solved (test_a_load_at_the_bound_is_solved...)
    values = ['0', '0', '0']
    values[axis] = f'{sign}{magnitude!r}'
    at = ['--at', 'wc'] if option == '--load' else []
    out = tmp_path / 'loaded.csv'
    with pytest.raises(SystemExit) as ended:
        main([SCENE, '--travel', '0', option, ','.join(values), *at, '-o', str(out)])
    assert ended.value.code == 2
    err = capsys.readouterr().err
    component = ('force' if option == '--load' else 'moment') + '.' + 'xyz'[axis]
    assert len(err.splitlines()) == 1, err
    assert err.startswith(f'linkage-kc: error: {option}: {component} ')
    assert f'beyond the bound of {limit:g}' in err
    assert not out.exists()


def test_a_huge_moment_as_a_user_runs_it_is_one_line_status_2_no_traceback():
    done = subprocess.run([KC, SCENE, '--travel', '0', '--moment', '0,0,1e308'],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 2
    assert done.stderr == ('linkage-kc: error: --moment: moment.z 1e+308 N m is beyond the '
                           'bound of 1e+06 N m on each component (no tyre carries that: a '
                           'unit slip, or not a load) (see linkage-kc --help)\n')
    assert done.stdout == ''


def test_a_load_at_the_bound_is_solved_or_not_carried_never_a_traceback(capsys):
    # at the bound itself: taken, and answered with a status (1: not carried, said in a line)
    status = main([SCENE, '--travel', '0', '--load', '1e7,-1e7,1e7', '--at', 'cp',
                   '--moment', '1e6,-1e6,1e6'])
    err = capsys.readouterr().err
    assert status in (0, 1)
    assert 'Traceback' not in err
    if status == 1:
        assert 'ERROR NOT_CARRIED: ' in err
