# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench replay: a run's commands, read as linkage-replay reads them, timed by bench.

A bag's commands, their losses and its mistakes: test/tools/test_replay_inputs.py and
test_cli_manners.py.
"""

from linkage_ros.bench.replay import main


def test_a_sweep_s_commands_are_timed_in_each_recording_mode(capsys):
    assert main(['--travel', '0:3:1']) == 0
    out, err = capsys.readouterr()
    lines = out.strip().splitlines()
    assert lines[0] == 'mode,commands,us_per_command,ratio,extra_us_per_message'
    assert [line.split(',')[:2] for line in lines[1:]] == [
        ['no recording', '4'], ['McapRecorder', '4'], ['RerunRecorder', '4'], ['both', '4']]
    assert lines[1].split(',')[3] == '1.000'   # no recording against itself
    assert 'linkage-bench replay: five_link: timing 4 commands, method fast' in err
