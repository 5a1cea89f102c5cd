"""comply's recordings (MCAP, ROS 2 profile) read in pure Python: numpy, and zstandard for
zstd-compressed chunks. Nothing here needs the C++ extension.

read_recording() decodes every message into numpy columns, one Topic per channel:

    import comply
    rec = comply.read_recording("run.mcap")
    state = rec["/comply/state"]                  # a Topic: field name -> column
    state.log_time                                # int64 ns, shape (n,)
    state["position"]                             # float64 (n, dof)
    state["header.stamp.sec"]                     # int32 (n,); nested fields get dotted names
    rec.metadata["comply_recording"]["records_dropped"]
    rec.truncated                                 # the file was cut short (a crash)

Columns: a scalar field is an array of shape (n,); a fixed array T[N] is (n, N); a sequence
T[] is (n, k) when every message holds k elements, else a list of n arrays; strings are numpy
object arrays (a string[] of varying length: a list of lists); a sequence or fixed array of
messages is a list of n lists of dicts, made on first access. When every message holds exactly
one element of such a sequence (the "optional" idiom), the element's fields are columns too,
under dotted names:

    cycle = rec["/comply/cycle"]
    cycle["cartesian_in_force.stiffness_translational"]   # float64 (n, 9)
    cycle["cartesian_in_force"][k][0]["position"]          # the same values, message by message

Messages are in log-time order (stable).

The parts stand alone: McapReader walks the records in file order and yields the messages;
parse_ros2msg() reads a schema's .msg text; MessageDecoder turns one CDR message into a dict.
"""

from __future__ import annotations

import contextlib
import gc
import os
import re
import struct
import zlib
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Channel", "McapReader", "MessageDecoder", "MsgField", "Recording", "RecordingError",
           "Schema", "Statistics", "Topic", "parse_ros2msg", "read_recording"]

MAGIC = b"\x89MCAP0\r\n"

# The opcodes this reader acts on; the others (indexes, attachments, summary offsets) it skips.
OP_HEADER, OP_FOOTER, OP_SCHEMA, OP_CHANNEL, OP_MESSAGE = 0x01, 0x02, 0x03, 0x04, 0x05
OP_CHUNK, OP_STATISTICS, OP_METADATA, OP_DATA_END = 0x06, 0x0B, 0x0C, 0x0F

_RECORD_HEAD = struct.Struct("<BQ")
_MESSAGE = struct.Struct("<HIQQ")
_CHUNK = struct.Struct("<QQQI")
_STATISTICS = struct.Struct("<QHIIIIQQ")
_U16, _U32, _U64 = struct.Struct("<H"), struct.Struct("<I"), struct.Struct("<Q")


class RecordingError(ValueError):
    """A file that is not a readable comply recording; the message says where and why."""


# ------------------------------------------------------------------------------------------------
# MCAP records


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


# ------------------------------------------------------------------------------------------------
# ros2msg definitions

# name -> struct code; ROS 2's char is an unsigned byte, like byte and uint8.
_PRIMITIVES = {
    "bool": "?", "byte": "B", "char": "B", "int8": "b", "uint8": "B", "int16": "h",
    "uint16": "H", "int32": "i", "uint32": "I", "int64": "q", "uint64": "Q", "float32": "f",
    "float64": "d",
}

_FIELD_LINE = re.compile(r"(?P<type>[A-Za-z][\w/]*(?:<=\d+)?)(?P<array>\[(?:<=)?\d*\])?"
                         r"\s+(?P<name>[A-Za-z]\w*)\s*(?P<rest>.*)")
_SEPARATOR = re.compile(r"^=+[ \t]*\r?$", re.MULTILINE)


@dataclass(frozen=True)
class MsgField:
    """One field of a .msg: `type` is a primitive name, "string" or a message "pkg/Type";
    `length` is N for a fixed array T[N]; `sequence` for T[] and T[<=N] (`bound` N)."""
    name: str
    type: str
    length: int | None = None
    sequence: bool = False
    bound: int | None = None

    @property
    def is_message(self):
        return self.type != "string" and self.type not in _PRIMITIVES


def _type_key(name):
    """'pkg/msg/Type' (schema names, rosidl) and 'pkg/Type' (.msg files) name one type."""
    parts = name.split("/")
    if len(parts) == 3 and parts[1] == "msg":
        return f"{parts[0]}/{parts[2]}"
    return name


