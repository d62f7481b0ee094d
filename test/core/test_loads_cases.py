# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Load case files (core/loads/cases.py): every number within its stated range, or one line.

A value is read as given when it is a finite number within the range doc/loads.md states,
and refused otherwise with one SceneError naming the file and the field; names likewise.
"""

import math
from pathlib import Path
import re

from hypothesis import example, given, HealthCheck, settings, strategies as st
from linkage_ros.core.base import LinkageError
from linkage_ros.core.loads import built_in_cases, LoadCase, Loads, RANGES, read_cases
from linkage_ros.core.model import load_vehicle, SceneError
import pytest
import yaml

SETTINGS = settings(deadline=None, database=None, max_examples=120,
                    suppress_health_check=[HealthCheck.too_slow,
                                           HealthCheck.function_scoped_fixture])
# magnitudes: the largest float, tiny, negative, zero, subnormal, and the ranges' edges
MAGNITUDES = (st.floats(allow_nan=True, allow_infinity=True)
              | st.sampled_from([1.7e308, -1.7e308, 5e-324, -5e-324, 0.0, -0.0, 1e-300,
                                 5.0, -5.0, 10.0, 20.0, 1e6, -1e6, 1e5, 1e300])
              | st.integers(-10**400, 10**400))
FIELDS = {'longitudinal_g': 'longitudinal_g', 'lateral_g': 'lateral_g',
          'vertical_g': 'vertical_g'}


def write(tmp_path, data):
    """Write a cases file and return its path."""
    path = tmp_path / 'cases.yaml'
    path.write_text(yaml.safe_dump(data, allow_unicode=True))
    return path


def inside(value, bounds):
    """Tell whether value is a finite number within the inclusive bounds."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return False
    # an int beyond the float range compares exactly with the bounds
    return (isinstance(value, int) or math.isfinite(value)) and bounds[0] <= value <= bounds[1]


def one_line(exc, path, field):
    """Assert a SceneError is one line naming the file and the field."""
    text = str(exc)
    assert '\n' not in text and text.startswith(f'{path}: {field}'), text


@SETTINGS
@given(key=st.sampled_from(sorted(FIELDS)), value=MAGNITUDES)
@example(key='vertical_g', value=0.0)
@example(key='vertical_g', value=5e-324)
@example(key='lateral_g', value=5.000000000000001)
def test_a_case_acceleration_is_read_within_its_range_or_refused_naming_it(
        tmp_path, key, value):
    path = write(tmp_path, {'cases': {'c1': {key: value}}})
    ok = inside(value, RANGES[key]) and (key != 'vertical_g' or value > 0)
    try:
        case = read_cases(path)['c1']
    except SceneError as exc:
        assert not ok, exc
        one_line(exc, path, f'cases.c1.{key}')
        return
    assert ok and getattr(case, key) == float(value)


@SETTINGS
@given(key=st.sampled_from(['longitudinal_g', 'lateral_g', 'vertical_g']), value=MAGNITUDES)
def test_a_corner_multiple_is_read_within_its_range_or_refused_naming_it(tmp_path, key, value):
    path = write(tmp_path, {'cases': {'hit': {'corners': {'front_left': {key: value}}}}})
    bounds = RANGES['corner_vertical_g' if key == 'vertical_g' else 'corner_g']
    try:
        corner = read_cases(path)['hit'].corners['front_left']
    except SceneError as exc:
        assert not inside(value, bounds), exc
        one_line(exc, path, f'cases.hit.corners.front_left.{key}')
        return
    assert inside(value, bounds)
    assert corner.g[('longitudinal_g', 'lateral_g', 'vertical_g').index(key)] == float(value)


@SETTINGS
@given(key=st.sampled_from(['force_n', 'moment_nm']), index=st.integers(0, 2),
       value=MAGNITUDES)
def test_a_corner_wrench_is_read_within_its_range_or_refused_naming_it(
        tmp_path, key, index, value):
    vector = [0.0, 0.0, 0.0]
    vector[index] = value
    path = write(tmp_path, {'cases': {'kerb': {'corners': {'rear_right': {key: vector}}}}})
    try:
        corner = read_cases(path)['kerb'].corners['rear_right']
    except SceneError as exc:
        assert not inside(value, RANGES[key]), exc
        one_line(exc, path, f'cases.kerb.corners.rear_right.{key}')
        return
    assert inside(value, RANGES[key]) and getattr(corner, key)[index] == float(value)


NAMES = (st.text(min_size=0, max_size=80)
         | st.sampled_from(['static', 'bump-2', '3g_bump', 'a' * 64, 'a' * 65, 'ü', 'kerb strike',
                            '-x', '_x', 'x/y', 'x.y', 'braking\n', '']))


