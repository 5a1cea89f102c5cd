"""MCAP files read as a stream: McapReader yields the messages in file order and fills in the
schemas, channels, metadata and statistics as it passes their records."""

from __future__ import annotations

import os
import struct
import zlib
from dataclasses import dataclass

from .errors import RecordingError

MAGIC = b"\x89MCAP0\r\n"

# The opcodes this reader acts on; the others (indexes, attachments, summary offsets) it skips.
OP_HEADER, OP_FOOTER, OP_SCHEMA, OP_CHANNEL, OP_MESSAGE = 0x01, 0x02, 0x03, 0x04, 0x05
OP_CHUNK, OP_STATISTICS, OP_METADATA, OP_DATA_END = 0x06, 0x0B, 0x0C, 0x0F

_RECORD_HEAD = struct.Struct("<BQ")
_MESSAGE = struct.Struct("<HIQQ")
_CHUNK = struct.Struct("<QQQI")
_STATISTICS = struct.Struct("<QHIIIIQQ")
_U16, _U32, _U64 = struct.Struct("<H"), struct.Struct("<I"), struct.Struct("<Q")


@dataclass(frozen=True)
class Schema:
    id: int
    name: str
    encoding: str
    data: bytes


@dataclass(frozen=True)
class Channel:
    id: int
    schema_id: int
    topic: str
    message_encoding: str
    metadata: dict


@dataclass(frozen=True)
class Statistics:
    """The summary's Statistics record: what the writer counted (absent from a cut file)."""
    message_count: int
    schema_count: int
    channel_count: int
    attachment_count: int
    metadata_count: int
    chunk_count: int
    message_start_time: int
    message_end_time: int
    channel_message_counts: dict  # channel id -> messages


class _Fields:
    """Reads a record body's fields in order; running past the body's end is a format error
    (the record itself is complete, so this is not a cut file)."""

    def __init__(self, body, what):
        self.body, self.pos, self.what = body, 0, what

    def take(self, size):
        if self.pos + size > len(self.body):
            raise RecordingError(f"{self.what} is malformed: a field runs past its end")
        start = self.pos
        self.pos += size
        return start

    def u16(self):
        return _U16.unpack_from(self.body, self.take(2))[0]

    def u32(self):
        return _U32.unpack_from(self.body, self.take(4))[0]

    def u64(self):
        return _U64.unpack_from(self.body, self.take(8))[0]

    def bytes32(self):
        size = self.u32()
        start = self.take(size)
        return bytes(self.body[start:start + size])

    def string(self):
        try:
            return self.bytes32().decode()
        except UnicodeDecodeError as error:
            raise RecordingError(f"{self.what} is malformed: a string is not UTF-8") from error

    def _map(self, read_key, read_value):
        inner = _Fields(self.bytes32(), self.what)
        pairs = {}
        while inner.pos < len(inner.body):
            key = read_key(inner)
            pairs[key] = read_value(inner)
        return pairs

    def string_map(self):
        return self._map(_Fields.string, _Fields.string)

    def count_map(self):
        return self._map(_Fields.u16, _Fields.u64)


