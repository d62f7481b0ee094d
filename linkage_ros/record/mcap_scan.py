# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
One pass over the records of an MCAP file, every declared size checked, damage named.

An MCAP file is the magic bytes, then records (opcode: 1 byte, length: 8 bytes, content),
then the magic bytes again. Scan walks the records itself only to check each declared size
against the file before anything is read or allocated; every record is then parsed by the
mcap library (its record classes and breakup_chunk, which decompresses a chunk and checks its
CRC). Whatever is damaged is named with its byte offset (Damage), and reading goes on
wherever the file still says where the next record is. mcap_reader.read_bag builds a Bag of
what the scan found.
"""

from dataclasses import dataclass
import functools
import io
import struct
import zlib

from mcap.data_stream import ReadDataStream
from mcap.exceptions import EndOfFile, McapError
from mcap.opcode import Opcode
from mcap.records import (Attachment, AttachmentIndex, Channel, Chunk, ChunkIndex, DataEnd,
                          Footer, Header, Message, MessageIndex, Metadata, MetadataIndex,
                          Schema, Statistics, SummaryOffset)
from mcap.stream_reader import breakup_chunk, CRCValidationError

MCAP_MAGIC = b'\x89MCAP0\r\n'
RECORD_LIMIT = 4 * 2**30     # bytes: largest record or uncompressed chunk read (mcap's default)
# Most bytes one compressed byte can become: zstd's RLE block turns 4 bytes into 128 KiB;
# lz4 turns about 1 byte into 255.
EXPANSION = {'zstd': 2**15, 'lz4': 2**8, '': 1}
_NAMES = {op: op.name.lower().replace('_', ' ') for op in Opcode}
_FIXED_LENGTH = {Opcode.FOOTER: 20, Opcode.DATA_END: 4, Opcode.SUMMARY_OFFSET: 17}
_PARSERS = {Opcode.HEADER: Header.read, Opcode.FOOTER: Footer.read, Opcode.SCHEMA: Schema.read,
            Opcode.CHANNEL: Channel.read, Opcode.MESSAGE_INDEX: MessageIndex.read,
            Opcode.CHUNK_INDEX: ChunkIndex.read, Opcode.ATTACHMENT: Attachment.read,
            Opcode.ATTACHMENT_INDEX: AttachmentIndex.read, Opcode.STATISTICS: Statistics.read,
            Opcode.METADATA: Metadata.read, Opcode.METADATA_INDEX: MetadataIndex.read,
            Opcode.SUMMARY_OFFSET: SummaryOffset.read, Opcode.DATA_END: DataEnd.read}
# What mcap's parsers raise on malformed content (EndOfFile: a field runs past the record).
_MALFORMED = (McapError, struct.error, UnicodeDecodeError, ValueError, OverflowError)


@dataclass(frozen=True)
class Damage:
    """
    One thing found wrong in a file: kind, the byte offset where it is, and what it is.

    kind: 'cut' (the file ends early), 'length' (a record's declared size is impossible),
    'record' (a record's content is malformed), 'crc' (a CRC does not match), 'decompress'
    (a chunk does not decompress), 'channel' (messages of a channel the file does not
    define), 'summary' or 'footer' (the index at the end of the file).
    """

    kind: str
    offset: int
    message: str


class _Stop(Exception):
    """The records cannot be followed past this damage."""

    def __init__(self, damage):
        super().__init__(damage.message)
        self.damage = damage


class Scan:
    """
    One pass over an MCAP file: records checked, parsed by mcap, damage noted.

    Scan(stream, size).run() fills: damage (Damage, in the order found), profile, schemas and
    channels ({id: mcap record}), raw ((channel id, log time, publish time, data, record
    offset) of each message, in file order), metadata, statistics.
    """

    def __init__(self, stream, size):
        self.stream, self.size = stream, size
        self.damage = []
        self.profile = ''
        self.schemas, self.channels = {}, {}
        self.raw = []   # (channel id, log time, publish time, data, record offset), file order
        self.metadata = {}   # name -> {key: value} of each metadata record (the first)
        self.statistics = None
        self.chunk_indexes, self.metadata_indexes = [], []
        self.chunks_read = set()    # byte offsets of the chunk records met, damaged or not

    # --- walking the records ---

    def run(self):
        """Read every record from the first to the footer and the closing magic bytes."""
        offset, previous = len(MCAP_MAGIC), None
        crc = zlib.crc32(MCAP_MAGIC)  # of the data section: every byte before the data end
        summary_start = None          # offset after the data end record
        while True:
            if offset == self.size:
                after = (f'after the {_record_name(previous[0])} record at byte {previous[1]}'
                         if previous else 'after the magic bytes')
                self.note('cut', offset, f'cut at byte {offset} (the file ends {after}, '
                          'before the footer)')
                return
            try:
                opcode, head, content = self._record_at(offset)
            except _Stop as stop:
                damage = stop.damage
                if summary_start is None:
                    self.damage.append(damage)
                    self._resync(offset)
                elif damage.kind == 'cut':
                    self.damage.append(damage)
                elif self._read_at(offset, 1) == bytes([Opcode.FOOTER]):
                    self.note('footer', damage.offset, f'bad footer: {damage.message}')
                else:
                    self.note('summary', damage.offset, f'bad summary: {damage.message}')
                return
            if opcode == Opcode.FOOTER:
                self._footer(offset, content, summary_start)
                return
            if summary_start is None and opcode == Opcode.DATA_END:
                self._data_end(offset, content, crc)
                summary_start = offset + len(head) + len(content)
            elif summary_start is None:
                crc = zlib.crc32(content, zlib.crc32(head, crc))
                self._handle(opcode, offset, content, summary=False)
            else:
                self._handle(opcode, offset, content, summary=True)
            previous = (opcode, offset)
            offset += len(head) + len(content)

    def _read_at(self, offset, length):
        self.stream.seek(offset)
        return self.stream.read(length)

    def _record_at(self, offset):
        """
        Return (opcode, 9 header bytes, content) of the record at offset.

        Its declared length is checked against the file size, RECORD_LIMIT and its own
        fields before it is read; _Stop says what is wrong.
        """
        head = self._read_at(offset, 9)
        name = f'the {_record_name(head[0])} record' if head else 'a record'
        if len(head) < 9:
            raise _Stop(Damage('cut', self.size, f'cut at byte {self.size} (the file ends '
                               f'inside {name} at byte {offset})'))
        opcode, length = struct.unpack('<BQ', head)
        if opcode == 0:
            raise _Stop(Damage('record', offset, f'a record at byte {offset} has opcode 0x00, '
                               'which no MCAP record has'))
        what = f'a record at byte {offset} ({_record_name(opcode)})'
        available = self.size - offset - 9
        if length > available:
            fields = _implied_length(opcode, self._read_at(offset + 9, min(available, 4096)),
                                     length)
            if length > RECORD_LIMIT or fields not in (None, length):
                raise _Stop(Damage('length', offset, f'{what} declares {length} bytes, beyond '
                                   f'the end of the file (size {self.size})'))
            raise _Stop(Damage('cut', self.size, f'cut at byte {self.size} (the file ends '
                               f'inside {name} at byte {offset})'))
        content = self.stream.read(length)
        fields = _implied_length(opcode, content, length)
        if fields is not None and fields != length:
            take = ('run past its end' if fields > length else f'take {fields}')
            raise _Stop(Damage('length', offset, f'{what} declares {length} bytes, but its '
                               f'fields {take}'))
        return opcode, head, content

    def _data_end(self, offset, content, crc):
        try:
            record = DataEnd.read(ReadDataStream(io.BytesIO(content)))
        except _MALFORMED:
            return    # its fixed length was checked: not reached
        if record.data_section_crc and record.data_section_crc != crc:
            if not any(d.kind in ('crc', 'decompress', 'record', 'channel')
                       for d in self.damage):
                self.note('crc', offset, 'CRC mismatch in the data section (checked by the '
                          f'data end record at byte {offset})')

    def _footer(self, offset, content, summary_start):
        footer = Footer.read(ReadDataStream(io.BytesIO(content)))   # 20 bytes: checked
        if summary_start is None:
            self.note('footer', offset, f'bad footer at byte {offset}: no data end record '
                      'comes before it')
        elif footer.summary_start == 0 and summary_start != offset:
            self.note('footer', offset, f'bad footer at byte {offset}: it says the file has '
                      f'no summary, but one starts at byte {summary_start}')
        elif footer.summary_start not in (0, summary_start):
            self.note('footer', offset, f'bad footer at byte {offset}: it says the summary '
                      f'starts at byte {footer.summary_start}, but it starts at byte '
                      f'{summary_start}')
        elif footer.summary_start and footer.summary_crc:
            data = self._read_at(summary_start, offset + 9 + 16 - summary_start)
            if zlib.crc32(data) != footer.summary_crc:   # says it all: no detail before
                self.damage = [d for d in self.damage if d.kind != 'summary']
                self.note('summary', summary_start, 'bad summary: CRC mismatch in the summary '
                          f'at byte {summary_start} (checked by the footer at byte {offset})')
        end = offset + 9 + 20
        magic = self._read_at(end, len(MCAP_MAGIC) + 1)
        if not magic:
            self.note('cut', self.size, f'cut at byte {self.size} (the file ends after the '
                      f'footer record at byte {offset}, before the closing magic bytes)')
        elif len(magic) < len(MCAP_MAGIC) and magic == MCAP_MAGIC[:len(magic)]:
            self.note('cut', self.size, f'cut at byte {self.size} (the file ends inside the '
                      'closing magic bytes)')
        elif magic[:len(MCAP_MAGIC)] != MCAP_MAGIC:
            self.note('footer', end, f'bad footer at byte {offset}: the MCAP magic bytes do '
                      f'not follow it at byte {end}')
        elif len(magic) > len(MCAP_MAGIC):
            extra = self.size - end - len(MCAP_MAGIC)
            self.note('footer', end + len(MCAP_MAGIC), f'{extra} bytes follow the closing '
                      f'magic bytes at byte {end}')

    def _resync(self, damaged):
        """
        Read on after damage at byte damaged of the data section, through the summary.

        The chunks and metadata records at or after it that an intact summary indexes are
        read (footer and summary checked by their CRC first). Nothing happens if the file
        has no intact footer and summary.
        """
        footer_at = self.size - len(MCAP_MAGIC) - 9 - 20
        if footer_at <= damaged or self._read_at(footer_at + 29, 8) != MCAP_MAGIC:
            return
        head = self._read_at(footer_at, 9)
        if head != struct.pack('<BQ', Opcode.FOOTER, 20):
            return
        footer = Footer.read(ReadDataStream(io.BytesIO(self._read_at(footer_at + 9, 20))))
        start = footer.summary_start
        if not damaged < start <= footer_at or (footer.summary_crc and zlib.crc32(
                self._read_at(start, footer_at + 9 + 16 - start)) != footer.summary_crc):
            return
        try:
            records = []
            offset = start
            while offset < footer_at:
                opcode, head, content = self._record_at(offset)
                records.append((opcode, offset, content))
                offset += len(head) + len(content)
        except _Stop:
            return
        if offset != footer_at:
            return
        for opcode, offset, content in records:
            self._handle(opcode, offset, content, summary=True)
        for index in sorted(self.chunk_indexes, key=lambda c: c.chunk_start_offset):
            self._indexed(index.chunk_start_offset, index.chunk_length, Opcode.CHUNK,
                          damaged, footer_at)
        for index in sorted(self.metadata_indexes, key=lambda m: m.offset):
            self._indexed(index.offset, index.length, Opcode.METADATA, damaged, footer_at)

    def _indexed(self, offset, length, opcode, damaged, limit):
        """Read a record the summary locates (at or after byte damaged, before limit)."""
        if not (damaged <= offset and 9 <= length and offset + length <= limit):
            return
        if self._read_at(offset, 1) != bytes([opcode]):
            return
        content = self._read_at(offset + 9, length - 9)   # the index's length, not the record's
        if _implied_length(opcode, content, len(content)) in (None, len(content)):
            self._handle(opcode, offset, content, summary=False)

    # --- records ---

    def note(self, kind, offset, message):
        """Add a Damage of kind at byte offset, saying message."""
        self.damage.append(Damage(kind, offset, message))

    def _handle(self, opcode, offset, content, summary):
        if opcode == Opcode.CHUNK:
            self._chunk(offset, content)
            return
        parse = _PARSERS.get(opcode)
        if opcode == Opcode.MESSAGE:
            parse = functools.partial(_read_message, length=len(content))
        if parse is None:
            return                    # a record type of a later MCAP version: skipped
        try:
            record = parse(ReadDataStream(io.BytesIO(content)))
        except _MALFORMED as exc:
            prefix = 'bad summary: ' if summary else ''
            self.note('summary' if summary else 'record', offset, f'{prefix}the '
                      f'{_NAMES[opcode]} record at byte {offset} is malformed ({_reason(exc)})')
            return
        self._take(record, offset)

    def _take(self, record, offset):
        if isinstance(record, Message):
            self.raw.append((record.channel_id, record.log_time, record.publish_time,
                             bytes(record.data), offset))
        elif isinstance(record, Channel):
            self.channels.setdefault(record.id, record)
        elif isinstance(record, Schema):
            self.schemas.setdefault(record.id, record)
        elif isinstance(record, Header):
            self.profile = record.profile
        elif isinstance(record, Metadata):
            self.metadata.setdefault(record.name, dict(record.metadata))
        elif isinstance(record, Statistics):
            self.statistics = record
        elif isinstance(record, ChunkIndex):
            self.chunk_indexes.append(record)
        elif isinstance(record, MetadataIndex):
            self.metadata_indexes.append(record)

    def _chunk(self, offset, content):
        """
        Decompress a chunk (mcap's breakup_chunk, CRC checked) and take its records.

        Its uncompressed size is checked first, against what its compression can produce.
        """
        where = f'the chunk at byte {offset}'
        self.chunks_read.add(offset)
        usize, = struct.unpack_from('<Q', content, 16)
        clen, = struct.unpack_from('<I', content, 28)    # fields checked by _record_at
        data = content[40 + clen:]
        try:
            compression = content[32:32 + clen].decode()
        except UnicodeDecodeError:
            compression = repr(bytes(content[32:32 + clen]))
        problem = _size_problem(compression, usize, data)
        if problem:
            self.note('decompress', offset, f'{where} does not decompress ({problem})')
            return
        try:
            chunk = Chunk.read(ReadDataStream(io.BytesIO(content)))
            records = breakup_chunk(chunk, validate_crc=True)
        except CRCValidationError:
            self.note('crc', offset, f'CRC mismatch in {where}')
            return
        except _DECOMPRESSION_ERRORS as exc:
            self.note('decompress', offset, f'{where} does not decompress ({compression}: '
                      f'{_reason(exc)})')
            return
        except _MALFORMED as exc:
            self.note('record', offset, f'{where} holds a malformed record ({_reason(exc)})')
            return
        for record in records:
            self._take(record, offset)


_DECOMPRESSION_ERRORS = (RuntimeError,)   # lz4.frame; zstandard.ZstdError added on import
try:
    import zstandard
    _DECOMPRESSION_ERRORS += (zstandard.ZstdError,)
except ImportError:   # mcap reads zstd chunks only with zstandard installed
    zstandard = None
try:
    import lz4.frame as lz4_frame
except ImportError:   # and lz4 chunks only with lz4
    lz4_frame = None


def _read_message(stream, length):
    return Message.read(stream, length)


def _record_name(opcode):
    return _NAMES.get(opcode, f'unknown (opcode 0x{opcode:02x})')


def _reason(exc):
    if isinstance(exc, EndOfFile):
        return 'a field runs past its end'
    return f'{type(exc).__name__}: {exc}' if str(exc) else type(exc).__name__


def _implied_length(opcode, content, length):
    """
    Return the content length that the fields at the start of a record imply.

    content: all or the first bytes of the record's content; length: its declared length.
    None if the fields do not say, or are not all there. Exact for chunks, message indexes
    and fixed-size records; for a chunk whose compression name runs past length, a lower
    bound above length.
    """
    if opcode in _FIXED_LENGTH:
        return _FIXED_LENGTH[opcode]
    if opcode == Opcode.CHUNK and length < 40:
        return 40
    if opcode == Opcode.CHUNK and len(content) >= 32:
        clen, = struct.unpack_from('<I', content, 28)
        if 40 + clen > length:
            return 40 + clen
        if len(content) < 40 + clen:
            return None
        rlen, = struct.unpack_from('<Q', content, 32 + clen)
        return 40 + clen + rlen
    if opcode == Opcode.MESSAGE_INDEX and length < 6:
        return 6
    if opcode == Opcode.MESSAGE_INDEX and len(content) >= 6:
        return 6 + struct.unpack_from('<I', content, 2)[0]
    if opcode == Opcode.MESSAGE:
        return None if len(content) >= 22 else 22
    return None


def _size_problem(compression, usize, data):
    """Why a chunk's declared uncompressed size (usize) cannot be right, or ''."""
    if compression not in EXPANSION:
        return f'unknown compression {compression!r}'
    if compression == '':
        if usize != len(data):
            return (f'it declares {usize} bytes uncompressed, but stores {len(data)} bytes '
                    'without compression')
        return ''
    if usize > RECORD_LIMIT or usize > EXPANSION[compression] * len(data):
        return (f'it declares {usize} bytes uncompressed from {len(data)} compressed bytes, '
                f'more than {compression} can make of them')
    if compression == 'zstd' and zstandard is not None:
        try:
            stored = zstandard.frame_content_size(data)
        except zstandard.ZstdError:
            return 'zstd: not a zstd frame'
        if stored >= 0 and stored != usize:
            return f'its zstd frame holds {stored} bytes, but the chunk declares {usize}'
    if compression == 'lz4' and lz4_frame is not None:
        try:
            stored = lz4_frame.get_frame_info(data)['content_size']
        except RuntimeError:
            return 'lz4: not an lz4 frame'
        if stored and stored != usize:
            return f'its lz4 frame holds {stored} bytes, but the chunk declares {usize}'
    return ''
