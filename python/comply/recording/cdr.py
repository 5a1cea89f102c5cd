"""MessageDecoder: the CDR messages (XCDR1, little endian) of one ros2msg type, decoded into
nested dicts or into the per-step values that columns are made of."""

from __future__ import annotations

from .cdr_steps import _FixedRun, _Leaf, _Messages, _Mismatch, _Primitives, _Strings
from .errors import RecordingError
from .ros2msg import _PRIMITIVES, _type_key, parse_ros2msg


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
