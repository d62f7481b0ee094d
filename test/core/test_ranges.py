# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The stated ranges of the numbers a scene or vehicle file holds (issue 36, items 2 and 11).

Each class of number gets a property-based test over magnitudes (1.7e308 down to the
subnormal 5e-324, zero, negative, integers of 400 digits): a value within its stated range
loads as the same number in the core's units, one outside is refused in one line that names
the file, the field, the value as given with its unit and the range. The expected verdict is
computed here from the bounds the manual states (doc/scenes.md#ranges), not by the loader's
own check.
"""

import copy
from pathlib import Path
import tempfile

from hypothesis import example, given, HealthCheck, settings, strategies as st
from linkage_ros.core.base.ranges import markdown_table, RANGE, say_ranges
from linkage_ros.core.model import load_scene, load_vehicle, parse_scene, SceneError
import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / 'test' / 'data'
FUZZ = settings(deadline=None, database=None, max_examples=120,
                suppress_health_check=[HealthCheck.too_slow])

# The bounds the manual states (doc/scenes.md#ranges), in the core's units (mm, N, kg, deg).
RATE = (1e-3, 1e11)            # N/mm: bushing axial and radial, spring, tyre
ANGULAR = (1e-3, 1e10)         # N m/deg: bushing torsion and conical, anti-roll bar
MASS = (1e-3, 1e7)             # kg
HEIGHT = (1e-6, 1e12)          # mm
FORCE = 1e9                    # N, in magnitude
LENGTH = 1e12                  # mm, in magnitude

SPECIAL = [1.7976931348623157e308, 1.7e308, 1e308, 1e300, 1e30, 1e12, 1.0000001e11, 1e11,
           1e10, 1e9, 1.0000001e7, 1e7, 1.0, 1e-3, 9.99e-4, 1e-6, 9.99e-7, 1e-300,
           2.2250738585072014e-308, 1e-310, 5e-324, 0.0]
magnitudes = (st.sampled_from(SPECIAL) | st.floats(min_value=0.0, allow_nan=False,
                                                   allow_infinity=False)
              | st.integers(0, 10**400))
numbers = st.tuples(magnitudes, st.booleans()).map(lambda t: -t[0] if t[1] else t[0])


def within(value, low, high, scale=1.0, zero=False):
    """Whether value (file units, scale: the core's units per file unit) is in [low, high]."""
    if value == 0:
        return zero
    try:
        core = float(value) * scale
    except OverflowError:      # an integer beyond the float range
        return False
    return value > 0 and low <= core <= high


def scene_data(name):
    """Return the data of a scene file (bundled name, or a file of test/data)."""
    path = DATA / f'{name}.yaml' if (DATA / f'{name}.yaml').exists() else Path(
        load_scene(name).source)
    return yaml.safe_load(path.read_text())


def assert_refused(info, source, field, value, stated):
    """Assert a SceneError that is one line naming source, field, the value and the range."""
    text = str(info.value)
    assert '\n' not in text and len(text) < 600, text
    assert text.startswith(f'{source}: {field}: '), text
    assert stated in text and 'doc/scenes.md#ranges' in text, text
    if isinstance(value, float) or abs(value) < 10**16:   # said as given
        shown = repr(value) if isinstance(value, float) else str(value)
        assert f': {shown} ' in text, text


# --- Scenes ------------------------------------------------------------------------------

BUSHED = scene_data('double_wishbone_bushings')          # mm; constraints[0] is an arm
METRE = scene_data('chrono_sedan_doublewishbone_bushings')   # m; constraints[0] is an arm


def put_bushing(data, key, value):
    """Return data with constraints[0].bushing[key] = value."""
    data = copy.deepcopy(data)
    data['constraints'][0]['bushing'][key] = value
    return data


@FUZZ
@given(value=numbers, key=st.sampled_from(['axial', 'radial']),
       units=st.sampled_from(['mm', 'm']))
@example(value=1e308, key='axial', units='mm')            # issue 36, item 2
@example(value=5e-324, key='radial', units='mm')
@example(value=1e14, key='axial', units='m')              # 1e11 N/mm: the top, in N/m
@example(value=1.0000001e14, key='axial', units='m')
def test_a_bushing_rate_loads_within_its_range_and_is_refused_outside(value, key, units):
    base, scale = (BUSHED, 1.0) if units == 'mm' else (METRE, 1e-3)   # N/m -> N/mm
    data = put_bushing(base, key, value)
    name = data['constraints'][0]['name']
    field = f'constraints[0] ({name}).bushing.{key}'
    if within(value, *RATE, scale):
        bushing = parse_scene(data, 'scene.yaml').constraints[0].bushing
        assert getattr(bushing, key) == float(value) * scale   # one operation, as the loader
        return
    with pytest.raises(SceneError) as info:
        parse_scene(data, 'scene.yaml')
    unit = 'N/mm' if units == 'mm' else 'N/m'
    assert_refused(info, 'scene.yaml', field, value, RANGE['bushing_rate'].said(
        1.0 if units == 'mm' else 1000.0))
    assert unit in str(info.value)


@FUZZ
@given(value=numbers, key=st.sampled_from(['torsion', 'conical']))
@example(value=1e305, key='torsion')                     # issue 36, item 2
@example(value=1e304, key='conical')
@example(value=0, key='conical')
def test_a_bushing_angular_rate_is_zero_or_within_its_range(value, key):
    data = put_bushing(BUSHED, key, value)
    field = f'constraints[0] (upper_arm).bushing.{key}'
    if within(value, *ANGULAR, zero=True):
        bushing = parse_scene(data, 'scene.yaml').constraints[0].bushing
        assert getattr(bushing, key) == float(value)
        return
    with pytest.raises(SceneError) as info:
        parse_scene(data, 'scene.yaml')
    assert_refused(info, 'scene.yaml', field, value, '0, or 0.001 to 1e+10 N m/deg')


SPRUNG = scene_data('double_wishbone')   # elements[1] is a spring with a rate


def spring_with(**keys):
    """Return double_wishbone's data with its spring's keys replaced (None: taken out)."""
    data = copy.deepcopy(SPRUNG)
    spring = data['elements'][1]
    for key, value in keys.items():
        spring.pop(key, None)
        if value is not None:
            spring[key] = value
    return data


@FUZZ
@given(value=numbers)
@example(value=1e308)
def test_a_spring_rate_loads_within_its_range_and_is_refused_outside(value):
    data = spring_with(rate=value)
    if within(value, *RATE):
        assert parse_scene(data, 'scene.yaml').elements[1].rate == float(value)
        return
    with pytest.raises(SceneError) as info:
        parse_scene(data, 'scene.yaml')
    assert_refused(info, 'scene.yaml', 'elements[1] (spring).rate', value,
                   '0.001 to 1e+11 N/mm')


@FUZZ
@given(value=numbers)
def test_a_free_length_loads_within_its_range_and_is_refused_outside(value):
    data = spring_with(free_length=value)
    if within(value, *HEIGHT):
        assert parse_scene(data, 'scene.yaml').elements[1].free_length == float(value)
        return
    with pytest.raises(SceneError) as info:
        parse_scene(data, 'scene.yaml')
    assert_refused(info, 'scene.yaml', 'elements[1] (spring).free_length', value,
                   '1e-06 to 1e+12 mm')


@FUZZ
@given(value=numbers)
@example(value=-1e308)                                    # issue 36, item 11
@example(value=1e308)
def test_a_force_table_force_is_within_its_range(value):
    # a flat table: its slope is 0, so only the force decides
    data = spring_with(rate=None, force_table=[[0.0, value], [10.0, value]])
    field = 'elements[1] (spring).force_table[0][1] (force)'
    if value == 0 or within(abs(value), 0.0, FORCE):
        table = parse_scene(data, 'scene.yaml').elements[1].force_table
        assert table[0, 1] == table[1, 1] == float(value)
        return
    with pytest.raises(SceneError) as info:
        parse_scene(data, 'scene.yaml')
    assert_refused(info, 'scene.yaml', field, value, '-1e+09 to 1e+09 N')


@FUZZ
@given(run=magnitudes, falls=st.booleans())
@example(run=1e-300, falls=False)                          # 1e303 N/mm
@example(run=1e-8, falls=True)                             # -1e11 N/mm: the steepest
@example(run=9.99e-9, falls=False)
def test_a_force_table_segment_has_a_slope_within_the_range_of_a_rate(run, falls):
    # 1000 N over run mm: a slope of 1e3 / run N/mm, rising or falling
    rows = [[0.0, 1000.0 if falls else 0.0], [run, 0.0 if falls else 1000.0]]
    data = spring_with(rate=None, force_table=rows)
    if not 0 < run <= LENGTH:
        with pytest.raises(SceneError):   # not rising, or a deflection beyond the limit
            parse_scene(data, 'scene.yaml')
        return
    slope = 1000.0 / float(run)
    if slope <= RATE[1]:
        parse_scene(data, 'scene.yaml')
        return
    with pytest.raises(SceneError) as info:
        parse_scene(data, 'scene.yaml')
    text = str(info.value)
    assert text.startswith('scene.yaml: elements[1] (spring).force_table[1]: the segment from '
                           'the row before rises'), text
    assert 'outside -1e+11 to 1e+11 N/mm' in text and '\n' not in text


@FUZZ
@given(value=numbers)
def test_a_force_table_deflection_is_a_coordinate(value):
    rows = [[-LENGTH, 0.0], [value, 0.0]] if value != -LENGTH else [[value, 0.0], [0.0, 0.0]]
    data = spring_with(rate=None, force_table=rows)
    try:
        fits = abs(float(value)) <= LENGTH
    except OverflowError:
        fits = False
    if fits and float(value) > -LENGTH:
        parse_scene(data, 'scene.yaml')
        return
    if not fits:
        with pytest.raises(SceneError, match=r'force_table\[1\]\[0\] \(deflection\): .* is '
                           r'outside -1e\+12 to 1e\+12 mm'):
            parse_scene(data, 'scene.yaml')


@FUZZ
@given(value=numbers)
def test_a_wheel_radius_is_zero_or_within_its_range(value):
    data = copy.deepcopy(SPRUNG)
    data['wheel_radius'] = value
    if within(value, *HEIGHT, zero=True):
        assert parse_scene(data, 'scene.yaml').wheel_radius == float(value)
        return
    with pytest.raises(SceneError) as info:
        parse_scene(data, 'scene.yaml')
    assert_refused(info, 'scene.yaml', 'wheel_radius', value, '0, or 1e-06 to 1e+12 mm')


# --- Vehicles ----------------------------------------------------------------------------

VEHICLE = yaml.safe_load((ROOT / 'config' / 'vehicles' / 'demo_vehicle.yaml').read_text())
FOLDER = Path(tempfile.mkdtemp(prefix='ranges_'))


def vehicle_with(put):
    """Write demo_vehicle with put(data) applied; return its path."""
    data = copy.deepcopy(VEHICLE)
    put(data)
    path = FOLDER / 'vehicle.yaml'
    path.write_text(yaml.safe_dump(data))
    return str(path)


VEHICLE_FIELDS = {   # field -> (where the value goes, the loaded value, bounds, zero allowed)
    'mass.sprung': (lambda d, v: d['mass'].update(sprung=v), lambda m: m.sprung, MASS, False),
    'mass.unsprung.front': (lambda d, v: d['mass']['unsprung'].update(front=v),
                            lambda m: m.unsprung['front'], MASS, True),
    'tyre_rate.rear': (lambda d, v: d['tyre_rate'].update(rear=v),
                       lambda m: m.tyre_rate['rear'], RATE, False),
    'mass.unsprung_cg_height.rear': (lambda d, v: d['mass']['unsprung_cg_height'].update(
        rear=v), lambda m: m.unsprung_cg_height['rear'], HEIGHT, False),
    'cg_height': (lambda d, v: d.update(cg_height=v), lambda m: m.cg_height, HEIGHT, False),
}


@settings(FUZZ, max_examples=60)
@given(value=numbers, field=st.sampled_from(sorted(VEHICLE_FIELDS)))
@example(value=1e308, field='mass.sprung')                    # issue 36, item 11
@example(value=1e-300, field='tyre_rate.rear')
@example(value=0, field='mass.unsprung.front')
def test_a_mass_a_height_and_a_tyre_rate_load_within_their_ranges(value, field):
    put, get, bounds, zero = VEHICLE_FIELDS[field]
    path = vehicle_with(lambda d: put(d, value))
    if within(value, *bounds, zero=zero):
        assert get(load_vehicle(path).mass) == float(value)
        return
    with pytest.raises(SceneError) as info:
        load_vehicle(path)
    assert_refused(info, path, field, value, '')


@settings(FUZZ, max_examples=60)
@given(value=numbers)
def test_a_front_share_is_within_its_range(value):
    path = vehicle_with(lambda d: d['mass'].update(front_share=value))
    if within(value, 1e-3, 1.0 - 1e-3):
        mass = load_vehicle(path).mass
        assert mass.cg_x == pytest.approx(-1400.0 + float(value) * 2800.0, abs=1e-9)
        return
    with pytest.raises(SceneError) as info:
        load_vehicle(path)
    assert_refused(info, path, 'mass.front_share', value, '0.001 to 0.999')


def test_a_centre_of_gravity_a_hair_off_the_rear_axle_is_refused_by_its_share():
    # cg_x 1e-9 mm ahead of the rear axle: inside the wheelbase, but its front share of 3.6e-13
    # would put a subnormal corner mass into the ride frequency's division
    path = vehicle_with(lambda d: (d['mass'].pop('front_share'),
                                   d['mass'].update(cg_x=-1400.0 + 1e-9)))
    with pytest.raises(SceneError, match=r'mass.cg_x: the centre of gravity at x = -1400 mm '
                       r'puts a share of the sprung mass on the front axle of 3.57\d*e-13 is '
                       r'outside 0.001 to 0.999'):
        load_vehicle(path)


@settings(FUZZ, max_examples=60)
@given(value=numbers)
@example(value=1e308)
def test_an_anti_roll_bar_rate_is_within_its_range(value):
    path = vehicle_with(lambda d: d['axles']['front']['anti_roll_bar'].update(rate=value))
    if within(value, *ANGULAR):
        bar = load_vehicle(path).axles.axles['front'].anti_roll_bar
        assert bar.rate == float(value)
        return
    with pytest.raises(SceneError) as info:
        load_vehicle(path)
    assert_refused(info, path, 'axles.front.anti_roll_bar.rate', value,
                   '0.001 to 1e+10 N m/deg')


# --- The table ---------------------------------------------------------------------------

def test_doc_scenes_md_holds_the_table_of_ranges_as_the_code_states_it():
    text = (ROOT / 'doc' / 'scenes.md').read_text()
    start = text.index('<!-- ranges: the table of linkage_ros/core/base/ranges.py -->\n')
    block = text[text.index('\n', start) + 1:text.index('<!-- end of ranges -->')]
    assert block == markdown_table(), (
        'doc/scenes.md#ranges is stale: python -m linkage_ros.core.base.ranges')


@pytest.mark.parametrize('doc, keys', [
    ('kc.md', ('bushing_rate', 'bushing_angular_rate')),
    ('scenes.md', ('bushing_rate', 'bushing_angular_rate')),
    ('elements.md', ('spring_rate', 'force_table_force', 'force_table_slope')),
    ('vehicle.md', ('sprung_mass', 'unsprung_mass', 'front_share', 'height', 'tyre_rate',
                    'bar_rate')),
    ('anti_roll_bar.md', ('bar_rate',))])
def test_each_page_that_quotes_a_range_quotes_it_as_the_table_states_it(doc, keys):
    text = ' '.join((ROOT / 'doc' / doc).read_text().split())
    for key in keys:
        assert RANGE[key].said() in text, (doc, key, RANGE[key].said())


def test_the_programs_help_says_the_ranges_of_what_they_read(capsys):
    from linkage_ros.tools import kc, sweep, vehicle
    for module, keys in ((kc, ('bushing_rate', 'bushing_angular_rate', 'spring_rate')),
                         (sweep, ('spring_rate', 'force_table_force', 'force_table_slope')),
                         (vehicle, ('sprung_mass', 'tyre_rate', 'bar_rate'))):
        with pytest.raises(SystemExit):
            module.main(['--help'])
        out = ' '.join(capsys.readouterr().out.split())
        for key in keys:
            assert ' '.join(say_ranges(key).split()) in out, (module.PROG, key)


def test_the_stiff_limit_of_the_statics_tests_lies_within_the_range_of_a_bushing():
    # test_statics.py scales the translational and conical rates of the bushed scenes by up to
    # 1e7 in memory (stiffer()): the stiffest (5000 N/mm, 10 N m/deg) stays in range, so the
    # solver is tested over the range the loader lets in.
    for name in ('double_wishbone_bushings', 'five_link_bushings'):
        for c in load_scene(name).constraints:
            if c.bushing is None:
                continue
            for rate in (c.bushing.axial * 1e7, c.bushing.radial * 1e7):
                assert RATE[0] <= rate <= RATE[1], (name, c.name, rate)
            assert c.bushing.conical * 1e7 <= ANGULAR[1]
    # and Chrono's sedan (conical 1745 N m/deg) at the x1e6 of the other stiff test
    for c in load_scene('chrono_sedan_doublewishbone_bushings').constraints:
        if c.bushing is not None:
            assert c.bushing.conical * 1e6 <= ANGULAR[1] and c.bushing.axial * 1e6 <= RATE[1]


def test_a_huge_integer_is_said_by_its_size_not_its_4300_digits():
    data = put_bushing(BUSHED, 'axial', 10**4000)
    with pytest.raises(SceneError) as info:
        parse_scene(data, 'scene.yaml')
    assert str(info.value) == ('scene.yaml: constraints[0] (upper_arm).bushing.axial: an '
                               'integer of about 4001 digits N/mm is outside 0.001 to 1e+11 '
                               'N/mm (doc/scenes.md#ranges)')
