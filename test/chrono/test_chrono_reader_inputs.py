# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The Chrono reader's input classes: files, numbers, keys, names, nesting and data paths.

The specification is Chrono's reader: RapidJSON as Chrono::Vehicle calls it (ReadFileJSON:
ParseStream<kParseCommentsFlag>; chrono_thirdparty/rapidjson reader.h ParseNumber,
document.h FindMember) and vehicle::GetDataFile for the files a vehicle names. What Chrono
refuses is refused in one line (a ChronoError, exit status 2); what it reads is read as it
reads it. Hypothesis settings are modest and write no database.
"""

import json
import math
import os
from pathlib import Path
import re
import shutil
import subprocess
import sys

from hypothesis import given, HealthCheck, settings, strategies as st
from linkage_ros.chrono.files import data_file, export_file, import_file
from linkage_ros.chrono.names import token
from linkage_ros.chrono.reader import ChronoError, MAX_DEPTH, parse_chrono
from linkage_ros.core.base import LinkageError
from linkage_ros.core.model.bundled import config_dir
import pytest
import yaml

CHRONO = config_dir() / 'chrono'
PROGRAM = Path(sys.executable).parent / 'linkage-chrono'
GOOD = CHRONO / 'generic/suspension/DoubleWishbone.json'
TOKEN = re.compile(r'^[A-Za-z][A-Za-z0-9_]*$')   # a ROS name token (rcl's rule), no '__'
FUZZ = settings(deadline=None, database=None, max_examples=200,
                suppress_health_check=[HealthCheck.too_slow])


def run(*args, timeout=120):
    return subprocess.run([str(PROGRAM), *map(str, args)], capture_output=True, text=True,
                          timeout=timeout)


def one_line(result, said):
    assert result.returncode == 2, result.stderr
    assert len(result.stderr.splitlines()) == 1 and said in result.stderr, result.stderr


# --- files ---------------------------------------------------------------------------------

@pytest.mark.parametrize('command', ['import', 'export'])
def test_a_fifo_is_refused_at_once_not_waited_on(command, tmp_path):
    fifo, out = tmp_path / 'in.json', tmp_path / 'out.yaml'
    os.mkfifo(fifo)
    args = (['import', fifo, '-o', out] if command == 'import'
            else ['export', 'double_wishbone', '-o', out, '--like', fifo])
    one_line(run(*args, timeout=60), 'not a regular file')   # before: blocked for ever
    assert not out.exists()


def test_a_folder_is_refused_in_one_line(tmp_path):
    one_line(run('import', tmp_path, '-o', tmp_path / 'out.yaml'), 'not a regular file')


# --- numbers -------------------------------------------------------------------------------

def test_an_integer_of_more_than_4300_digits_is_one_line(tmp_path):
    data = GOOD.read_text().replace('"Mass":                     14.705',
                                    '"Mass": ' + '7' * 4301, 1)
    assert '7' * 4301 in data
    source = tmp_path / 'long.json'
    source.write_text(data)
    one_line(run('import', source, '-o', tmp_path / 'out.yaml'), 'beyond the range of a double')


def _rapidjson_taken(token: str) -> int:
    """
    Return the fraction digits RapidJSON takes into its significand (reader.h ParseNumber).

    Written out digit by digit as the C++ does: a second, independent reading of the rule.
    """
    minus = token.startswith('-')
    mantissa = token.lstrip('-').lower().split('e')[0]
    whole, _, fraction = mantissa.partition('.')
    limit = 2 ** 63 if minus else 2 ** 64 - 1
    i64, significant = 0, 0
    for k, digit in enumerate(whole):
        if i64 * 10 + int(digit) > limit:
            return 0   # a double from here on; its digit count is past 17 already
        i64 = i64 * 10 + int(digit)
        significant += 1 if k else 0
    taken, d = 0, float(i64)
    rest = list(fraction)
    while rest and i64 <= 2 ** 53 - 1:
        i64 = i64 * 10 + int(rest.pop(0))
        taken += 1
        significant += 1 if i64 != 0 else 0
        d = float(i64)
    for digit in rest:
        if significant < 17:
            d = d * 10 + int(digit)
            taken += 1
            significant += 1 if d > 0 else 0
    return taken


digits = st.text('0123456789', min_size=1, max_size=400)
numbers = st.builds(
    lambda minus, whole, fraction, exponent: (
        ('-' if minus else '') + (whole.lstrip('0') or '0') + (f'.{fraction}' if fraction else '')
        + (f'e{exponent}' if exponent is not None else '')),
    st.booleans(), digits | st.text('0123456789', min_size=4290, max_size=4400),
    st.none() | digits, st.none() | st.integers(-400, 400) | st.integers(-10**6, 10**6))


@FUZZ
@given(numbers)
def test_a_number_of_any_magnitude_and_length_is_read_as_rapidjson_or_refused(token):
    try:
        value = parse_chrono(f'{{"a": {token}}}')['a']
    except ChronoError as exc:
        assert 'beyond the range of a double' in str(exc)
        exponent = int(token.lower().split('e')[1]) if 'e' in token.lower() else 0
        assert math.isinf(float(token)) or exponent > 308 + _rapidjson_taken(token)
        return
    assert float(value) == float(token)   # correctly rounded (RapidJSON: within a few ulps)
    assert math.isfinite(float(token))


@pytest.mark.parametrize('token, refused', [
    ('1e308', False), ('1e309', True), ('0e999', True), ('0.000e309', False),
    ('1.7976931348623157e308', False), ('1.8e308', True), ('-' + '9' * 400, True),
    ('1e-400', False), ('18446744073709551615', False), ('0.01e309', False),
    ('18446744073709551616', False), ('-9223372036854775809', False),
])
def test_numbers_at_rapidjsons_edges(token, refused):
    if refused:
        with pytest.raises(ChronoError, match='beyond the range of a double'):
            parse_chrono(f'{{"a": {token}}}')
    else:   # Chrono reads every number with GetDouble
        assert float(parse_chrono(f'{{"a": {token}}}')['a']) == float(token)


# --- keys ----------------------------------------------------------------------------------

def test_a_key_given_twice_takes_the_first_value_as_chrono_does(tmp_path):
    text = GOOD.read_text().replace(
        '"Location Upright":         [-0.088, 0.808, 0.243]',
        '"Location Upright":         [-0.088, 0.808, 0.243],\n'
        '    "Location Upright":         [0.5, 0.5, 0.5]', 1)
    assert '[0.5, 0.5, 0.5]' in text
    source, out = tmp_path / 'twice.json', tmp_path / 'twice.yaml'
    source.write_text(text)
    scene = yaml.safe_load(import_file(str(source), str(out))[0][str(out)])
    upper = next(c for c in scene['constraints'] if c['name'] == 'UpperControlArm')
    assert upper['carrier'] == [-0.088, 0.808, 0.243]   # before: [0.5, 0.5, 0.5]


keys = st.text(max_size=6) | st.sampled_from(['Mass', 'COM', ''])


@FUZZ
@given(st.lists(st.tuples(keys, st.integers(-5, 5)), max_size=8))
def test_of_keys_given_twice_the_first_counts_at_every_depth(pairs):
    body = ', '.join(f'{json.dumps(k)}: {v}' for k, v in pairs)
    first = {}
    for key, value in pairs:
        first.setdefault(key, value)
    data = parse_chrono(f'{{"outer": {{{body}}}, "list": [{{{body}}}]}}')
    assert data == {'outer': first, 'list': [first]}


# --- names and nesting ---------------------------------------------------------------------

names = st.text(max_size=40) | st.sampled_from(
    ['lower-arm', 'unterer_Querlenker_ü', '9arm', 'a__b', '\U0001f600', 'x\ny', 'true',
     'x' * 300, '"quoted"', 'back\\slash', '\u2028', '\x00'])


def _renamed(value, old, new):
    """Return value with every string equal to old (a body's name) replaced by new."""
    if isinstance(value, dict):
        return {k: _renamed(v, old, new) for k, v in value.items()}
    if isinstance(value, list):
        return [_renamed(v, old, new) for v in value]
    return new if value == old else value


@FUZZ
@given(name=names, body=names)
def test_any_name_in_a_file_reads_back_whole_from_the_scene(name, body, tmp_path_factory):
    from linkage_ros.chrono.reader import read_chrono
    data = read_chrono(CHRONO / 'hmmwv/suspension/HMMWV_DoubleWishboneFront_replica.json')
    data['Name'] = name
    upright = data['Spindle']['Attachment Body']
    arm = next(b['Name'] for b in data['Bodies'] if b['Name'] != upright)
    if body not in {b['Name'] for b in data['Bodies']} | {'Chassis', 'Steering', 'Subchassis'}:
        data, arm = _renamed(data, arm, body), body
    folder = tmp_path_factory.mktemp('names')
    source, out = folder / 'n.json', folder / 'n.yaml'
    source.write_text(json.dumps(data), encoding='utf-8')
    try:
        texts, _ = import_file(str(source), str(out))
    except LinkageError as exc:   # one line, never another exception
        assert '\n' not in str(exc)
        return
    scene = yaml.safe_load(texts[str(out)])
    assert scene['description'] == f'Chrono::Vehicle GenericWheeledSuspension: {name}'
    for item in scene['constraints'] + scene.get('elements', []):   # ROS name tokens
        assert TOKEN.match(item['name']) and '__' not in item['name'], item['name']
    ours = [c for c in scene['constraints'] if c.get('x_chrono_name', c['name']) == arm]
    assert [c['name'] for c in ours] == [token(arm)]   # the Chrono name kept beside its token


@pytest.mark.parametrize('chrono, ours', [
    ('lower-arm', 'lower_arm'), ('unterer_Querlenker_ü', 'unterer_Querlenker'),
    ('9arm', 'x_9arm'), ('a__b', 'a_b'), ('ü', 'x'), ('Upper Arm', 'Upper_Arm'),
    ('x' * 100, 'x' * 64)])
def test_chrono_names_become_ros_name_tokens_and_go_back_out(chrono, ours, tmp_path):
    from linkage_ros.chrono.reader import read_chrono
    replica = CHRONO / 'hmmwv/suspension/HMMWV_DoubleWishboneFront_replica.json'
    data = read_chrono(replica)
    upright = data['Spindle']['Attachment Body']
    arm = next(b['Name'] for b in data['Bodies'] if b['Name'] != upright)
    data = _renamed(data, arm, chrono)
    source, out = tmp_path / 'n.json', tmp_path / 'n.yaml'
    source.write_text(json.dumps(data))
    texts, _ = import_file(str(source), str(out))
    out.write_text(texts[str(out)])
    scene = yaml.safe_load(texts[str(out)])
    item = next(c for c in scene['constraints'] if c.get('x_chrono_name') == chrono)
    assert item['name'] == ours
    again = json.loads(export_file(str(out), str(source))[0])
    assert again == data   # --like finds every body by its Chrono name: the file comes back


@pytest.mark.parametrize('depth', [MAX_DEPTH, MAX_DEPTH + 1, 10000, 10 ** 6])
def test_nesting_deeper_than_the_limit_is_one_line(depth):
    text = '{"a": ' + '[' * (depth - 1) + ']' * (depth - 1) + '}'
    if depth <= MAX_DEPTH:
        assert parse_chrono(text)['a'] is not None
    else:
        with pytest.raises(ChronoError, match='nested deeper'):
            parse_chrono(text)


def test_a_lone_surrogate_is_refused_as_rapidjson_does():
    with pytest.raises(ChronoError, match='lone UTF-16 surrogate'):
        parse_chrono('{"Name": "\\ud800"}')


# --- the files a vehicle names -------------------------------------------------------------

def _vehicle(tmp_path, name):
    """Copy the bundled HMMWV into a Chrono data layout whose front axle reads name."""
    data = tmp_path / 'data' / 'vehicle'
    shutil.copytree(CHRONO / 'hmmwv', data / 'hmmwv')
    path = data / 'hmmwv' / 'vehicle' / 'HMMWV_Vehicle.json'
    vehicle = json.loads(path.read_text())
    vehicle['Axles'][0]['Suspension Input File'] = name
    path.write_text(json.dumps(vehicle))
    outside = tmp_path / 'outside.json'   # a good suspension file, outside the data folder
    shutil.copy(CHRONO / 'hmmwv/suspension/HMMWV_DoubleWishboneFront.json', outside)
    return path, outside


@pytest.mark.parametrize('name', ['../../../../outside.json', 'hmmwv/../../../outside.json',
                                  '{outside}', '/proc/self/environ', '../../../../etc/passwd'])
def test_a_suspension_file_outside_chronos_data_folder_is_refused(name, tmp_path):
    path, outside = _vehicle(tmp_path, '')
    name = name.replace('{outside}', str(outside))
    vehicle = json.loads(path.read_text())
    vehicle['Axles'][0]['Suspension Input File'] = name
    path.write_text(json.dumps(vehicle))
    out = tmp_path / 'car.yaml'
    result = run('import', path, '-o', out)
    one_line(result, '"Suspension Input File"')   # before: the outside file was imported
    assert not out.exists() and not (tmp_path / 'car_front.yaml').exists()


def test_a_symbolic_link_out_of_the_data_folder_is_refused(tmp_path):
    path, outside = _vehicle(tmp_path, 'hmmwv/suspension/Linked.json')
    (path.parents[1] / 'suspension' / 'Linked.json').symlink_to(outside)
    one_line(run('import', path, '-o', tmp_path / 'car.yaml'), 'leads out of')


def test_a_name_inside_the_data_folder_still_reads(tmp_path):
    path, _ = _vehicle(tmp_path, 'hmmwv/vehicle/../suspension/HMMWV_DoubleWishboneFront.json')
    result = run('import', path, '-o', tmp_path / 'car.yaml')
    assert result.returncode == 0, result.stderr


paths = st.lists(st.sampled_from(['..', '.', 'hmmwv', 'suspension', '', 'x' * 300, '\x00',
                                  'HMMWV_DoubleWishboneFront.json', 'ü', '/']),
                 max_size=6).map('/'.join)


@FUZZ
@given(paths)
def test_any_data_file_name_resolves_inside_the_data_folder_or_is_refused(name):
    vehicle = CHRONO / 'hmmwv' / 'vehicle' / 'HMMWV_Vehicle.json'
    try:
        found = data_file(str(vehicle), name)
    except ChronoError as exc:
        assert '\n' not in str(exc)
        return
    folders = list(vehicle.resolve().parents[:4])
    assert any(found.resolve().is_relative_to(f) for f in folders)
    assert found.is_file()


# --- export --like -------------------------------------------------------------------------

@pytest.mark.parametrize('like, said', [
    ('{"Name": "x"}', '"Type": missing'),
    ('{"Name": "x", "Type": "Vehicle", "Template": "WheeledVehicle"}', 'not a suspension'),
    ('vehicle', 'not a suspension'),
    ('solid', 'not a suspension'),
    ('no_upright_mass', '"Upright" / "Mass": missing'),
    ('no_spring_force', '"Spring" / no "Spring Coefficient"'),
])
def test_like_a_file_that_is_no_chrono_suspension_is_refused(like, said, tmp_path):
    source = tmp_path / 'like.json'
    good = json.loads(GOOD.read_text())
    if like == 'vehicle':
        shutil.copy(CHRONO / 'hmmwv/vehicle/HMMWV_Vehicle.json', source)
    elif like == 'solid':
        shutil.copy(CHRONO / 'generic/suspension/SolidAxle.json', source)
    elif like == 'no_upright_mass':
        good['Upright'].pop('Mass')
        source.write_text(json.dumps(good))
    elif like == 'no_spring_force':
        good['Spring'].pop('Spring Coefficient')
        source.write_text(json.dumps(good))
    else:
        source.write_text(like)
    out = tmp_path / 'out.json'
    one_line(run('export', 'chrono_generic_doublewishbone', '-o', out, '--like', source), said)
    assert not out.exists()   # before: written, status 0


@pytest.mark.parametrize('name', sorted(p.name for p in CHRONO.glob('*/suspension/*.json')))
def test_every_bundled_suspension_chrono_reads_passes_as_an_original(name, tmp_path):
    from linkage_ros.chrono.needs import check_chrono, NEEDS
    from linkage_ros.chrono.reader import read_chrono
    source = next(CHRONO.glob(f'*/suspension/{name}'))
    data = read_chrono(source)
    if data['Template'] in NEEDS:
        check_chrono(data, str(source))   # Chrono's own files: nothing missing
    else:
        with pytest.raises(ChronoError, match='not a suspension of the templates'):
            check_chrono(data, str(source))


def test_every_export_of_a_bundled_scene_is_a_file_chrono_reads():
    from linkage_ros.chrono.needs import check_chrono
    from linkage_ros.core.model.bundled import bundled_scenes
    for name in sorted(bundled_scenes()):
        check_chrono(json.loads(export_file(name)[0]), name)


@FUZZ
@given(st.floats(allow_nan=False, allow_infinity=False)
       | st.sampled_from([1e20, -1e308, 5e-324, 1e16, 1.7976931348623157e308, -0.0]))
def test_every_finite_number_the_import_writes_reads_back_the_same(value):
    from linkage_ros.chrono.writer import scene_text
    text = scene_text({'name': 'x', 'wheel_radius': value, 'carrier': {'wheel_center': [value]}},
                      [])
    back = yaml.safe_load(text)   # before: 1e+20 came back as the string '1e+20'
    assert back['wheel_radius'] == value and isinstance(back['wheel_radius'], float)
    assert back['carrier']['wheel_center'] == [value]
    assert math.copysign(1.0, back['wheel_radius']) == math.copysign(1.0, value)


json_values = st.recursive(
    st.none() | st.booleans() | st.integers(-2 ** 63, 2 ** 64 - 1) | st.just(2 ** 64 - 1)
    | st.floats(allow_nan=False, allow_infinity=False) | st.text(max_size=8),
    lambda inner: (st.lists(inner, max_size=3)
                   | st.dictionaries(st.text(max_size=4), inner, max_size=3)),
    max_leaves=60)


def _depth(value) -> int:
    if isinstance(value, dict):
        return 1 + max((_depth(v) for v in value.values()), default=0)
    if isinstance(value, list):
        return 1 + max((_depth(v) for v in value), default=0)
    return 0


@FUZZ
@given(json_values, st.integers(0, 40))
def test_any_nesting_reads_back_the_same_or_is_refused_past_the_limit(value, wrap):
    for _ in range(wrap):
        value = [value]
    text = '{"a": ' + json.dumps(value) + '} // a comment\n'
    depth = 1 + _depth(value)
    try:
        data = parse_chrono(text)
    except ChronoError as exc:
        assert depth > MAX_DEPTH and 'nested deeper' in str(exc)
        return
    assert depth <= MAX_DEPTH and data == {'a': value}
