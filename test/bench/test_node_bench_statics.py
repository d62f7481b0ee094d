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