class McapReader:
    """Walks an MCAP file's records from the start, the way a streaming reader does, so a file
    cut short by a crash (no summary, no footer, its last record incomplete) reads up to its
    last complete record; `truncated` then turns True.

        reader = McapReader("run.mcap")
        for channel, log_time_ns, publish_time_ns, data in reader.messages():
            ...
        reader.truncated, reader.metadata, reader.channels

    The tables (schemas and channels by id, metadata by name, statistics, profile) fill in as the
    walk passes their records. Chunk CRCs, the data-section CRC and the summary CRC are checked
    when the writer set them (non-zero).
    """

    def __init__(self, path):
        self.path = os.fspath(path)
        self.profile = self.library = None
        self.schemas: dict[int, Schema] = {}
        self.channels: dict[int, Channel] = {}
        self.metadata: dict[str, dict[str, str]] = {}
        self.statistics: Statistics | None = None
        self.truncated = False
        self._zstd = None

    def messages(self):
        """Yields (Channel, log_time_ns, publish_time_ns, data) in file order; data is the
        message's bytes (CDR for comply)."""
        with open(self.path, "rb") as file:
            yield from self._walk(file, os.fstat(file.fileno()).st_size)

    def _walk(self, file, size):
        magic = file.read(len(MAGIC))
        if magic != MAGIC:
            raise RecordingError(f"{self.path} is not an MCAP file: it starts with {magic!r}, "
                                 f"not the MCAP magic {MAGIC!r}")
        offset, crc, summary_start = len(MAGIC), zlib.crc32(magic), None
        while True:
            head = file.read(_RECORD_HEAD.size)
            if len(head) < _RECORD_HEAD.size:
                self.truncated = True  # no footer: the writer never finished
                return
            opcode, length = _RECORD_HEAD.unpack(head)
            # A length past the end of the file is the record the crash cut, not a request to
            # allocate whatever its bytes say.
            body = file.read(length) if length <= size - offset - len(head) else b""
            if len(body) < length:
                self._check_cut(file, size, offset, opcode, length)
                self.truncated = True
                return
            if offset == len(MAGIC) and opcode != OP_HEADER:
                raise RecordingError(f"{self.path} is not an MCAP file: its first record has "
                                     f"opcode 0x{opcode:02x}, not a Header")
            if opcode == OP_FOOTER:
                self._footer(head, body, offset, crc, summary_start)
                self.truncated = file.read(len(MAGIC)) != MAGIC
                return
            if opcode == OP_DATA_END:
                self._check_crc(_Fields(body, self._where("DataEnd", offset)).u32(), crc,
                                f"the data section (DataEnd record at offset {offset})")
                crc, summary_start = 0, offset + len(head) + length
            else:
                crc = zlib.crc32(body, zlib.crc32(head, crc))
            if opcode == OP_MESSAGE:
                yield self._message(body, 0, len(body), offset)
            elif opcode == OP_CHUNK:
                yield from self._chunk(body, offset)
            else:
                self._record(opcode, body, offset)
            offset += len(head) + length

    def _check_cut(self, file, size, offset, opcode, length):
        """A record running past the end is a crash's cut, unless the file still ends with the
        closing magic: then the writer finished it and the record's length is corrupt."""
        file.seek(size - len(MAGIC))
        if size - len(MAGIC) > offset and file.read(len(MAGIC)) == MAGIC:
            raise RecordingError(f"{self.path}: the record at offset {offset} (opcode "
                                 f"0x{opcode:02x}) claims {length} bytes, past the end of a file "
                                 f"that ends with the MCAP magic: the file is corrupt")

    def _where(self, what, offset):
        return f"{self.path}: the {what} record at offset {offset}"

    def _check_crc(self, stored, computed, what):
        if stored != 0 and stored != computed:
            raise RecordingError(f"{self.path}: CRC-32 mismatch in {what}: the file says "
                                 f"0x{stored:08x}, its bytes give 0x{computed:08x}")

    def _footer(self, head, body, offset, crc, summary_start):
        footer = _Fields(body, self._where("Footer", offset))
        start, _, stored = footer.u64(), footer.u64(), footer.u32()
        # The summary CRC runs from the summary's start through the footer's fields before it.
        if start != 0 and start == summary_start:
            computed = zlib.crc32(body[:16], zlib.crc32(head, crc))
            self._check_crc(stored, computed, f"the summary section (Footer at offset {offset})")

    def _record(self, opcode, body, offset):
        """The records other than messages and chunks; unknown opcodes are skipped, as the
        spec asks of readers."""
        if opcode == OP_HEADER:
            fields = _Fields(body, self._where("Header", offset))
            self.profile, self.library = fields.string(), fields.string()
        elif opcode == OP_SCHEMA:
            fields = _Fields(body, self._where("Schema", offset))
            schema = Schema(fields.u16(), fields.string(), fields.string(), fields.bytes32())
            self.schemas.setdefault(schema.id, schema)  # the summary repeats it
        elif opcode == OP_CHANNEL:
            fields = _Fields(body, self._where("Channel", offset))
            channel = Channel(fields.u16(), fields.u16(), fields.string(), fields.string(),
                              fields.string_map())
            self.channels.setdefault(channel.id, channel)
        elif opcode == OP_METADATA:
            fields = _Fields(body, self._where("Metadata", offset))
            name = fields.string()
            self.metadata.setdefault(name, {}).update(fields.string_map())
        elif opcode == OP_STATISTICS:
            self.statistics = self._statistics(body, offset)

    def _statistics(self, body, offset):
        fields = _Fields(body, self._where("Statistics", offset))
        fields.take(_STATISTICS.size)
        return Statistics(*_STATISTICS.unpack_from(body), fields.count_map())

    def _message(self, buf, start, end, offset):
        """The Message record in buf[start:end] (a chunk's records or the record's body)."""
        if end - start < _MESSAGE.size:
            raise RecordingError(f"{self._where('Message', offset)} is malformed: "
                                 f"{end - start} bytes")
        channel_id, _, log_time, publish_time = _MESSAGE.unpack_from(buf, start)
        channel = self.channels.get(channel_id)
        if channel is None:
            raise RecordingError(f"{self._where('Message', offset)} is on channel {channel_id}, "
                                 f"which no Channel record defined before it")
        return channel, log_time, publish_time, bytes(buf[start + _MESSAGE.size:end])

    def _chunk(self, body, offset):
        records = self._chunk_records(body, offset)
        pos = 0
        while pos < len(records):
            if pos + _RECORD_HEAD.size > len(records):
                raise RecordingError(f"{self._where('Chunk', offset)} ends inside a record head")
            opcode, length = _RECORD_HEAD.unpack_from(records, pos)
            start, pos = pos + _RECORD_HEAD.size, pos + _RECORD_HEAD.size + length
            if pos > len(records):
                raise RecordingError(f"{self._where('Chunk', offset)}: a record runs past the "
                                     f"chunk's end")
            if opcode == OP_MESSAGE:
                yield self._message(records, start, pos, offset)
            else:
                self._record(opcode, records[start:pos], offset)

    def _chunk_records(self, body, offset):
        """The chunk's records, decompressed and checked against the chunk's size and CRC."""
        what = self._where("Chunk", offset)
        fields = _Fields(body, what)
        fields.take(_CHUNK.size)
        _, _, uncompressed_size, uncompressed_crc = _CHUNK.unpack_from(body)
        compression = fields.string()
        size = fields.u64()
        start = fields.take(size)
        data = body[start:start + size]
        if compression == "zstd":
            data = self._decompress_zstd(data, uncompressed_size, what)
        elif compression != "":
            raise RecordingError(f"{what} is compressed with {compression!r}; this reader "
                                 f"knows zstd and uncompressed chunks")
        if len(data) != uncompressed_size:
            raise RecordingError(f"{what} holds {len(data)} bytes uncompressed, not the "
                                 f"{uncompressed_size} it declares")
        self._check_crc(uncompressed_crc, zlib.crc32(data), f"the chunk at offset {offset}")
        return data

    def _decompress_zstd(self, data, size, what):
        if self._zstd is None:
            try:
                import zstandard
            except ImportError as error:
                raise RecordingError(f"{what} is zstd-compressed: install the zstandard module "
                                     f"(Debian: python3-zstandard)") from error
            self._zstd = (zstandard.ZstdDecompressor(), zstandard.ZstdError)
        decompressor, zstd_error = self._zstd
        try:
            return decompressor.decompress(data, max_output_size=size)
        except zstd_error as error:
            raise RecordingError(f"{what} does not decompress: {error}") from error
