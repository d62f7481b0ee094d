# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Bad Chrono files: one line naming the problem, exit status 2, nothing written."""

import json
from pathlib import Path
import subprocess
import sys

from linkage_ros.chrono.reader import ChronoError, MAX_DEPTH, parse_chrono
from linkage_ros.core.model.bundled import config_dir
import pytest

CHRONO = config_dir() / 'chrono'
PROGRAM = Path(sys.executable).parent / 'linkage-chrono'
GOOD = (CHRONO / 'generic/suspension/DoubleWishbone.json').read_text()


def spoiled(change):
    data = json.loads(GOOD)
    change(data)
    return json.dumps(data)


CASES = {
    'not_json': ('{"Template": "DoubleWishbone",,}', 'not JSON'),
    'missing_point': (spoiled(lambda d: d['Tierod'].pop('Location Chassis')),
                      '"Tierod" / "Location Chassis": missing'),
    'solid_axle': ((CHRONO / 'generic/suspension/SolidAxle.json').read_text(), 'SolidAxle'),
    'semi_trailing': ((CHRONO / 'generic/suspension/SemiTrailingArm.json').read_text(),
                      'SemiTrailingArm'),
    'nan': (GOOD.replace('"Mass":                     14.705', '"Mass": NaN'), 'NaN'),
    'string_number': (spoiled(lambda d: d['Tierod'].update({'Location Upright':
                                                            ['0.1', 0.8, 0.0]})),
                      'expected a number'),
    'deep': ('[' * (MAX_DEPTH + 5) + ']' * (MAX_DEPTH + 5), 'nested deeper'),
}


@pytest.mark.parametrize('case', sorted(CASES))
def test_bad_file_is_one_line_status_2_and_nothing_written(case, tmp_path):
    text, said = CASES[case]
    source, out = tmp_path / f'{case}.json', tmp_path / 'out.yaml'
    source.write_text(text)
    run = subprocess.run([str(PROGRAM), 'import', str(source), '-o', str(out)],
                         capture_output=True, text=True)
    assert run.returncode == 2, run.stderr
    assert len(run.stderr.splitlines()) == 1 and said in run.stderr
    assert not out.exists()


def test_file_over_the_size_limit_is_refused_unread(tmp_path):
    source, out = tmp_path / 'huge.json', tmp_path / 'out.yaml'
    with open(source, 'wb') as stream:   # 100 MB, sparse: only the size matters
        stream.truncate(100 * 1024 * 1024)
    run = subprocess.run([str(PROGRAM), 'import', str(source), '-o', str(out)],
                         capture_output=True, text=True)
    assert run.returncode == 2 and 'larger than' in run.stderr
    assert len(run.stderr.splitlines()) == 1 and not out.exists()


def test_comments_are_read_as_rapidjson_reads_them():
    data = parse_chrono('{ // a line comment\n "a": /* a block */ 1, "b": "x // y"}')
    assert data == {'a': 1, 'b': 'x // y'}


def test_unclosed_block_comment_is_not_json():
    with pytest.raises(ChronoError, match='never closed'):
        parse_chrono('{"a": 1 /* open')


def test_point_beyond_the_length_limit_is_one_line(tmp_path):
    data = json.loads(GOOD)
    data['Tierod']['Location Chassis'][0] = 1e308
    source, out = tmp_path / 'far.json', tmp_path / 'out.yaml'
    source.write_text(json.dumps(data))
    run = subprocess.run([str(PROGRAM), 'import', str(source), '-o', str(out)],
                         capture_output=True, text=True)
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
    assert '"Tierod" / "Location Chassis"' in run.stderr and not out.exists()
