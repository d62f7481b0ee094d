# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Fuzzed input files: scene and vehicle YAML, and bags of arbitrary or damaged bytes.

A loader may refuse a file only with LinkageError (the base class of the project's input
errors) whose message names the file and a field; read_bag may only return a Bag (damaged
or not) or raise RecordingError, without allocating anything near a size the file declares.
Hypothesis settings are modest (a few dozen to a few hundred examples) and write no database.
"""

import math
from pathlib import Path
import struct
import tempfile
import tracemalloc

from hypothesis import given, HealthCheck, settings, strategies as st
from linkage_ros.core.base import LinkageError, MAX_POSITIONS, positions_needed
from linkage_ros.core.base.errors import bounded, PROBLEM_LIMIT, WHERE_LIMIT
from linkage_ros.core.model import load_scene, load_vehicle, safe_stem, SceneError
from linkage_ros.core.solve import travel_range
from linkage_ros.record.mcap_reader import Bag, read_bag, RecordingError
from linkage_ros.record.mcap_writer import McapRecorder
import pytest
from std_msgs.msg import Float64
import yaml

ROOT = Path(__file__).resolve().parents[2]
SCENES = sorted((ROOT / 'config' / 'scenes').glob('*.yaml'))
VEHICLES = sorted((ROOT / 'config' / 'vehicles').glob('*.yaml'))
FUZZ = settings(deadline=None, database=None, max_examples=150,
                suppress_health_check=[HealthCheck.too_slow])

# --- YAML values ---------------------------------------------------------------------------

scalars = (st.none() | st.booleans() | st.integers() | st.integers(-10**400, 10**400)
           | st.floats() | st.text(max_size=12)
           | st.sampled_from(['mm', 'm', 'left', 'right', 'sphere', 'circle', 'line', 'rack',
                              'five_link', 'double_wishbone', '', '.yaml', 'x.yml']))
values = st.recursive(scalars, lambda children: st.lists(children, max_size=4)
                      | st.dictionaries(st.text(max_size=8) | scalars.filter(
                          lambda v: v is None or isinstance(v, (bool, int, str))),
                          children, max_size=4),
                      max_leaves=12)


def structure(data):
    """Every (path, value) of a nested mapping or list; path: the keys and indices to it."""
    yield (), data
    items = data.items() if isinstance(data, dict) else enumerate(data) \
        if isinstance(data, list) else ()
    for key, value in items:
        for path, inner in structure(value):
            yield (key, *path), inner


def broken(data, path, new, delete):
    """Return a deep copy of data with the value at path replaced by new (or deleted)."""
    copy = yaml.safe_load(yaml.safe_dump(data))
    if not path:
        return new
    parent = copy
    for key in path[:-1]:
        parent = parent[key]
    if delete and isinstance(parent, dict):
        del parent[path[-1]]
    else:
        parent[path[-1]] = new
    return copy


@pytest.fixture(scope='module')
def folder():
    with tempfile.TemporaryDirectory() as name:
        yield Path(name)


def write(folder, name, data=None, text=None):
    path = folder / name
    if text is not None:
        path.write_bytes(text if isinstance(text, bytes) else text.encode('utf-8',
                                                                          'surrogatepass'))
    else:
        path.write_text(yaml.safe_dump(data, allow_unicode=True))
    return path


def assert_refused_well(exc, path):
    """
    Check that exc is a LinkageError naming the file and a field.

    Its message is 'file: field: problem' about path (or a scene a vehicle names), the
    field not empty.
    """
    assert isinstance(exc, LinkageError), f'{type(exc).__name__}: {exc}'
    # one line of bounded length: a where or problem too long is cut in the middle (issue 36)
    assert len(str(exc)) <= WHERE_LIMIT + PROBLEM_LIMIT + 2 and '\n' not in str(exc)
    if isinstance(exc, SceneError):
        assert exc.field and str(exc) == (f'{bounded(f"{exc.source}: {exc.field}", WHERE_LIMIT)}'
                                          f': {bounded(exc.problem, PROBLEM_LIMIT)}')
        assert exc.source == str(path) or Path(exc.source).suffix in ('.yaml', '.yml'), exc
    else:
        assert str(path) in str(exc)


def load(loader, path):
    """loader(path), or the exception it raised (anything but LinkageError fails the test)."""
    try:
        return loader(path)
    except Exception as exc:  # noqa: B902 (the test is that only LinkageError comes out)
        assert_refused_well(exc, path)
        return exc


@FUZZ
@given(data=values)
def test_any_yaml_structure_as_a_scene_or_vehicle_gives_a_result_or_a_linkage_error(
        folder, data):
    for loader, name in ((load_scene, 'scene.yaml'), (load_vehicle, 'vehicle.yaml')):
        load(loader, write(folder, name, data))


# Hostile files of issue 23 (since refused as they are read, see test_yaml_file): aliases
# that multiply, a recursive alias, a tag that would run code, a key twice.
HOSTILE = ['a: &a [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n' + ''.join(
    f'{b}: &{b} [{", ".join([f"*{a}"] * 10)}]\n' for a, b in zip('abcdefgh', 'bcdefghi'))
    + 'name: *i\n', 'a: &a [1, *a]\nname: *a\n', 'units: !!python/object/apply:os.system [x]',
    'units: mm\nunits: m\n']


@FUZZ
@given(text=st.text(max_size=60) | st.binary(max_size=60) | st.sampled_from([
    'a: 2001-13-45', 'units: [', '\x00', 'carrier: !!binary x', '- ' * 2000 + 'x',
    '[' * 2000, 'units: mm\nside: left\ncarrier: 2001-02-30', *HOSTILE]))
def test_any_text_or_bytes_as_a_scene_or_vehicle_gives_a_linkage_error(folder, text):
    for loader, name in ((load_scene, 'scene.yaml'), (load_vehicle, 'vehicle.yaml')):
        load(loader, write(folder, name, text=text))


@FUZZ
@given(scene=st.sampled_from(SCENES), choice=st.integers(0, 10**6), new=values,
       delete=st.booleans())
def test_a_bundled_scene_with_one_field_broken_loads_or_names_the_field(folder, scene, choice,
                                                                        new, delete):
    data = yaml.safe_load(scene.read_text())
    paths = [p for p, _ in structure(data)]
    path = paths[choice % len(paths)]
    written = write(folder, 'scene.yaml', broken(data, path, new, delete))
    result = load(load_scene, written)
    if isinstance(result, SceneError) and path and isinstance(path[0], str):
        # A constraint broken may be the error of what names it: an element, the kingpin.
        top = result.field.split('.')[0].split('[')[0]
        assert result.field == 'file' or top in (
            path[0], 'carrier', 'constraints', 'travel', 'scene', 'kingpin', 'elements'), (
                path, str(result))


@FUZZ
@given(vehicle=st.sampled_from(VEHICLES), choice=st.integers(0, 10**6), new=values,
       delete=st.booleans())
def test_a_bundled_vehicle_with_one_field_broken_loads_or_names_the_field(folder, vehicle,
                                                                          choice, new, delete):
    data = yaml.safe_load(vehicle.read_text())
    paths = [p for p, _ in structure(data)]
    path = paths[choice % len(paths)]
    written = write(folder, 'vehicle.yaml', broken(data, path, new, delete))
    result = load(load_vehicle, written)
    if isinstance(result, SceneError) and result.source == str(written) and len(path) > 1:
        assert result.field.split('.')[0] in (path[0], 'file', 'corners', 'axles'), (
            path, str(result))


@FUZZ
@given(name=st.text() | st.sampled_from(['..', '.', '../../x', '/abs/x', '-rf', '']))
def test_any_scene_name_gives_a_file_stem_that_stays_in_its_folder(folder, name):
    stem = safe_stem(name)
    assert 0 < len(stem) <= 100 and '/' not in stem and '\x00' not in stem
    assert stem not in ('.', '..') and not stem.startswith(('-', '.'))
    assert (folder / f'{stem}.mcap').resolve().parent == folder.resolve()


@FUZZ
@given(start=st.floats() | st.integers(-10**400, 10**400), stop=st.floats(),
       step=st.floats() | st.integers(-10**400, 10**400))
def test_any_travel_range_gives_a_bounded_count_or_a_linkage_error(start, stop, step):
    try:
        count = positions_needed(start, stop, step)
    except LinkageError as exc:
        assert exc.where == 'travel' and ('finite' in exc.problem or 'limit' in exc.problem)
        return
    assert 1 <= count <= MAX_POSITIONS
    assert count == len(travel_range(float(start), stop, float(step)))


# --- bags ----------------------------------------------------------------------------------

@pytest.fixture(scope='module')
def small_bag(folder):
    """Bytes of a complete bag: 40 messages on two topics, in chunks of about 512 bytes."""
    path = folder / 'small.mcap'
    with McapRecorder(path, chunk_size=512, flush_period=0, custom_data={'scene': 'x'}) as rec:
        for i in range(20):
            rec.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=i / 100), i, i)
            rec.record('/camber', 'std_msgs/msg/Float64', Float64(data=-i / 100), i, i)
    return path.read_bytes()


def read_safely(folder, data):
    """read_bag of data written to a file: a Bag or a RecordingError, read in bounded memory."""
    path = write(folder, 'fuzz.mcap', text=bytes(data))
    tracemalloc.start()
    try:
        try:
            result = read_bag(path)
        except RecordingError as exc:
            result = exc
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 32 * 2**20 + 50 * len(data), peak   # never near a size the file declares
    assert isinstance(result, (Bag, RecordingError))
    if isinstance(result, Bag):
        assert result.truncated == bool(result.damage) == bool(result.problem)
        assert result.problem == '; '.join(d.message for d in result.damage)
        assert all(m.topic in result.topics for m in result.messages)
    return result


MAGIC = b'\x89MCAP0\r\n'


@FUZZ
@given(data=st.binary(max_size=300) | st.binary(max_size=300).map(lambda b: MAGIC + b))
def test_arbitrary_bytes_give_a_bag_or_a_recording_error(folder, data):
    result = read_safely(folder, data)
    if not data.startswith(MAGIC[:len(data)]) or not data:
        assert isinstance(result, RecordingError) and 'not an MCAP file' in str(result)


@settings(deadline=None, database=None, max_examples=300)
@given(edits=st.lists(st.tuples(st.integers(0, 10**6), st.binary(min_size=1, max_size=8)),
                      min_size=1, max_size=4),
       cut=st.none() | st.integers(0, 10**6))
def test_a_valid_bag_with_bytes_overwritten_or_cut_gives_a_bag_with_what_is_intact(
        folder, small_bag, edits, cut):
    data = bytearray(small_bag)
    for position, new in edits:
        at = position % len(data)
        data[at:at + len(new)] = new
    if cut is not None:
        data = data[:cut % (len(data) + 1)]
    result = read_safely(folder, data)
    if isinstance(result, Bag):
        assert len(result.messages) <= 40
        if not result.truncated:
            assert len(result.messages) == 40 and result.lost == 0


@pytest.mark.parametrize('opcode', [0x01, 0x7F])   # a second Header; a later version's record
def test_a_chunk_whose_opcode_is_overwritten_is_named_as_damage_at_its_offset(
        folder, small_bag, opcode):
    # found by the fuzz test above: the reader read past the record as another kind, and one
    # message was lost with no damage said (the bag looked whole)
    from mcap.reader import make_reader
    import io
    start = min(c.chunk_start_offset for c in make_reader(
        io.BytesIO(small_bag)).get_summary().chunk_indexes)
    data = bytearray(small_bag)
    data[start] = opcode
    result = read_safely(folder, data)
    assert isinstance(result, Bag) and result.truncated and result.lost >= 1
    assert [(d.kind, d.offset) for d in result.damage] == [('record', start)]


@settings(deadline=None, database=None, max_examples=200)
@given(field=st.sampled_from(['record length', 'uncompressed size', 'compression length',
                              'records length']),
       value=st.integers(0, 2**64 - 1), chunk=st.integers(0, 100))
def test_any_declared_size_in_a_chunk_is_checked_before_it_is_read(folder, small_bag, field,
                                                                   value, chunk):
    from mcap.reader import make_reader
    import io
    starts = sorted(c.chunk_start_offset for c in make_reader(
        io.BytesIO(small_bag)).get_summary().chunk_indexes)
    start = starts[chunk % len(starts)]
    at, size = {'record length': (start + 1, 8), 'uncompressed size': (start + 9 + 16, 8),
                'compression length': (start + 9 + 28, 4),
                'records length': (start + 9 + 36, 8)}[field]
    data = bytearray(small_bag)
    data[at:at + size] = struct.pack('<Q' if size == 8 else '<I', value % 2**(8 * size))
    result = read_safely(folder, data)
    assert isinstance(result, Bag)
    if result.truncated:
        assert any(str(start) in d.message for d in result.damage), result.problem
    assert math.isfinite(len(result.messages))
