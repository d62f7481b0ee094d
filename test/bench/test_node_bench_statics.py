# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench node's callback section with statics: a contact wrench and a travel a command.

The statics modes run only when --modes names them; every command of theirs is answered (a
command not answered would be timed as a cheap refusal), and the table compares them with
the plain callback of the same run.
"""

from linkage_ros.bench.node_bench import main
from linkage_ros.core.base import LinkageError
import pytest


def table(text):
    """Return {mode: row cells} of the callback table printed on stdout."""
    lines = [line.split(',') for line in text.splitlines() if line]
    assert lines[0][:2] == ['callback', 'commands']
    return {cells[0]: cells for cells in lines[1:]}


def test_the_statics_mode_times_every_command_beside_plain(capsys):
    assert main(['--only', 'callback', '--quick', '--modes', 'statics']) == 0
    out, err = capsys.readouterr()
    rows = table(out)
    assert list(rows) == ['plain', 'statics']
    assert rows['statics'][1] == '200'
    assert 'not answered' not in err
    assert float(rows['statics'][4]) > 1.0     # the ratio to plain: the loaded solve costs


def test_without_modes_the_callback_section_leaves_statics_out(capsys):
    assert main(['--only', 'callback', '--quick']) == 0
    rows = table(capsys.readouterr()[0])
    assert 'plain' in rows and not {'statics', 'bushings'} & set(rows)


def test_an_unknown_mode_is_named():
    with pytest.raises(LinkageError, match="unknown mode 'statix'"):
        main(['--only', 'callback', '--quick', '--modes', 'statix'])


def test_the_step_section_times_every_bushed_step_in_three_configurations(capsys):
    # one bushed vehicle step in process: lean, the node's defaults, every output on; every
    # step answered (a refused one would be timed as a cheap refusal)
    assert main(['--only', 'step', '--quick']) == 0
    lines = [line.split(',') for line in capsys.readouterr()[0].splitlines() if line]
    assert lines[0] == ['step', 'steps', 'median_us', 'mean_us', 'ratio_to_lean', 'failures',
                        'load_average']
    rows = {cells[0]: cells for cells in lines[1:]}
    assert list(rows) == ['node_lean', 'node_defaults', 'node_all']
    assert {row[1] for row in rows.values()} == {'200'}
    assert {row[5] for row in rows.values()} == {'0'}
    # more outputs cost more: the defaults add TF and a WrenchStamped per pickup to lean
    assert float(rows['node_all'][4]) > 1.0
