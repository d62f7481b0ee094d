# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-chrono as a program: examples that run, arguments described, outputs never inputs.

Its --help examples and doc/chrono.md's commands run as written from a checkout's root; its
help describes every argument with its range and default (issue 36 item 17).
"""

import json
import os
from pathlib import Path
import re
import shlex
import subprocess
import sys

import pytest

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(sys.executable).parent
PROGRAM = BIN / 'linkage-chrono'


def help_of(*command):
    run = subprocess.run([str(PROGRAM), *command, '--help'], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return run.stdout


def checkout(tmp_path):
    """Return a folder that looks like a checkout's root to a command: config and .venv."""
    (tmp_path / 'config').symlink_to(ROOT / 'config')
    (tmp_path / '.venv').mkdir()
    (tmp_path / '.venv' / 'bin').symlink_to(BIN)
    return tmp_path


def test_every_example_of_the_help_runs_as_written(tmp_path):
    text = help_of()
    examples = [line.strip() for line in text.splitlines()
                if line.startswith('  linkage-chrono ')]
    assert len(examples) >= 4 and help_of('import').count('linkage-chrono import') >= 2
    folder = checkout(tmp_path)
    env = {**os.environ, 'PATH': f'{BIN}{os.pathsep}{os.environ.get("PATH", "")}'}
    for example in examples:
        run = subprocess.run(shlex.split(example), cwd=folder, env=env, capture_output=True,
                             text=True)
        assert run.returncode == 0, (example, run.stderr)   # before: no such file
    assert (folder / 'hmmwv_front.yaml').is_file() and (folder / 'dw.json').is_file()


def test_doc_chrono_commands_run_as_written_from_a_checkout(tmp_path):
    doc = (ROOT / 'doc' / 'chrono.md').read_text()
    block = re.search(r'```bash\n(.*?)```', doc, re.S).group(1)
    commands = block.strip().splitlines()
    assert commands and all(c.startswith('.venv/bin/') for c in commands)
    folder = checkout(tmp_path)
    for command in commands:
        run = subprocess.run(['bash', '-c', command], cwd=folder, capture_output=True,
                             text=True)
        assert run.returncode == 0, (command, run.stderr)
    assert (folder / 'dw.csv').read_text().startswith('travel_mm')


@pytest.mark.parametrize('command, described', [
    ('import', {'CHRONO.json': ['at most 10 MB'], '--output FILE.yaml': ['Required'],
                '--wheel-radius M': ['in (0, 1e+09]', 'default 0.33']}),
    ('export', {'SCENE': ['bundled scene name'], '--output FILE.json': ['Required'],
                '--like ORIGINAL.json': ['default: the bundled']}),
])
def test_each_subcommand_help_describes_every_argument(command, described):
    text = ' '.join(help_of(command).split())   # the help's own line breaks do not count
    for argument, words in described.items():
        assert re.search(re.escape(argument) + r' +[A-Za-z(]', text), argument   # described
        for word in words:
            assert word in text, (argument, word)


@pytest.mark.parametrize('value', ['0', '-1', 'nan', 'inf', '1e308', '2e9', 'abc'])
def test_a_wheel_radius_out_of_its_range_is_one_line(value, tmp_path):
    out = tmp_path / 'w.yaml'
    run = subprocess.run([str(PROGRAM), 'import',
                          str(ROOT / 'config/chrono/generic/suspension/DoubleWishbone.json'),
                          '-o', str(out), '--wheel-radius', value],
                         capture_output=True, text=True)
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
    assert '--wheel-radius' in run.stderr and not out.exists()


def test_a_vehicle_import_never_writes_over_a_suspension_file_it_reads(tmp_path):
    import shutil
    shutil.copytree(ROOT / 'config/chrono/hmmwv', tmp_path / 'hmmwv')
    front = tmp_path / 'hmmwv/suspension/HMMWV_DoubleWishboneFront.json'
    before = front.read_bytes()
    vehicle = tmp_path / 'hmmwv/vehicle/HMMWV_Vehicle.json'
    run = subprocess.run([str(PROGRAM), 'import', str(vehicle), '-o', str(front)],
                         capture_output=True, text=True)
    assert run.returncode == 2 and 'is the input' in run.stderr, run.stderr
    assert front.read_bytes() == before


def test_export_to_dash_writes_the_json_on_stdout_and_no_file_named_dash(tmp_path):
    # '-' is stdout, as for linkage-urdf and linkage-foxglove: the text equals the file export
    run = subprocess.run([str(PROGRAM), 'export', 'double_wishbone', '-o', '-'],
                         capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert not (tmp_path / '-').exists()
    subprocess.run([str(PROGRAM), 'export', 'double_wishbone', '-o', str(tmp_path / 'f.json')],
                   check=True, capture_output=True)
    assert json.loads(run.stdout) == json.loads((tmp_path / 'f.json').read_text())


def test_import_to_dash_is_one_line_and_writes_nothing(tmp_path):
    run = subprocess.run([str(PROGRAM), 'import',
                          str(ROOT / 'config/chrono/generic/suspension/DoubleWishbone.json'),
                          '-o', '-'], capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
    assert '-o -' in run.stderr and not list(tmp_path.iterdir())
