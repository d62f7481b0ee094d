# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Every console script of the package meets a newcomer the same way.

--help: what it does, an example and the exit statuses, on stdout, status 0, without
starting anything. An unknown option: one line on stderr, naming the program and the
option, status 2, never a traceback. The list of scripts is read from the installed
package's entry points, so a new script is covered as soon as it is declared in setup.py.
"""

from importlib.metadata import distribution
import os
from pathlib import Path
import subprocess
import sys

import pytest

SCRIPTS = sorted(e.name for e in distribution('linkage_ros').entry_points
                 if e.group == 'console_scripts')
# Positional arguments a script requires, so that the unknown option is the only mistake.
REQUIRED = {'linkage-sweep': ['five_link'], 'linkage-plot': ['camber-toe', '-o', 'out.png'],
            'linkage-rerun': ['run.mcap'], 'linkage-replay': ['solve', 'run.mcap'],
            'linkage-map': ['five_link']}


# What each program writes to stdout when no file is named: a table, a URDF, a layout.
TABLES = {'linkage-sweep': ['five_link'], 'linkage-axle': [],
          'linkage-vehicle': ['demo_vehicle'],
          'linkage-kc': ['double_wishbone_bushings', '--travel', '0'],
          'linkage-study': ['sensitivity', 'five_link', '--travel', '0'],
          'linkage-bench': ['replay', str(Path(__file__).resolve().parents[2] / 'bags'
                                          / 'five_link_sweep.mcap')],
          'linkage-urdf': ['five_link', '-o', '-'], 'linkage-foxglove': ['five_link', '-o', '-']}
# Programs with subcommands: each subcommand's --help too.
SUBCOMMANDS = {'linkage-bench': ['accuracy', 'node', 'soak', 'sweep', 'axle', 'map', 'vehicle',
                                 'study', 'replay', 'kc', 'chrono'],
               'linkage-replay': ['solve', 'sweep', 'copy', 'publish'],
               'linkage-study': ['sensitivity', 'tolerance', 'fit'],
               'linkage-chrono': ['import', 'export']}


def run(name, *args, cwd=None):
    """Run an installed console script to its end; return (status, stdout, stderr)."""
    done = subprocess.run([str(Path(sys.executable).parent / name), *args],
                          capture_output=True, text=True, timeout=120, cwd=cwd)
    return done.returncode, done.stdout, done.stderr


def test_every_documented_program_is_a_console_script():
    assert {'suspension_node', 'linkage-sweep', 'linkage-replay', 'linkage-rerun',
            'linkage-plot', 'linkage-bench', 'linkage-kc'} <= set(SCRIPTS)


@pytest.mark.parametrize('name', SCRIPTS)
def test_help_says_what_it_does_an_example_and_the_exit_statuses(name):
    status, out, err = run(name, '--help')
    assert status == 0 and err == '', err
    assert out.startswith(f'usage: {name} '), out[:200]   # its own name, no other's
    assert 'example' in out.lower(), out
    assert 'exit status' in out and 'mistake' in out


@pytest.mark.parametrize('name', SCRIPTS)
def test_an_unknown_option_is_one_line_naming_it_with_status_2(name, tmp_path):
    status, out, err = run(name, *REQUIRED.get(name, []), '--no-such-option', cwd=tmp_path)
    assert status == 2 and out == '', (out, err)
    assert list(tmp_path.iterdir()) == []
    assert err.count('\n') == 1 and err.startswith(f'{name}: '), err
    assert '--no-such-option' in err and 'Traceback' not in err


@pytest.mark.parametrize('name, args, says', [
    ('node', ['--plot', '/no/such/folder/x.png'],
     '--plot: cannot write /no/such/folder/x.png: no folder /no/such/folder'),
    ('node', ['--scene', 'nowhere'], 'nowhere: scene: no such file'),
    ('node', ['--only', 'core,speed'], "--only: unknown section 'speed'"),
    # it wrote nothing and said nothing: the plot is of the latency section
    ('node', ['--plot', 'x.png', '--only', 'core,sweep'],
     '--plot draws the latency section: add latency to --only'),
    ('accuracy', ['-o', 'setup.py'], '-o: setup.py is a file, not a folder'),
    ('accuracy', ['--scenes', 'nowhere'], 'nowhere: scene: no such file'),
    ('accuracy', ['--entries', 'magic'], "--entries: unknown ['magic']"),
    ('soak', ['--scene', 'nowhere'], 'nowhere: scene: no such file'),
    ('soak', ['--commands', '10'], '--commands must exceed --warmup'),
])
def test_a_benchmark_given_a_mistake_says_it_in_one_line_before_it_runs(
        name, args, says, tmp_path):
    (tmp_path / 'setup.py').write_text('')
    status, out, err = run('linkage-bench', name, *args, cwd=tmp_path)
    assert status == 2 and out == '', (out, err)
    assert err.count('\n') == 1 and err.startswith(f'linkage-bench {name}: ') and says in err, \
        err
    assert sorted(p.name for p in tmp_path.iterdir()) == ['setup.py']


def into_a_closed_pipe(name, *args, cwd):
    """
    Run a console script with stdout a pipe whose reader is gone before it starts.

    The environment is a fresh shell's (env -i, with PATH and HOME only): no
    PYTHONUNBUFFERED, so that stdout to a pipe is block-buffered and a short output meets the
    gone reader only at the flush. Returns (status, stderr).
    """
    read, write = os.pipe()
    os.close(read)
    fresh = {'PATH': os.defpath, 'HOME': os.environ.get('HOME', '/'),
             'ROS_AUTOMATIC_DISCOVERY_RANGE': 'LOCALHOST'}
    try:
        done = subprocess.run([str(Path(sys.executable).parent / name), *args], stdout=write,
                              stderr=subprocess.PIPE, text=True, env=fresh, cwd=cwd,
                              timeout=300)
    finally:
        os.close(write)
    return done.returncode, done.stderr


HELPS = [(name, ['--help']) for name in SCRIPTS] + [
    (name, [command, '--help']) for name, commands in SUBCOMMANDS.items() for command in commands]


@pytest.mark.parametrize('name, args', HELPS, ids=[' '.join([n, *a]) for n, a in HELPS])
def test_help_into_a_closed_pipe_ends_quietly_as_cat_does(name, args, tmp_path):
    # Status 120 and "Exception ignored ... BrokenPipeError" in a fresh shell (issue 36)
    assert into_a_closed_pipe(name, *args, cwd=tmp_path) == (128 + 13, '')   # SIGPIPE, as cat


@pytest.mark.parametrize('name', sorted(TABLES))
def test_a_table_into_a_closed_pipe_ends_quietly_as_cat_does(name, tmp_path):
    status, err = into_a_closed_pipe(name, *TABLES[name], cwd=tmp_path)
    assert status == 128 + 13 and 'Error' not in err and 'Traceback' not in err, err
    assert list(tmp_path.iterdir()) == []      # nothing written in place of stdout
