# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-bench map: the cost of the elements' quantities per answer, against without."""

from pathlib import Path

from linkage_ros.bench.map import main
import pytest


def test_benchmark_prints_with_and_without_elements_at_three_sizes(capsys):
    assert main(['five_link'], 1) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith('five_link: 2 elements (damper, spring)')
    rows = [line.replace('one command', 'one_command').split() for line in lines[2:]]
    assert [(r[0].replace('_', ' '), r[1], r[2]) for r in rows] == [
        ('one command', '1x', '161'), ('one command', '10x', '1610'),
        ('one command', '100x', '16100'), ('sweep', '1x', '161'), ('sweep', '10x', '1610'),
        ('sweep', '100x', '16100')]
    for row in rows:   # without + elements = with, and the ratio of with to without
        without, extra, total, ratio = map(float, row[3:])
        assert total == pytest.approx(without + extra, abs=0.02)
        # The table prints 2 decimals, so each time is off by up to 0.005 and the ratio of the
        # printed times by up to that much relative to each: the bound holds however busy the
        # machine (a slow `without` makes the ratio large and its rounding error with it).
        rounding = (total / without) * (0.005 / without + 0.005 / total) + 0.005
        assert ratio == pytest.approx(total / without, abs=rounding + 1e-9)


def test_a_benchmark_of_a_scene_out_of_reach_times_nothing_and_says_why(capsys):
    # It once ended in a numba TypingError: the elements of an answer that has no pose.
    singular = Path(__file__).resolve().parents[1] / 'data' / 'five_link_singular.yaml'
    assert main([str(singular)], 1) == 1
    out, err = capsys.readouterr()
    assert out == '' and err.splitlines()[-1].startswith(
        'linkage-map: nothing to time: five_link_singular: travel -80 mm is out of reach')


def test_no_output_folder_is_needed_to_time_the_maps(capsys, tmp_path, monkeypatch):
    # linkage-map requires -o; its timing writes nothing, so bench asks for none
    monkeypatch.chdir(tmp_path)
    assert main(['double_wishbone', '--travel', '5'], 1) == 0
    assert list(tmp_path.iterdir()) == []
