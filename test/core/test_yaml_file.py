# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Reading scene and vehicle files: one line for a file that is not plain YAML, bounded cost.

A syntax error, a refused tag or a key given twice is one line: file, line, column, problem
(PyYAML's own message is eight lines that echo the file). A file whose aliases multiply (a
"billion laughs") or that is larger than a scene can be is refused as it is read, in the
memory of a program that refuses any bad file; the memory is measured on the real programs,
run as a user runs them, with os.wait4's rusage of that one process.
"""

import os
from pathlib import Path
import subprocess
import sys

from linkage_ros.core.model import (FILE_LIMIT_BYTES, load_scene, load_vehicle, read_yaml,
                                    SceneError, VALUES_LIMIT)
import pytest

ROOT = Path(__file__).resolve().parents[2]
FIVE_LINK = (ROOT / 'config' / 'scenes' / 'five_link.yaml').read_text()
BIN = Path(sys.executable).parent

# The "billion laughs" of the issue, 9 levels of 9: 9**9 (387 million) strings once expanded.
LAUGHS = ''.join(f'{a}: &{a} [{", ".join([f"*{b}"] * 9)}]\n'
                 for b, a in zip('abcdefgh', 'bcdefghi'))
LAUGHS = 'a: &a ["lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol"]\n' + LAUGHS
# Memory of a program that refuses a malformed scene: about 130 MB (Python, numpy, numba
# imported); the laughs drove linkage-sweep to 2.9 GB and the node to 6.5 GB.
SMALL_MEMORY_MB = 400


def written(tmp_path, text, name='scene.yaml'):
    path = tmp_path / name
    path.write_text(text)
    return path


def refusal(loader, path):
    with pytest.raises(SceneError) as raised:
        loader(path)
    return str(raised.value)


# Run by a small launcher process: a child forked from pytest itself starts with pytest's
# resident memory (hundreds of MB, counted in its ru_maxrss before it execs the program).
LAUNCHER = """
import os, resource, subprocess, sys
resource.setrlimit(resource.RLIMIT_AS, (2 * 2**30, 2 * 2**30))
process = subprocess.Popen(sys.argv[1:], stdout=subprocess.DEVNULL)
_, status, usage = os.wait4(process.pid, 0)
print(os.waitstatus_to_exitcode(status), usage.ru_maxrss / 1024)
"""


def run_measured(argv, cwd):
    """
    Run a program to its end; return (status, stderr, peak memory in MB of that process).

    Its address space is capped at 2 GB, so that a program that would expand a file without
    bound fails here (with a MemoryError) instead of taking the machine's memory.
    """
    env = {**os.environ, 'ROS_AUTOMATIC_DISCOVERY_RANGE': os.environ.get(
        'ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')}   # the node starts ROS, on this machine
    result = subprocess.run([sys.executable, '-c', LAUNCHER, *argv], capture_output=True,
                            text=True, cwd=cwd, env=env, timeout=600)
    status, memory = result.stdout.split()
    return int(status), result.stderr, float(memory)


def test_a_syntax_error_is_one_line_with_file_line_column_and_problem(tmp_path):
    path = written(tmp_path, 'units: mm\nside: [left\n')
    message = refusal(load_scene, path)
    # PyYAML: "while parsing a flow sequence ... did not find expected ',' or ']'" at the
    # start of line 3 (the sequence opened on line 2), echoing both lines
    assert message == (f'{path}: line 3, column 1: not valid YAML: while parsing a flow '
                       "sequence (from line 2), did not find expected ',' or ']'")


def test_a_syntax_error_in_a_vehicle_file_is_one_line_too(tmp_path):
    path = written(tmp_path, 'corners:\n  front_left: {scene: five_link\n', 'car.yaml')
    message = refusal(load_vehicle, path)
    assert message.startswith(f'{path}: line 3, column 1: not valid YAML: ')
    assert '\n' not in message


@pytest.mark.parametrize('tag, shown', [
    ('!!python/object/apply:os.system ["true"]', '!!python/object/apply:os.system'),
    ('!!python/object:collections.OrderedDict {}', '!!python/object:collections.OrderedDict'),
    ('!!binary aGVsbG8=', '!!binary'),
    ('!mine x', '!mine')])
def test_a_tag_of_anything_but_plain_data_is_refused_by_name_and_place(tmp_path, tag, shown):
    for loader, name in ((load_scene, 'scene.yaml'), (load_vehicle, 'car.yaml')):
        path = written(tmp_path, f'name: ok\nunits: {tag}\n', name)
        assert refusal(loader, path) == (
            f'{path}: line 2, column 8: the tag {shown} is refused: these files hold plain '
            'data (mappings, lists, numbers, text, true/false, null)')


def test_a_key_given_twice_is_refused_with_both_lines(tmp_path):
    # YAML keeps the last silently: a scene would be solved with a point the user overwrote
    path = written(tmp_path, FIVE_LINK.replace('units: mm\n', 'units: mm\nunits: m\n'))
    assert refusal(load_scene, path).endswith(
        "column 1: key 'units' given twice (first on line 7)")


def test_aliases_that_share_a_point_are_read(tmp_path):
    text = 'a: &p [1, 2, 3]\nb: [*p, *p]\nc: {<<: {x: 1}, y: 2}\n'
    assert read_yaml(written(tmp_path, text)) == {'a': [1, 2, 3], 'b': [[1, 2, 3], [1, 2, 3]],
                                                  'c': {'x': 1, 'y': 2}}


def test_a_number_with_an_exponent_and_no_point_is_a_number(tmp_path):
    # YAML 1.1 (PyYAML) reads 1e-3 as text: "travel.step: expected a number, got '1e-3'"
    assert read_yaml(written(tmp_path, 'a: 1e-3\nb: -2E5\nc: 12\nd: 1.5\ne: 1e\n')) == {
        'a': 0.001, 'b': -200000.0, 'c': 12, 'd': 1.5, 'e': '1e'}


def test_a_date_stays_text_and_an_impossible_one_is_no_error(tmp_path):
    # 2001-13-45 once raised ValueError from inside PyYAML's date constructor
    assert read_yaml(written(tmp_path, 'a: 2001-13-45\nb: 2024-01-01\n')) == {
        'a': '2001-13-45', 'b': '2024-01-01'}


@pytest.mark.parametrize('text, problem', [
    ('a: &a [1, *a]\n', 'line 1, column 11: the alias *a is inside its own anchor (a '
     'recursive structure)'),
    ('a: *nowhere\n', 'line 1, column 4: the alias *nowhere names no anchor before it'),
    ('- ' * 101 + 'x\n', 'line 1, column 201: nested deeper than 100 levels')])
def test_a_recursive_or_dangling_alias_and_deep_nesting_are_refused(tmp_path, text, problem):
    path = written(tmp_path, text)
    assert refusal(load_scene, path) == f'{path}: {problem}'


def test_aliases_that_multiply_are_refused_as_they_are_read(tmp_path):
    path = written(tmp_path, LAUGHS + 'name: *i\n')
    assert len(LAUGHS) < 2000
    message = refusal(load_scene, path)
    assert message.startswith(f'{path}: line ')
    assert message.endswith(f'its aliases expand it to more than {VALUES_LIMIT:,} values (a '
                            'chain of aliases that multiply?)')


@pytest.mark.parametrize('key', ['name', 'description'])
def test_laughs_in_a_scene_cost_linkage_sweep_no_memory(tmp_path, key):
    # the reproduction: linkage-sweep on a valid five_link with the laughs in name:
    # or description: took 2.9 GB
    path = written(tmp_path, LAUGHS + FIVE_LINK.replace(f'\n{key}: ', f'\nx_{key}: ')
                   + f'{key}: *i\n')
    status, err, memory = run_measured([str(BIN / 'linkage-sweep'), str(path)], tmp_path)
    assert status == 2 and err.count('\n') == 1, err
    assert err.startswith(f'linkage-sweep: {path}: line ') and 'its aliases expand' in err
    assert memory < SMALL_MEMORY_MB, memory


def test_laughs_in_a_vehicle_file_cost_the_node_no_memory(tmp_path):
    # suspension_node with such a vehicle file reached 6.5 GB and a MemoryError; it reads
    # the file before it starts ROS, and refuses it with one line and status 2
    path = written(tmp_path, LAUGHS + 'name: *i\ncorners:\n  rear_left: {scene: five_link}\n',
                   'car.yaml')
    status, err, memory = run_measured(
        [str(BIN / 'suspension_node'), '--ros-args', '-p', f'vehicle:={path}'], tmp_path)
    assert status == 2 and 'its aliases expand' in err, err
    assert memory < SMALL_MEMORY_MB, memory


def test_a_file_larger_than_a_scene_can_be_is_refused_unread(tmp_path):
    # 2 MB of reference rows: once parsed whole (about 25 s and 600 MB for PyYAML)
    rows = ''.join(f'    - [{i}, 0.0, 0.0]\n' for i in range(120_000))
    path = written(tmp_path, FIVE_LINK + '  more_rows:\n' + rows)
    size = path.stat().st_size
    assert size > 2 * FILE_LIMIT_BYTES
    status, err, memory = run_measured([str(BIN / 'linkage-sweep'), str(path)], tmp_path)
    assert status == 2
    assert err == (f'linkage-sweep: {path}: file: {size:,} bytes, over the limit of '
                   f'{FILE_LIMIT_BYTES:,} bytes for a scene file (a scene file is a few KB)\n')
    assert memory < SMALL_MEMORY_MB, memory


def test_a_file_with_more_values_than_a_scene_holds_is_refused(tmp_path):
    path = written(tmp_path, 'rows: [' + ', '.join(['1'] * (VALUES_LIMIT + 1)) + ']\n')
    assert path.stat().st_size < FILE_LIMIT_BYTES
    assert refusal(load_scene, path).endswith(
        f'more than {VALUES_LIMIT:,} values (a scene holds a few hundred)')


def test_a_number_with_a_point_and_an_unsigned_exponent_is_a_number(tmp_path):
    # YAML 1.1 (PyYAML) reads -1.0e9 as text: a fit bound of -1.0e9 was "expected a number"
    assert read_yaml(written(tmp_path, 'a: -1.0e9\nb: .5e3\nc: 1.e2\nd: 2.5E-1\ne: 1.0e\n')) \
        == {'a': -1.0e9, 'b': 500.0, 'c': 100.0, 'd': 0.25, 'e': '1.0e'}
