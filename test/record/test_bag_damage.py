# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Damaged recordings: each kind of damage made with real corrupt bytes, named exactly.

The bag's layout (chunk offsets, which messages each chunk holds) and what linkage-replay
--copy recovers are read with mcap's own reader and with rosbags' AnyReader, never with
project code.
"""

import struct
import tracemalloc

from linkage_ros.record.mcap_reader import read_bag, RecordingError
from linkage_ros.record.mcap_writer import McapRecorder
from linkage_ros.tools import replay, rerun_convert
from mcap.reader import make_reader
from mcap.stream_reader import breakup_chunk, StreamReader
import pytest
from rosbags.highlevel import AnyReader
from std_msgs.msg import Float64

T0 = 1_700_000_000_000_000_000
COMMANDS = 120
HUGE = 2**62


def write_bag(path):
    """COMMANDS wheel-travel commands, each with a camber, in chunks of about 1 KiB."""
    with McapRecorder(path, chunk_size=1024, flush_period=0,
                      custom_data={'scene': 'five_link'}) as rec:
        for i in range(COMMANDS):
            t = T0 + i * 10**7
            rec.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=i / 1000.0), t, t)
            rec.record('/camber', 'std_msgs/msg/Float64', Float64(data=-i / 1e4), t + 1, t + 1)


class Layout:
    """
    Where things are in an intact bag, by mcap's reader.

    chunks: (start, length, compressed size, [(topic, log time, data)]); summary_start, the
    footer offset, the file size.
    """

    def __init__(self, path):
        self.data = path.read_bytes()
        with open(path, 'rb') as stream:
            reader = make_reader(stream)
            summary = reader.get_summary()
            self.footer = len(self.data) - 8 - 29
            topics = {c.id: c.topic for c in summary.channels.values()}
            indexes = sorted(summary.chunk_indexes, key=lambda c: c.chunk_start_offset)
        with open(path, 'rb') as stream:
            contents = [[(topics[r.channel_id], r.log_time, bytes(r.data))
                         for r in breakup_chunk(chunk) if type(r).__name__ == 'Message']
                        for chunk in StreamReader(stream, emit_chunks=True).records
                        if type(chunk).__name__ == 'Chunk']
        self.chunks = [(c.chunk_start_offset, c.chunk_length, c.compressed_size, messages)
                       for c, messages in zip(indexes, contents)]
        self.summary_start = struct.unpack_from('<Q', self.data, self.footer + 9)[0]
        self.size = len(self.data)

    def messages(self, without=(), before=None):
        """
        Return every message in file order, less those of the chunks numbered in without.

        With before: only those of the chunks before chunk number before.
        """
        chunks = self.chunks if before is None else self.chunks[:before]
        return [m for i, c in enumerate(chunks) if i not in without for m in c[3]]


@pytest.fixture(scope='module')
def layout(tmp_path_factory):
    path = tmp_path_factory.mktemp('intact') / 'run.mcap'
    write_bag(path)
    found = Layout(path)
    assert len(found.chunks) >= 6 and sum(len(c[3]) for c in found.chunks) == 2 * COMMANDS
    return found


def damaged(tmp_path, data, name='damaged.mcap'):
    path = tmp_path / name
    path.write_bytes(bytes(data))
    return path


def with_bytes(data, offset, new):
    out = bytearray(data)
    out[offset:offset + len(new)] = new
    return out


def flipped(data, offset):
    out = bytearray(data)
    out[offset] ^= 0xFF
    return out


def read_independently(path):
    """
    Return [(topic, log time, data)] of a file, by mcap and by rosbags (they must agree).

    mcap's make_reader gives file order, rosbags time order (the same here); both need a
    complete file with its summary.
    """
    with open(path, 'rb') as stream:
        by_mcap = [(c.topic, m.log_time, bytes(m.data))
                   for _, c, m in make_reader(stream).iter_messages(log_time_order=False)]
    with AnyReader([path]) as reader:
        by_rosbags = [(c.topic, t, bytes(raw)) for c, t, raw in reader.messages()]
    assert by_rosbags == sorted(by_mcap, key=lambda m: m[1])
    return by_mcap


def copied(tmp_path, path, capsys):
    """linkage-replay copy BAG -o OUT: (exit status, stderr, messages read back)."""
    out = tmp_path / 'recovered.mcap'
    status = replay.main(['copy', str(path), '-o', str(out)])
    err = capsys.readouterr().err
    return status, err, read_independently(out)


def messages(count):
    return f'{count} message{"" if count == 1 else "s"}'


def from_bag(bag):
    return [(m.topic, m.log_time, m.data) for m in bag.messages]


# --- chunks: damage inside, the file framing intact ----------------------------------------

CHUNK = 2     # the damaged chunk: one in the middle


def chunk_damage(layout):
    start, length, compressed, _ = layout.chunks[CHUNK]
    data = layout.data
    records = start + 9 + 40 + 4       # compressed bytes: after the header, 'zstd', length
    return {
        'compressed byte': (flipped(data, records + compressed // 2),
                            f'CRC mismatch in the chunk at byte {start}'),
        'crc field': (flipped(data, start + 9 + 24),
                      f'CRC mismatch in the chunk at byte {start}'),
        'zstd magic': (flipped(data, records),
                       f'the chunk at byte {start} does not decompress (zstd: not a zstd '
                       'frame)'),
        'zstd frame size': (flipped(data, records + 6),
                            f'the chunk at byte {start} does not decompress (its zstd frame '
                            f'holds '),
        'uncompressed size 2^62': (with_bytes(data, start + 9 + 16, struct.pack('<Q', HUGE)),
                                   f'the chunk at byte {start} does not decompress (it '
                                   f'declares {HUGE} bytes uncompressed from {compressed} '
                                   'compressed bytes, more than zstd can make of them)'),
        'compression name': (with_bytes(data, start + 9 + 32, b'zsTd'),
                             f'the chunk at byte {start} does not decompress (unknown '
                             "compression 'zsTd')"),
    }


@pytest.mark.parametrize('kind', ['compressed byte', 'crc field', 'zstd magic',
                                  'zstd frame size', 'uncompressed size 2^62',
                                  'compression name'])
def test_a_damaged_chunk_is_named_and_every_other_chunk_read(layout, tmp_path, capsys, kind):
    data, problem = chunk_damage(layout)[kind]
    path = damaged(tmp_path, data)
    bag = read_bag(path)
    assert bag.problem.startswith(problem)
    assert len(bag.damage) == 1 and bag.truncated
    expected = layout.messages(without={CHUNK})
    assert from_bag(bag) == expected
    assert bag.lost == len(layout.chunks[CHUNK][3])       # the summary's statistics count
    status, err, recovered = copied(tmp_path, path, capsys)
    assert status == 1 and recovered == expected
    assert (f'bag damaged: {len(expected)} messages read, {bag.lost} lost '
            f'({bag.problem}); copied the {len(expected)} messages read') in err


def test_a_flipped_byte_in_a_chunk_length_is_named_and_the_chunk_read_through_the_index(
        layout, tmp_path, capsys):
    start, length, _, _ = layout.chunks[CHUNK]
    declared = (length - 9) ^ 0x01                   # the lowest bit of the length flipped
    path = damaged(tmp_path, with_bytes(layout.data, start + 1, struct.pack('<Q', declared)))
    bag = read_bag(path)
    take = 'run past its end' if declared < length - 9 else f'take {length - 9}'
    assert bag.problem == f'a record at byte {start} (chunk) declares {declared} bytes, but ' \
                          f'its fields {take}'
    assert from_bag(bag) == layout.messages() and bag.lost == 0 and bag.truncated
    status, _, recovered = copied(tmp_path, path, capsys)
    assert status == 1 and recovered == layout.messages()


@pytest.mark.parametrize('declared', [HUGE, 2**64 - 1, 2**32 + 7, 100_000])
def test_a_length_beyond_the_file_is_refused_before_anything_is_read(
        layout, tmp_path, capsys, declared):
    start = layout.chunks[CHUNK][0]
    path = damaged(tmp_path, with_bytes(layout.data, start + 1, struct.pack('<Q', declared)))
    tracemalloc.start()
    try:
        bag = read_bag(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 20 * layout.size + 10**6          # nothing near the declared size
    assert bag.problem == (f'a record at byte {start} (chunk) declares {declared} bytes, '
                           f'beyond the end of the file (size {layout.size})')
    assert bag.damage[0].kind == 'length' and bag.damage[0].offset == start
    # The summary's chunk index still locates every chunk, the damaged one included.
    assert from_bag(bag) == layout.messages()
    status, _, recovered = copied(tmp_path, path, capsys)
    assert status == 1 and recovered == layout.messages()


def test_without_a_summary_a_bad_length_ends_the_reading_at_the_damaged_record(
        layout, tmp_path, capsys):
    start = layout.chunks[CHUNK][0]
    data = with_bytes(layout.data, start + 1, struct.pack('<Q', HUGE))[:layout.summary_start]
    path = damaged(tmp_path, data)
    bag = read_bag(path)
    assert bag.problem == (f'a record at byte {start} (chunk) declares {HUGE} bytes, beyond '
                           f'the end of the file (size {len(data)})')
    assert from_bag(bag) == layout.messages(before=CHUNK) and bag.lost is None
    status, _, recovered = copied(tmp_path, path, capsys)
    assert status == 1 and recovered == layout.messages(before=CHUNK)


def test_an_opcode_of_zero_is_named_and_the_chunks_after_it_read_through_the_index(
        layout, tmp_path, capsys):
    start = layout.chunks[CHUNK][0]
    path = damaged(tmp_path, with_bytes(layout.data, start, b'\0'))
    bag = read_bag(path)
    assert bag.problem == f'a record at byte {start} has opcode 0x00, which no MCAP record has'
    expected = layout.messages(without={CHUNK})
    assert from_bag(bag) == expected and bag.lost == len(layout.chunks[CHUNK][3])
    status, _, recovered = copied(tmp_path, path, capsys)
    assert status == 1 and recovered == expected


# --- cuts ----------------------------------------------------------------------------------

def test_a_cut_at_every_chunk_boundary_and_inside_every_chunk(layout, tmp_path, capsys):
    for number, (start, length, _, _) in enumerate(layout.chunks):
        for offset, problem, kept in (
                (start + length, f'cut at byte {start + length} (the file ends after the '
                 f'chunk record at byte {start}, before the footer)', number + 1),
                (start + length // 2, f'cut at byte {start + length // 2} (the file ends '
                 f'inside the chunk record at byte {start})', number),
                (start + 4, f'cut at byte {start + 4} (the file ends inside the chunk record '
                 f'at byte {start})', number)):
            path = damaged(tmp_path, layout.data[:offset], f'cut_{offset}.mcap')
            bag = read_bag(path)
            assert (bag.problem, bag.cut) == (problem, True)
            assert from_bag(bag) == layout.messages(before=kept)
            status, err, recovered = copied(tmp_path, path, capsys)
            assert status == 1 and recovered == layout.messages(before=kept)
            assert f'bag truncated after {messages(len(recovered))} ({problem})' in err


@pytest.mark.parametrize('keep, problem', [
    (8, 'cut at byte 8 (the file ends after the magic bytes, before the footer)'),
    (5, 'cut at byte 5 (the file ends inside the magic bytes)'),
    (-3, 'cut at byte {s} (the file ends inside the closing magic bytes)'),
    (-8, 'cut at byte {s} (the file ends after the footer record at byte {f}, before the '
     'closing magic bytes)'),
    (-20, 'cut at byte {s} (the file ends inside the footer record at byte {f})'),
])
def test_a_cut_at_the_start_or_the_end(layout, tmp_path, keep, problem):
    data = layout.data[:keep]
    bag = read_bag(damaged(tmp_path, data))
    assert bag.problem == problem.format(s=len(data), f=layout.footer)
    assert from_bag(bag) == (layout.messages() if keep < 0 else [])


def test_a_cut_inside_the_summary_loses_no_message(layout, tmp_path, capsys):
    data = layout.data[:layout.summary_start + 20]
    path = damaged(tmp_path, data)
    bag = read_bag(path)
    assert bag.problem.startswith(f'cut at byte {len(data)} (the file ends inside the ')
    assert from_bag(bag) == layout.messages() and bag.custom_data == {'scene': 'five_link'}
    status, _, recovered = copied(tmp_path, path, capsys)
    assert status == 1 and recovered == layout.messages()


# --- summary and footer --------------------------------------------------------------------

def test_a_flipped_byte_in_the_summary_is_a_bad_summary(layout, tmp_path, capsys):
    path = damaged(tmp_path, flipped(layout.data, layout.summary_start + 40))
    bag = read_bag(path)
    assert bag.problem == (f'bad summary: CRC mismatch in the summary at byte '
                           f'{layout.summary_start} (checked by the footer at byte '
                           f'{layout.footer})')
    assert from_bag(bag) == layout.messages()
    status, _, recovered = copied(tmp_path, path, capsys)
    assert status == 1 and recovered == layout.messages()


@pytest.mark.parametrize('offset, problem', [
    (-1, 'bad footer at byte {f}: the MCAP magic bytes do not follow it at byte {m}'),
    (-8 - 20, 'bad footer at byte {f}: it says the summary starts at byte {x}, but it starts '
     'at byte {s}'),
    (-8 - 28, 'bad footer: a record at byte {f} (footer) declares {n} bytes, beyond the end '
     'of the file (size {size})'),
])
def test_a_damaged_footer_is_a_bad_footer(layout, tmp_path, capsys, offset, problem):
    data = flipped(layout.data, layout.size + offset)
    path = damaged(tmp_path, data)
    bag = read_bag(path)
    x = struct.unpack_from('<Q', data, layout.footer + 9)[0]
    n = struct.unpack_from('<Q', data, layout.footer + 1)[0]
    assert bag.problem == problem.format(f=layout.footer, m=layout.footer + 29, x=x,
                                         s=layout.summary_start, n=n, size=layout.size)
    assert from_bag(bag) == layout.messages()
    status, _, recovered = copied(tmp_path, path, capsys)
    assert status == 1 and recovered == layout.messages()


def test_bytes_after_the_closing_magic_are_named(layout, tmp_path):
    bag = read_bag(damaged(tmp_path, layout.data + b'junk'))
    assert bag.problem == f'4 bytes follow the closing magic bytes at byte {layout.size - 8}'
    assert from_bag(bag) == layout.messages()


# --- not a recording -----------------------------------------------------------------------

@pytest.mark.parametrize('content, problem', [
    (b'PK\x03\x04\x14\x00\x00\x00\x08\x00' + bytes(40),
     'not an MCAP file (it does not start with the MCAP magic bytes)'),
    (b'', 'not an MCAP file (it is empty)'),
])
def test_a_file_that_is_not_mcap_is_refused_by_reader_and_commands(tmp_path, capsys, content,
                                                                   problem):
    path = damaged(tmp_path, content, 'notes.mcap')
    with pytest.raises(RecordingError) as raised:
        read_bag(path)
    assert str(raised.value) == f'{path}: {problem}'
    for main, first, extra in ((replay.main, ['copy'], ['-o', str(tmp_path / 'out.mcap')]),
                               (replay.main, ['solve'], ['-o', str(tmp_path / 'out.mcap')]),
                               (rerun_convert.main, [], ['-o', str(tmp_path / 'out.rrd')])):
        assert main([*first, str(path), *extra]) == 2
        err = capsys.readouterr().err
        assert err.count('\n') == 1 and err.endswith(f'{path}: {problem}\n')
    assert not (tmp_path / 'out.mcap').exists() and not (tmp_path / 'out.rrd').exists()


def test_a_bag_folder_with_two_mcap_files_is_refused(layout, tmp_path, capsys):
    folder = tmp_path / 'run'
    folder.mkdir()
    (folder / 'run_0.mcap').write_bytes(layout.data)
    (folder / 'run_1.mcap').write_bytes(layout.data)
    with pytest.raises(RecordingError, match=r'exactly one \.mcap file \(found: run_0.mcap, '
                       r'run_1.mcap\)'):
        read_bag(folder)
    assert replay.main(['copy', str(folder), '-o', str(tmp_path / 'out.mcap')]) == 2
    err = capsys.readouterr().err
    assert err == (f'linkage-replay: {folder}: a bag folder must hold exactly one .mcap file '
                   '(found: run_0.mcap, run_1.mcap)\n')


# --- the commands on a damaged bag ---------------------------------------------------------

def test_replay_and_rerun_solve_and_convert_what_a_damaged_bag_holds_with_status_1(
        layout, tmp_path, capsys):
    data, problem = chunk_damage(layout)['crc field']
    path = damaged(tmp_path, data)
    expected = layout.messages(without={CHUNK})
    commands = sum(1 for m in expected if m[0] == '/wheel_travel')
    lost = len(layout.chunks[CHUNK][3])
    out = tmp_path / 'solved.mcap'
    assert replay.main(['solve', str(path), '-o', str(out)]) == 1
    err = capsys.readouterr().err
    assert (f'linkage-replay: warning: {path}: bag damaged: {len(expected)} messages read, '
            f'{lost} lost ({problem}); solving the {commands} commands read\n') in err
    solved = read_independently(out)
    assert sum(1 for m in solved if m[0] == '/wheel_travel') == commands
    assert sum(1 for m in solved if m[0] == '/camber') == commands
    assert rerun_convert.main([str(path), '-o', str(tmp_path / 'run.rrd')]) == 1
    err = capsys.readouterr().err
    assert (f'linkage-rerun: warning: {path}: bag damaged: {len(expected)} messages read, '
            f'{lost} lost ({problem}); converting those\n') in err
    assert replay.main(['solve', str(layout_path(tmp_path, layout)), '-o', str(out)]) == 0


def layout_path(tmp_path, layout):
    return damaged(tmp_path, layout.data, 'intact.mcap')