def _resolve(base, package, where):
    if base in _PRIMITIVES:
        return base
    if base == "string" or base.startswith("string<="):
        return "string"
    if base == "wstring" or base.startswith("wstring<="):
        raise RecordingError(f"{where}: wstring fields are not supported")
    if base == "Header":
        return "std_msgs/Header"
    if "/" not in base:
        return f"{package}/{base}"
    return _type_key(base)


def _parse_field(line, package, where):
    """The field a line declares, or None for a constant (NAME=value)."""
    match = _FIELD_LINE.fullmatch(line)
    if match is None:
        raise RecordingError(f"{where}: cannot read the line {line!r}")
    if match["rest"].startswith("="):
        return None
    kind = _resolve(match["type"], package, where)
    array = match["array"]
    if array is None:
        return MsgField(match["name"], kind)
    digits = array.strip("[]<=")
    if array.startswith("[<="):
        return MsgField(match["name"], kind, sequence=True, bound=int(digits))
    if digits:
        return MsgField(match["name"], kind, length=int(digits))
    return MsgField(match["name"], kind, sequence=True)


def _parse_section(text, package, where):
    fields = []
    for raw in text.splitlines():
        # A default or constant value cut at a '#' inside a string still reads as one, and
        # neither is decoded.
        line = raw.split("#", 1)[0].strip()
        if line:
            parsed = _parse_field(line, package, where)
            if parsed is not None:
                fields.append(parsed)
    return fields


def parse_ros2msg(name, text):
    """The types a ros2msg schema defines: {"pkg/Type": [MsgField, ...]}, the schema's own type
    (named like "comply_msgs/msg/ControllerState") first, then each dependency that follows a
    line of '=' and a line "MSG: pkg/Type"."""
    if isinstance(text, (bytes, bytearray)):
        text = text.decode()
    sections = _SEPARATOR.split(text)
    main = _type_key(name)
    types = {main: _parse_section(sections[0], main.split("/")[0], f"schema {name}")}
    for section in sections[1:]:
        if not section.strip():
            continue
        title, _, body = section.lstrip("\r\n").partition("\n")
        if not title.startswith("MSG:"):
            raise RecordingError(f"schema {name}: a dependency starts with {title!r}, not "
                                 f"'MSG: pkg/Type'")
        key = _type_key(title[4:].strip())
        types[key] = _parse_section(body, key.split("/")[0], f"schema {name}, {key}")
    return types


# ------------------------------------------------------------------------------------------------
# CDR (XCDR1, little endian) decoding
#
# Alignment counts from the byte after the 4-byte encapsulation header, so a primitive of size
# s sits at a position p with (p - 4) % s == 0. A type compiles once into steps, each reading
# one value per message; consecutive fixed-size fields (nested messages flattened into dotted
# names) make one step whose layout depends only on the phase (p - 4) % 8, so a message costs a
# handful of steps and a column of them is read by numpy in one go.


class _Mismatch(Exception):
    """Raised inside decoding; MessageDecoder turns it into a RecordingError naming the field."""

    def __init__(self, field_name, reason):
        super().__init__(field_name, reason)
        self.field_name, self.reason = field_name, reason


def _padded(pos, size):
    return pos + (4 - pos) % size


def _dtype(kind):
    return np.dtype("<" + _PRIMITIVES[kind])


def _path(name):
    """'header.stamp.sec' -> (('header', 'stamp'), 'sec'): where a leaf goes in a dict."""
    *outer, last = name.split(".")
    return tuple(outer), last


def _put(result, path, item):
    outer, last = path
    for key in outer:
        result = result.setdefault(key, {})
    result[last] = item


@dataclass(frozen=True)
class _Leaf:
    name: str
    kind: str
    count: int | None  # None: a scalar; N: a fixed array


