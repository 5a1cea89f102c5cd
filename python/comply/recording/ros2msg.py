"""The ros2msg schema encoding: a schema's .msg text, with the definitions of the types it uses,
parsed into MsgField lists by parse_ros2msg()."""

from __future__ import annotations

import re
from dataclasses import dataclass

from .errors import RecordingError

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
