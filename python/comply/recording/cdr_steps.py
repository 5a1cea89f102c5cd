"""The steps a ros2msg type compiles into: each reads one value per CDR message and makes its
columns (or its part of a message's dict) from those values."""

from __future__ import annotations

import contextlib
import gc
import struct
from dataclasses import dataclass

import numpy as np

from .ros2msg import _PRIMITIVES

# CDR here is XCDR1, little endian. Alignment counts from the byte after the 4-byte
# encapsulation header, so a primitive of size s sits at a position p with (p - 4) % s == 0. A
# type compiles once into steps, each reading one value per message; consecutive fixed-size
# fields (nested messages flattened into dotted names) make one step whose layout depends only on
# the phase (p - 4) % 8, so a message costs a handful of steps and a column of them is read by
# numpy in one go.


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



_unpack_u32 = struct.Struct("<I").unpack_from
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