class _FixedRun:
    """Consecutive fixed-size primitive fields and fixed arrays of them. A message's value is
    (phase, raw bytes): the dict path unpacks it with a struct, the columns read all messages'
    bytes at once through a numpy record type, both laid out for that phase."""

    def __init__(self, leaves):
        self.leaves = leaves
        self._structs, self._records = zip(*(self._layout(phase) for phase in range(8)))
        self._sizes = [layout.size for layout in self._structs]
        self._plan, at = [], 0  # per leaf: its dict path and where its values are
        for leaf in leaves:
            self._plan.append((_path(leaf.name), at, leaf.count, _dtype(leaf.kind)))
            at += leaf.count or 1

    def _layout(self, phase):
        """The struct and the numpy record type of the run starting at (position - 4) % 8 ==
        phase: the padding before each field depends on it."""
        formats, fields, at = ["<"], {"names": [], "formats": [], "offsets": []}, 0
        for index, leaf in enumerate(self.leaves):
            dtype = _dtype(leaf.kind)
            pad = -(phase + at) % dtype.itemsize
            formats.append("x" * pad + f"{leaf.count or 1}{_PRIMITIVES[leaf.kind]}")
            fields["names"].append(f"f{index}")
            fields["formats"].append(dtype if leaf.count is None else (dtype, (leaf.count,)))
            fields["offsets"].append(at + pad)
            at += pad + dtype.itemsize * (leaf.count or 1)
        return struct.Struct("".join(formats)), np.dtype(dict(fields, itemsize=at))

    def read(self, buf, pos):
        phase = (pos - 4) & 7
        end = pos + self._sizes[phase]
        if end > len(buf):
            raise _Mismatch(self._leaf_past_end(buf, pos), "the message ends inside it")
        return (phase, buf[pos:end]), end

    def _leaf_past_end(self, buf, pos):
        for leaf in self.leaves:
            size = struct.calcsize(_PRIMITIVES[leaf.kind])
            pos = _padded(pos, size) + size * (leaf.count or 1)
            if pos > len(buf):
                return leaf.name
        return self.leaves[-1].name

    def fill(self, value, result):
        """One message's leaves into a dict: Python scalars, arrays for T[N]."""
        phase, raw = value
        values = self._structs[phase].unpack(raw)
        for (outer, last), at, count, dtype in self._plan:
            level = result
            for key in outer:
                level = level.setdefault(key, {})
            level[last] = values[at] if count is None else np.array(values[at:at + count], dtype)

    def columns(self, entries):
        columns = [np.empty((len(entries),) if leaf.count is None else (len(entries), leaf.count),
                            _dtype(leaf.kind)) for leaf in self.leaves]
        phases = {phase for phase, _ in entries}
        for phase in phases:
            # Strings or sequences of varying length before the run shift its phase.
            rows = (slice(None) if len(phases) == 1 else
                    [row for row, (p, _) in enumerate(entries) if p == phase])
            raw = bytearray().join(raw for p, raw in entries if p == phase)
            table = np.frombuffer(raw, self._records[phase])
            for index, column in enumerate(columns):
                column[rows] = table[f"f{index}"]
        return zip((leaf.name for leaf in self.leaves), columns)


_unpack_u32 = _U32.unpack_from
_NO_BOUND = 1 << 32


def _read_count(buf, pos, name, bound=_NO_BOUND):
    """A sequence's element count (a string's byte count), at the next multiple of 4."""
    pos += -pos & 3  # the origin, 4, is a multiple of 4
    if pos + 4 > len(buf):
        raise _Mismatch(name, "the message ends inside its element count")
    count = _unpack_u32(buf, pos)[0]
    if count > bound:
        raise _Mismatch(name, f"{count} elements, more than its bound {bound}")
    return count, pos + 4