@SETTINGS
@given(name=NAMES)
def test_a_case_name_is_ascii_letters_digits_dash_underscore_or_refused(tmp_path, name):
    path = write(tmp_path, {'cases': {name: {'vertical_g': 1.0}}})
    ok = re.fullmatch(r'[A-Za-z0-9][A-Za-z0-9_-]{0,63}', name) is not None
    try:
        cases = read_cases(path)
    except SceneError as exc:
        assert not ok, exc
        assert '\n' not in str(exc) and str(exc).startswith(f'{path}: cases.')
        return
    assert ok and list(cases) == [name]


@SETTINGS
@given(name=NAMES)
def test_a_corner_of_a_case_names_a_vehicle_corner_or_is_refused_when_solved(tmp_path, name):
    path = write(tmp_path, {'cases': {'c': {'corners': {name: {'vertical_g': 2.0}}}}})
    try:
        case = read_cases(path)['c']
    except SceneError as exc:
        assert re.fullmatch(r'[A-Za-z0-9][A-Za-z0-9_-]{0,63}', name) is None, exc
        assert '\n' not in str(exc)
        return
    try:
        keys = LOADS.corner_keys(case)
    except LinkageError as exc:
        assert name not in ('front_left', 'front_right', 'rear_left', 'rear_right')
        assert str(exc) == (f'case c: corners.{name}: demo_vehicle_loads has no such corner '
                            '(corners: front_left, front_right, rear_left, rear_right)')
        return
    assert keys == {name: name}


LOADS = None


def setup_module():
    """Prepare the vehicle once (its setup sheet): the corner names are checked against it."""
    global LOADS
    LOADS = Loads(load_vehicle('demo_vehicle_loads'))


scalars = (st.none() | st.booleans() | st.integers(-10**400, 10**400) | st.floats()
           | st.text(max_size=8) | st.sampled_from(['cp', 'wc', 'front_left', 'static']))
values = st.recursive(scalars, lambda children: st.lists(children, max_size=4)
                      | st.dictionaries(st.text(max_size=6) | st.sampled_from(
                          ['vertical_g', 'corners', 'at', 'force_n']), children, max_size=3),
                      max_leaves=10)


@SETTINGS
@given(where=st.sampled_from(['top', 'cases', 'case', 'corners', 'corner', 'at']),
       new=values)
def test_a_cases_file_with_anything_anywhere_loads_or_is_one_line(tmp_path, where, new):
    data = {'cases': {'c': {'vertical_g': 1.0,
                            'corners': {'front_left': {'vertical_g': 3.0, 'at': 'wc'}}}}}
    if where == 'top':
        data = new
    elif where == 'cases':
        data['cases'] = new
    elif where == 'case':
        data['cases']['c'] = new
    elif where == 'corners':
        data['cases']['c']['corners'] = new
    elif where == 'corner':
        data['cases']['c']['corners']['front_left'] = new
    else:
        data['cases']['c']['corners']['front_left']['at'] = new
    path = write(tmp_path, data)
    try:
        cases = read_cases(path)
    except SceneError as exc:
        assert '\n' not in str(exc) and str(exc).startswith(str(path)), str(exc)
        return
    assert all(isinstance(c, LoadCase) for c in cases.values())


def test_the_built_in_cases_are_the_issues_seven():
    """Issue 39 item 1 and config/loads/cases.yaml: the accelerations of each (g)."""
    cases = built_in_cases()
    assert {n: c.accelerations_g for n, c in cases.items()} == {
        'static': (0.0, 0.0, 1.0), 'bump': (0.0, 0.0, 3.0), 'braking': (-1.0, 0.0, 1.0),
        'cornering': (0.0, 1.0, 1.0), 'traction': (0.5, 0.0, 1.0), 'pothole': (0.0, 0.0, 1.0),
        'combined': (-0.7, 0.7, 1.0)}
    hole = cases['pothole'].corners['front_left']
    assert hole.g == (-1.0, 0.0, 3.0) and hole.at == 'wc'
    assert all(not c.corners for n, c in cases.items() if n != 'pothole')


def test_a_file_that_is_not_a_cases_file_is_one_line(tmp_path):
    path = Path(tmp_path) / 'c.yaml'
    path.write_text('cases: [1, 2]\n')
    with pytest.raises(SceneError, match=r'c.yaml: cases: expected a mapping of case names'):
        read_cases(path)
    path.write_text('cases: {c: {vertical_g: 1, sideways_g: 1}}\n')
    with pytest.raises(SceneError, match=r'cases.c.sideways_g: unknown key'):
        read_cases(path)
