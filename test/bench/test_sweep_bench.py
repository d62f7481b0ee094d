# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-bench sweep: linkage-sweep's request timed by bench, its table and its refusals."""

from pathlib import Path

from linkage_ros.bench.sweep import main

SINGULAR = Path(__file__).resolve().parents[1] / 'data' / 'five_link_singular.yaml'


def test_the_table_names_the_positions_and_times_each_way_of_solving(capsys):
    assert main(['five_link', '--travel', '0:10:10'], 1) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith('five_link: 2 positions from 0 to 10 mm, largest residual ')
    assert lines[1].split() == ['method', 'median_us_per_position', 'p95_us', 'ratio_to_fast']
    assert [line[:30].strip() for line in lines[2:]] == [
        'paper sweep', 'fast sweep', 'fast, one command at a time']
    assert lines[3].split()[-1] == '1.0'   # the fast sweep against itself


def test_a_benchmark_of_a_scene_out_of_reach_times_nothing_and_says_why(capsys):
    # five_link_singular solves nothing but travel 0: the benchmark once ended in a traceback
    # (the largest residual of an empty table).
    assert main([str(SINGULAR), '--travel', '-2:2:1'], 1) == 1
    out, err = capsys.readouterr()
    assert out == '' and err.splitlines()[-1].startswith(
        'linkage-sweep: nothing to time: travel -2 mm is out of reach: the guidance equations '
        'are singular')


def test_a_request_linkage_sweep_refuses_is_refused_in_its_words_before_any_timing(capsys):
    assert main(['five_link', '--rack', '5'], 1) == 2
    out, err = capsys.readouterr()
    assert out == '' and err == ('linkage-sweep: five_link: no constraint is marked steer: '
                                 'rack, so a rack input moves nothing\n')