class _Primitives:
    """A sequence T[] / T[<=N], or a long fixed array T[N], of a primitive; kept as raw bytes
    until the column (or dict) is made, where numpy reads them in one go."""

    def __init__(self, leaf_name, kind, length=None, bound=None):
        self.name, self.kind, self.length, self.path = leaf_name, kind, length, _path(leaf_name)
        self.bound = _NO_BOUND if bound is None else bound
        self.dtype = _dtype(kind)
        self.size = self.dtype.itemsize

    def read(self, buf, pos):
        count = self.length
        if count is None:
            # _read_count inlined: this runs for most fields of most messages.
            pos += -pos & 3
            if pos + 4 > len(buf):
                raise _Mismatch(self.name, "the message ends inside its element count")
            count = _unpack_u32(buf, pos)[0]
            pos += 4
            if count > self.bound:
                raise _Mismatch(self.name, f"{count} elements, more than its bound {self.bound}")
        if count == 0:
            return b"", pos  # no alignment for no element, as ROS 2's CDR libraries do
        pos += (4 - pos) % self.size
        end = pos + count * self.size
        if end > len(buf):
            raise _Mismatch(self.name, f"{count} elements run past the message's end")
        return buf[pos:end], end

    def fill(self, value, result):
        _put(result, self.path, np.frombuffer(value, self.dtype).copy())

    def columns(self, entries):
        sizes = {len(entry) for entry in entries}
        if len(sizes) > 1:
            yield self.name, [np.frombuffer(entry, self.dtype).copy() for entry in entries]
            return
        width = (sizes.pop() if sizes else (self.length or 0) * self.dtype.itemsize)
        if not entries or width == 0:
            yield self.name, np.empty((len(entries), width // self.dtype.itemsize), self.dtype)
            return
        joined = bytearray().join(entries)  # a bytearray, so the array is writable
        yield self.name, np.frombuffer(joined, self.dtype).reshape(len(entries), -1)


class _Strings:
    """A string, or a fixed array / sequence of strings. Repeated texts (frame ids, joint
    names) share one str object."""

    _MEMO_LIMIT = 4096

    def __init__(self, leaf_name, length=None, sequence=False, bound=None):
        self.name, self.length, self.sequence = leaf_name, length, sequence
        self.path = _path(leaf_name)
        self.bound = _NO_BOUND if bound is None else bound
        self._memo = {}
        self._last = None  # (raw bytes, texts) of the last sequence read

    def _one(self, buf, pos):
        pos += -pos & 3  # _read_count inlined, as in _Primitives.read
        if pos + 4 > len(buf):
            raise _Mismatch(self.name, "the message ends inside a string's length")
        size = _unpack_u32(buf, pos)[0]
        pos += 4
        end = pos + size
        if end > len(buf):
            raise _Mismatch(self.name, f"a string of {size} bytes runs past the message's end")
        if size == 0:
            return "", end
        if buf[end - 1] != 0:
            raise _Mismatch(self.name, "a string without its terminating NUL")
        raw = buf[pos:end - 1]
        text = self._memo.get(raw)
        if text is None:
            try:
                text = raw.decode()
            except UnicodeDecodeError:
                raise _Mismatch(self.name, "a string that is not UTF-8") from None
            if len(self._memo) < self._MEMO_LIMIT:
                self._memo[raw] = text
        return text, end

    def read(self, buf, pos):
        if not self.sequence and self.length is None:
            return self._one(buf, pos)
        if self.length == 0:
            return (), pos
        # The count (or the first string's length) sits at a multiple of 4, and from there the
        # bytes alone decide the texts: joint names, the same in every message, are read once.
        pos += -pos & 3
        if self._last is not None and buf.startswith(self._last[0], pos):
            return self._last[1], pos + len(self._last[0])
        start, count = pos, self.length
        if count is None:
            count, pos = _read_count(buf, pos, self.name, self.bound)
        texts = []
        for _ in range(count):
            text, pos = self._one(buf, pos)
            texts.append(text)
        texts = tuple(texts)
        self._last = (buf[start:pos], texts)
        return texts, pos

    def fill(self, value, result):
        _put(result, self.path, value if isinstance(value, str) else list(value))

    def columns(self, entries):
        if not self.sequence and self.length is None:
            yield self.name, _object_array(entries, (len(entries),))
        elif len({len(entry) for entry in entries}) <= 1:
            width = len(entries[0]) if entries else (self.length or 0)
            yield self.name, _object_array(entries, (len(entries), width))
        else:
            yield self.name, [list(entry) for entry in entries]


def _object_array(entries, shape):
    array = np.empty(shape, dtype=object)
    array[...] = entries
    return array


class _Messages:
    """A sequence or fixed array of a nested message: a message's value is its elements' step
    values. The column under the plain name, a list of n lists of dicts, is made on first
    access: readers mostly want the dotted columns, and the dicts would cost about as much as
    all the rest of a cycle record's decoding. When every message holds exactly one element (the
    "optional" idiom: CycleRecord's cartesian_in_force), the element's fields are also columns
    of their own, under dotted names ("cartesian_in_force.position"); a topic without messages
    has them too, empty."""

    def __init__(self, leaf_name, decoder, length=None, bound=None):
        self.name, self.decoder, self.length = leaf_name, decoder, length
        self.path = _path(leaf_name)
        self.bound = _NO_BOUND if bound is None else bound

    def read(self, buf, pos):
        count = self.length
        if count is None:
            count, pos = _read_count(buf, pos, self.name, self.bound)
        items = []
        read_values = self.decoder.read_values
        for index in range(count):
            try:
                values, pos = read_values(buf, pos)
            except _Mismatch as error:
                raise _Mismatch(f"{self.name}[{index}].{error.field_name}", error.reason) from None
            items.append(values)
        return items, pos

    def dicts(self, value):
        to_dict = self.decoder.to_dict
        return [to_dict(values) for values in value]

    def fill(self, value, result):
        _put(result, self.path, self.dicts(value))

    def columns(self, entries):
        yield self.name, _Deferred(lambda: [self.dicts(entry) for entry in entries])
        if any(len(entry) != 1 for entry in entries):
            return
        steps = self.decoder.steps
        # Each step's values down the messages; none when there are no messages.
        per_step = list(zip(*(entry[0] for entry in entries))) or [()] * len(steps)
        for step, values in zip(steps, per_step):
            for name, column in step.columns(list(values)):
                yield f"{self.name}.{name}", column


class _Deferred:
    """A column made on first access (Topic.__getitem__ replaces it by what it makes)."""

    __slots__ = ("_make",)

    def __init__(self, make):
        self._make = make

    def __call__(self):
        with _collector_paused():
            return self._make()


class MessageDecoder:
    """Decodes the CDR messages of one ros2msg type, compiled once from its definition:

        decoder = MessageDecoder.from_schema("comply_msgs/msg/ControllerState", text)
        decoder.decode(data)   # {"header": {"stamp": {"sec": ..}, ..}, "position": array, ..}

    `fields` lists the flattened field names in order ("header.stamp.sec", ...)."""

    def __init__(self, type_name, types, _compiled=None):
        self.type = _type_key(type_name)
        self._compiled = {} if _compiled is None else _compiled
        self._compiled[self.type] = self
        leaves, self.steps = [], []
        self._flatten(self.type, types, "", leaves, ())
        self._close_run(leaves)
        self.fields = [name for step in self.steps for name in _step_names(step)]

    @classmethod
    def from_schema(cls, name, text):
        return cls(name, parse_ros2msg(name, text))

    def _flatten(self, type_name, types, prefix, leaves, outer):
        if type_name not in types:
            raise RecordingError(f"type {self.type}: {type_name} is used but not defined in "
                                 f"the schema's text")
        if type_name in outer:
            raise RecordingError(f"type {self.type}: {type_name} contains itself")
        if not types[type_name]:
            # rosidl gives a type without fields (std_msgs/Empty) this one byte on the wire.
            leaves.append(_Leaf(prefix + "structure_needs_at_least_one_member", "uint8", None))
        for spec in types[type_name]:
            name = prefix + spec.name
            if spec.type in _PRIMITIVES and not spec.sequence and (spec.length or 1) <= 16:
                leaves.append(_Leaf(name, spec.type, spec.length))
            elif spec.is_message and not spec.sequence and spec.length is None:
                self._flatten(spec.type, types, name + ".", leaves, outer + (type_name,))
            else:
                self._close_run(leaves)
                self.steps.append(self._variable_step(name, spec, types))

    def _variable_step(self, name, spec, types):
        if spec.type in _PRIMITIVES:
            return _Primitives(name, spec.type, spec.length, spec.bound)
        if spec.type == "string":
            return _Strings(name, spec.length, spec.sequence, spec.bound)
        decoder = self._compiled.get(spec.type)
        if decoder is None:
            decoder = MessageDecoder(spec.type, types, self._compiled)
        return _Messages(name, decoder, spec.length, spec.bound)

    def _close_run(self, leaves):
        if leaves:
            self.steps.append(_FixedRun(list(leaves)))
            leaves.clear()

    def read_values(self, buf, pos):
        """One value per step, from `pos` in a CDR buffer; returns (values, end)."""
        values = []
        for step in self.steps:
            value, pos = step.read(buf, pos)
            values.append(value)
        return values, pos

    def read_dict(self, buf, pos):
        values, pos = self.read_values(buf, pos)
        return self.to_dict(values), pos

    def to_dict(self, values):
        result = {}
        for step, value in zip(self.steps, values):
            step.fill(value, result)
        return result

    def decode(self, data):
        """One CDR message (with its encapsulation header) as a nested dict."""
        values = self.decode_values(data)
        return self.to_dict(values)

    def decode_values(self, data):
        """One CDR message as one value per step (the columns' raw material)."""
        data = bytes(data)  # string texts are memoized by their (hashable) bytes
        _check_encapsulation(data)
        try:
            values, end = self.read_values(data, 4)
        except _Mismatch as error:
            raise RecordingError(f"a {self.type} message does not match its schema: field "
                                 f"{error.field_name}: {error.reason}") from None
        _check_rest(data, end, self.type)
        return values


def _step_names(step):
    if isinstance(step, _FixedRun):
        return [leaf.name for leaf in step.leaves]
    return [step.name]


def _check_encapsulation(data):
    if len(data) < 4 or data[0] != 0 or data[1] != 1:
        raise RecordingError(f"a message starts with {bytes(data[:4])!r}, not the little-endian "
                             f"CDR header 00 01 00 00")


def _check_rest(data, end, type_name):
    # Writers pad a message to a multiple of 4 bytes; more left over is a field the schema lacks.
    if len(data) - end > 3:
        raise RecordingError(f"a {type_name} message does not match its schema: "
                             f"{len(data) - end} bytes follow its last field")


# ------------------------------------------------------------------------------------------------
# Recordings


class Topic(Mapping):
    """The messages of one channel as columns: topic[field] for the flattened field names
    ("header.stamp.sec"), plus log_time and publish_time (int64 ns) and count."""

    def __init__(self, channel, schema, log_time, publish_time, columns):
        self.name, self.channel, self.schema = channel.topic, channel, schema
        self.log_time, self.publish_time, self._columns = log_time, publish_time, columns

    @property
    def count(self):
        return len(self.log_time)

    def __getitem__(self, name):
        try:
            column = self._columns[name]
        except KeyError:
            raise KeyError(f"{name!r}: topic {self.name} has the fields "
                           f"{', '.join(self._columns)}") from None
        if type(column) is _Deferred:
            column = self._columns[name] = column()
        return column

    def __iter__(self):
        return iter(self._columns)

    def __len__(self):
        return len(self._columns)

    def __repr__(self):
        return f"<Topic {self.name}: {self.count} messages of {self.schema.name}>"


@dataclass
class Recording(Mapping):
    """A recording read whole: recording[topic] is a Topic. `metadata` maps each Metadata
    record's name to its strings; `channels` and `schemas` are the file's tables by id;
    `message_counts` counts the messages read per topic (all topics, decoded or not);
    `statistics` is the writer's own count (None when the file was cut before its summary);
    `truncated` says the file was cut short (no footer)."""
    path: str
    profile: str | None
    library: str | None
    topics: dict = field(default_factory=dict)
    channels: dict = field(default_factory=dict)
    schemas: dict = field(default_factory=dict)
    metadata: dict = field(default_factory=dict)
    message_counts: dict = field(default_factory=dict)
    statistics: Statistics | None = None
    truncated: bool = False

    def __getitem__(self, topic):
        try:
            return self.topics[topic]
        except KeyError:
            raise KeyError(f"{topic!r}: {self.path} has the topics "
                           f"{', '.join(self.topics) or 'none'}") from None

    def __iter__(self):
        return iter(self.topics)

    def __len__(self):
        return len(self.topics)

    def __repr__(self):
        cut = ", truncated" if self.truncated else ""
        return f"<Recording {self.path}: {len(self.topics)} topics{cut}>"


class _TopicBuilder:
    """Collects one topic's decoded steps message by message; columns are made at the end."""

    def __init__(self, path, channel, schema, decoder):
        self.path, self.channel, self.schema, self.decoder = path, channel, schema, decoder
        self.entries = [[] for _ in decoder.steps]
        self.log_times, self.publish_times = [], []
        self._steps = list(zip(decoder.steps, [entries.append for entries in self.entries]))

    def add(self, log_time, publish_time, data):
        try:
            _check_encapsulation(data)
            pos = 4
            for step, append in self._steps:
                value, pos = step.read(data, pos)
                append(value)
            _check_rest(data, pos, self.decoder.type)
        except _Mismatch as error:
            raise self._error(log_time, f"field {error.field_name}: {error.reason}") from None
        except RecordingError as error:
            raise self._error(log_time, str(error)) from None
        self.log_times.append(log_time)
        self.publish_times.append(publish_time)

    def _error(self, log_time, reason):
        return RecordingError(f"{self.path}: a message on {self.channel.topic} (log time "
                              f"{log_time} ns) does not match its schema {self.schema.name}: "
                              f"{reason}")

    def topic(self):
        log_time, publish_time = self._times(self.log_times), self._times(self.publish_times)
        order = None
        if np.any(np.diff(log_time) < 0):
            order = np.argsort(log_time, kind="stable")
            log_time, publish_time = log_time[order], publish_time[order]
        columns = {}
        for step, entries in zip(self.decoder.steps, self.entries):
            if order is not None:
                entries = [entries[i] for i in order]
            columns.update(step.columns(entries))
        return Topic(self.channel, self.schema, log_time, publish_time, columns)

    def _times(self, times):
        # MCAP times are uint64, but one past 2**63 ns (the year 2262) is no clock's reading.
        try:
            return np.array(times, dtype=np.int64)
        except OverflowError:
            raise RecordingError(f"{self.path}: topic {self.channel.topic} has a message time "
                                 f"of {max(times)} ns, past the int64 range") from None


def _decoder_for(path, channel, schemas, decoders):
    """The channel's decoder, made once per schema; a channel that is not ros2msg + CDR is an
    error (read_recording's `topics` leaves it out)."""
    schema = schemas.get(channel.schema_id)
    if schema is None:
        raise RecordingError(f"{path}: topic {channel.topic} has schema id {channel.schema_id}, "
                             f"which no Schema record defines")
    if schema.encoding != "ros2msg":
        raise RecordingError(f"{path}: topic {channel.topic}: schema {schema.name} has the "
                             f"unknown encoding {schema.encoding!r} (this reader knows ros2msg)")
    if channel.message_encoding != "cdr":
        raise RecordingError(f"{path}: topic {channel.topic} has message encoding "
                             f"{channel.message_encoding!r} (this reader knows cdr)")
    if schema.id not in decoders:
        try:
            decoders[schema.id] = MessageDecoder.from_schema(schema.name, schema.data)
        except (RecordingError, UnicodeDecodeError) as error:
            raise RecordingError(f"{path}: topic {channel.topic}: {error}") from None
    return schema, decoders[schema.id]


_UNSEEN = object()  # a channel whose first message is still to come


@contextlib.contextmanager
def _collector_paused():
    """Decoding makes millions of small tuples, lists and dicts, none in a reference cycle; the
    cyclic collector's passes over them would cost about a fifth of the time."""
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was_enabled:
            gc.enable()


def read_recording(path, topics=None):
    """Reads a comply recording (MCAP, ros2msg schemas, CDR messages) into a Recording of numpy
    columns per topic. `topics` (names) limits the decoding to those; the others are only
    counted. A file cut short reads up to its last complete record (truncated=True)."""
    with _collector_paused():
        return _read_recording(McapReader(path), None if topics is None else set(topics))


def _read_recording(reader, wanted):
    builders, by_topic, decoders, counts = {}, {}, {}, {}

    def builder_for(channel):
        if wanted is not None and channel.topic not in wanted:
            return None
        builder = by_topic.get(channel.topic)
        if builder is not None and builder.channel.schema_id != channel.schema_id:
            raise RecordingError(f"{reader.path}: topic {channel.topic} has channels of two "
                                 f"schemas ({builder.channel.schema_id}, {channel.schema_id})")
        if builder is None:
            schema, decoder = _decoder_for(reader.path, channel, reader.schemas, decoders)
            builder = by_topic[channel.topic] = _TopicBuilder(reader.path, channel, schema,
                                                              decoder)
        return builder

    for channel, log_time, publish_time, data in reader.messages():
        counts[channel.topic] = counts.get(channel.topic, 0) + 1
        builder = builders.get(channel.id, _UNSEEN)
        if builder is _UNSEEN:
            builder = builders[channel.id] = builder_for(channel)
        if builder is not None:
            builder.add(log_time, publish_time, data)

    for channel in reader.channels.values():  # topics without messages get empty columns
        counts.setdefault(channel.topic, 0)
        if channel.id not in builders:
            builders[channel.id] = builder_for(channel)
    missing = sorted(wanted - by_topic.keys()) if wanted is not None else []
    if missing:
        raise RecordingError(f"{reader.path} has no topic {', '.join(missing)} (its topics: "
                             f"{', '.join(sorted(counts)) or 'none'})")
    return Recording(path=reader.path, profile=reader.profile, library=reader.library,
                     topics={name: builder.topic() for name, builder in by_topic.items()},
                     channels=dict(reader.channels), schemas=dict(reader.schemas),
                     metadata=reader.metadata, message_counts=counts,
                     statistics=reader.statistics, truncated=reader.truncated)
