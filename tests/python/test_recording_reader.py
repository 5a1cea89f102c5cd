"""comply.read_recording on MCAP files assembled here byte by byte (independent of comply's C++
writer): values through CDR and back, a file cut by a crash, CRC and format errors.
Usage: test_recording_reader.py (with the source's python/ on PYTHONPATH)."""

import os
import struct
import sys
import tempfile
import zlib

import numpy as np

try:
    import zstandard
except ImportError:
    print("skip: the zstandard module is not installed")
    sys.exit(0)

import comply
from comply.recording import MessageDecoder


SCHEMA_NAME = "comply_msgs/msg/TestState"
SEPARATOR = "=" * 80
SCHEMA_TEXT = "\n".join([
    "# A test type: every kind of field the reader decodes.",
    "std_msgs/Header header  # stamp and frame",
    "uint8 STATE_ACTIVE=1",
    'string NOTE="a # b"  # a constant with a hash inside',
    "uint8 state",
    "uint64 cycle",
    "bool passivity",
    "string[] joint_names",
    "float64[] position",
    "float64[] varying  # 0 to 3 elements: aligned to 8 only when there are some",
    "uint8 flag",
    "float64[3] tcp_position",
    "int16[2] pair",
    "Contact[] contacts",
    "Contact[] tool  # one in every message: its fields are columns too",
    "Contact[<=1] maybe  # none or one: a list of lists of dicts only",
    "builtin_interfaces/Time reference_stamp",
    "float32[<=4] bounded",
    "uint8[20] blob",
    "float64 gain_fraction",
    SEPARATOR,
    "MSG: std_msgs/Header",
    "builtin_interfaces/Time stamp",
    "string frame_id",
    SEPARATOR,
    "MSG: builtin_interfaces/Time",
    "int32 sec",
    "uint32 nanosec",
    SEPARATOR,
    "MSG: comply_msgs/Contact",
    "string link",
    "float64[3] force",
    "",
])
JOINTS = [f"joint{k}" for k in range(1, 8)]


# --- CDR (XCDR1, little endian), written by hand for TestState --------------------------------

class CdrWriter:
    def __init__(self):
        self.out = bytearray(b"\x00\x01\x00\x00")

    def align(self, size):
        while (len(self.out) - 4) % size:
            self.out.append(0)

    def put(self, code, value):
        self.align(struct.calcsize(code))
        self.out += struct.pack("<" + code, value)

    def array(self, code, values):
        for value in values:
            self.put(code, value)

    def sequence(self, code, values):
        self.put("I", len(values))
        self.array(code, values)

    def string(self, text):
        raw = text.encode() + b"\0"
        self.put("I", len(raw))
        self.out += raw


def state_values(i):
    """Message i's values, as the reader should give them back."""
    return {
        "header.stamp.sec": 1000 + i, "header.stamp.nanosec": 1000 * i,
        "header.frame_id": "base" if i % 2 else "world",
        "state": i % 3, "cycle": 2**63 + i, "passivity": i % 2 == 0,
        "joint_names": JOINTS, "position": [i + 0.125 * k for k in range(7)],
        "varying": [float(i * 10 + k) for k in range(i % 4)], "flag": 200 + i % 50,
        "tcp_position": [0.5, -0.25 * i, 1e-3 * i], "pair": [-i, i],
        "contacts": [{"link": f"link{k}", "force": [k, 2.0 * k, -3.0]} for k in range(i % 3)],
        "tool": [{"link": f"tool{i % 4}", "force": [0.5 * i, -1.0, i + 0.25]}],
        "maybe": [{"link": "maybe", "force": [i, i, i]}] * (i % 2),
        "reference_stamp.sec": -i, "reference_stamp.nanosec": 7,
        "bounded": [0.5] * (i % 5), "blob": [(i + k) % 256 for k in range(20)],
        "gain_fraction": 1.0 - i / 1000,
    }


def encode_state(v):
    cdr = CdrWriter()
    cdr.put("i", v["header.stamp.sec"])
    cdr.put("I", v["header.stamp.nanosec"])
    cdr.string(v["header.frame_id"])
    cdr.put("B", v["state"])
    cdr.put("Q", v["cycle"])
    cdr.put("?", v["passivity"])
    cdr.put("I", len(v["joint_names"]))
    for name in v["joint_names"]:
        cdr.string(name)
    cdr.sequence("d", v["position"])
    cdr.sequence("d", v["varying"])
    cdr.put("B", v["flag"])
    cdr.array("d", v["tcp_position"])
    cdr.array("h", v["pair"])
    for name in ("contacts", "tool", "maybe"):
        cdr.put("I", len(v[name]))
        for contact in v[name]:
            cdr.string(contact["link"])
            cdr.array("d", contact["force"])
    cdr.put("i", v["reference_stamp.sec"])
    cdr.put("I", v["reference_stamp.nanosec"])
    cdr.sequence("f", v["bounded"])
    cdr.array("B", v["blob"])
    cdr.put("d", v["gain_fraction"])
    return bytes(cdr.out)


# --- MCAP records ------------------------------------------------------------------------------

MAGIC = b"\x89MCAP0\r\n"


def record(opcode, body):
    return struct.pack("<BQ", opcode, len(body)) + body


def mcap_string(text):
    raw = text.encode()
    return struct.pack("<I", len(raw)) + raw


def string_map(pairs):
    body = b"".join(mcap_string(k) + mcap_string(v) for k, v in sorted(pairs.items()))
    return struct.pack("<I", len(body)) + body


def schema_record(schema_id, name, encoding, text):
    data = text.encode()
    return record(0x03, struct.pack("<H", schema_id) + mcap_string(name) + mcap_string(encoding)
                  + struct.pack("<I", len(data)) + data)


def channel_record(channel_id, schema_id, topic):
    return record(0x04, struct.pack("<HH", channel_id, schema_id) + mcap_string(topic)
                  + mcap_string("cdr") + string_map({}))


def message_record(channel_id, sequence, log_time, data):
    return record(0x05, struct.pack("<HIQQ", channel_id, sequence, log_time, log_time) + data)


def chunk_record(messages, compression):
    """messages: (channel id, log time, data); returns the Chunk record."""
    records = b"".join(message_record(c, n, t, d) for n, (c, t, d) in enumerate(messages))
    stored = zstandard.ZstdCompressor().compress(records) if compression == "zstd" else records
    times = [t for _, t, _ in messages]
    return record(0x06, struct.pack("<QQQI", min(times), max(times), len(records),
                                    zlib.crc32(records))
                  + mcap_string(compression) + struct.pack("<Q", len(stored)) + stored)


def message_index_record(channel_id, entries):
    body = b"".join(struct.pack("<QQ", t, offset) for t, offset in entries)
    return record(0x07, struct.pack("<HI", channel_id, len(body)) + body)


def statistics_record(message_count, chunk_count, start, end, counts):
    body = b"".join(struct.pack("<HQ", c, n) for c, n in sorted(counts.items()))
    return record(0x0B, struct.pack("<QHIIIIQQ", message_count, 1, len(counts), 0, 1,
                                    chunk_count, start, end)
                  + struct.pack("<I", len(body)) + body)


class Layout:
    """Offsets in an assembled file, for the tests that cut or corrupt it."""
    chunk_offsets = chunk_ends = ()
    data_end_offset = 0


def assemble(chunks, metadata, channels=((0, "/comply/state"), (1, "/comply/unused")),
             schema_encoding="ros2msg"):
    """A complete file: chunks is a list of (compression, [(channel, log time, data)])."""
    layout = Layout()
    out = bytearray(MAGIC)
    out += record(0x01, mcap_string("ros2") + mcap_string("test"))
    out += schema_record(1, SCHEMA_NAME, schema_encoding, SCHEMA_TEXT)
    for channel_id, topic in channels:
        out += channel_record(channel_id, 1, topic)
    offsets, ends, counts, times = [], [], {}, []
    for compression, messages in chunks:
        offsets.append(len(out))
        out += chunk_record(messages, compression)
        ends.append(len(out))
        for channel_id, log_time, _ in messages:
            counts[channel_id] = counts.get(channel_id, 0) + 1
            times.append(log_time)
        out += message_index_record(0, [])  # the reader has no use for the entries
    layout.chunk_offsets, layout.chunk_ends = offsets, ends
    out += record(0x0C, mcap_string("comply_recording") + string_map(metadata))
    layout.data_end_offset = len(out)
    out += record(0x0F, struct.pack("<I", zlib.crc32(out)))
    summary_start = len(out)
    out += schema_record(1, SCHEMA_NAME, schema_encoding, SCHEMA_TEXT)
    for channel_id, topic in channels:
        out += channel_record(channel_id, 1, topic)
    out += statistics_record(sum(counts.values()), len(chunks), min(times), max(times), counts)
    footer_head = struct.pack("<BQQQ", 0x02, 20, summary_start, 0)
    out += footer_head + struct.pack("<I", zlib.crc32(footer_head, zlib.crc32(out[summary_start:])))
    out += MAGIC
    return bytes(out), layout


def state_chunks(count, split):
    """Messages 0..count-1 on channel 0 (1 ms apart): a zstd chunk up to `split`, then an
    uncompressed one."""
    messages = [(0, 1_000_000 * (i + 1), encode_state(state_values(i))) for i in range(count)]
    return [("zstd", messages[:split]), ("", messages[split:])]


# --- checks ------------------------------------------------------------------------------------

def write(folder, name, data):
    path = os.path.join(folder, name)
    with open(path, "wb") as file:
        file.write(data)
    return path


def expect_error(path, *fragments, **kwargs):
    try:
        comply.read_recording(path, **kwargs)
    except comply.RecordingError as error:
        text = str(error)
        missing = [f for f in fragments if f not in text]
        assert not missing, f"error {text!r} lacks {missing}"
        return text
    raise AssertionError(f"{path} read without an error")


def check_columns(topic, indices):
    expected = [state_values(i) for i in indices]
    n = len(indices)
    assert topic.count == n, topic
    assert topic.log_time.dtype == np.int64
    assert np.array_equal(topic.log_time, [1_000_000 * (i + 1) for i in indices])
    for name in ("header.stamp.sec", "header.stamp.nanosec", "state", "flag",
                 "reference_stamp.sec", "reference_stamp.nanosec", "gain_fraction"):
        assert topic[name].shape == (n,), (name, topic[name].shape)
        assert np.array_equal(topic[name], [v[name] for v in expected]), name
    assert topic["header.stamp.sec"].dtype == np.int32 and topic["state"].dtype == np.uint8
    assert topic["cycle"].dtype == np.uint64
    assert [int(c) for c in topic["cycle"]] == [v["cycle"] for v in expected]  # > 2**63
    assert topic["passivity"].dtype == np.bool_
    assert topic["passivity"].tolist() == [v["passivity"] for v in expected]
    assert topic["header.frame_id"].tolist() == [v["header.frame_id"] for v in expected]
    assert topic["joint_names"].shape == (n, 7)
    assert topic["joint_names"].tolist() == [JOINTS] * n
    for name, shape in (("position", (n, 7)), ("tcp_position", (n, 3)), ("pair", (n, 2)),
                        ("blob", (n, 20))):
        assert topic[name].shape == shape, (name, topic[name].shape)
        assert np.array_equal(topic[name], [v[name] for v in expected]), name
    assert topic["pair"].dtype == np.int16 and topic["blob"].dtype == np.uint8
    topic["position"][0, 0] = 1.0  # columns are the caller's to change
    for name in ("varying", "bounded"):  # lengths vary: one array per message
        assert isinstance(topic[name], list) and len(topic[name]) == n
        for got, v in zip(topic[name], expected):
            assert np.array_equal(got, v[name]), (name, got, v[name])
    assert topic["bounded"][1].dtype == np.float32
    for name in ("contacts", "tool", "maybe"):
        for got, v in zip(topic[name], expected):
            assert [c["link"] for c in got] == [c["link"] for c in v[name]], name
            for c, want in zip(got, v[name]):
                assert np.array_equal(c["force"], want["force"]), name
    check_optional(topic, expected)


def check_optional(topic, expected):
    """A sequence of messages with one element in every message is columns as well."""
    n = len(expected)
    assert topic["tool.link"].shape == (n,)
    assert topic["tool.link"].tolist() == [v["tool"][0]["link"] for v in expected]
    assert topic["tool.force"].shape == (n, 3) and topic["tool.force"].dtype == np.float64
    assert np.array_equal(topic["tool.force"], [v["tool"][0]["force"] for v in expected])
    # "maybe" holds none in some messages and "contacts" two in others: no columns, only the
    # lists of dicts (checked in check_columns).
    assert not any(name.startswith(("maybe.", "contacts.")) for name in topic), list(topic)

def check_complete(folder):
    data, _ = assemble(state_chunks(50, 20), {"records_dropped": "3", "robot": "fr3"})
    rec = comply.read_recording(write(folder, "complete.mcap", data))
    assert not rec.truncated and rec.profile == "ros2"
    assert set(rec) == {"/comply/state", "/comply/unused"}, list(rec)
    check_columns(rec["/comply/state"], range(50))
    assert rec.metadata == {"comply_recording": {"records_dropped": "3", "robot": "fr3"}}
    assert rec.message_counts == {"/comply/state": 50, "/comply/unused": 0}
    assert rec.statistics.message_count == 50 and rec.statistics.chunk_count == 2
    assert rec.statistics.channel_message_counts == {0: 50}
    assert {c.topic for c in rec.channels.values()} == set(rec)
    assert rec.schemas[1].name == SCHEMA_NAME
    unused = rec["/comply/unused"]
    assert unused.count == 0 and unused["position"].shape == (0, 0)
    assert unused["tcp_position"].shape == (0, 3) and unused["state"].shape == (0,)
    assert unused["tool.force"].shape == (0, 3) and unused["tool"] == []
    only = comply.read_recording(rec.path, topics=["/comply/state"])
    assert list(only) == ["/comply/state"] and only.message_counts["/comply/unused"] == 0


def check_decoder():
    decoder = MessageDecoder.from_schema(SCHEMA_NAME, SCHEMA_TEXT)
    assert decoder.fields[:4] == ["header.stamp.sec", "header.stamp.nanosec", "header.frame_id",
                                  "state"], decoder.fields
    v = state_values(5)
    message = decoder.decode(encode_state(v))
    assert message["header"] == {"stamp": {"sec": 1005, "nanosec": 5000}, "frame_id": "base"}
    assert message["cycle"] == 2**63 + 5 and message["passivity"] is False
    assert message["joint_names"] == JOINTS
    assert np.array_equal(message["position"], v["position"])
    assert np.array_equal(message["tcp_position"], v["tcp_position"])
    assert message["contacts"][1]["link"] == "link1"
    assert message["tool"][0]["link"] == "tool1" and message["maybe"][0]["link"] == "maybe"
    assert np.array_equal(message["tool"][0]["force"], v["tool"][0]["force"])
    assert message["reference_stamp"] == {"sec": -5, "nanosec": 7}
    # A type without fields (std_msgs/Empty) is one byte on the wire, as rosidl makes it.
    empty = MessageDecoder.from_schema("test_msgs/msg/Ping", "\n".join([
        "std_msgs/Empty empty", "uint16 id", SEPARATOR, "MSG: std_msgs/Empty", "# nothing"]))
    cdr = CdrWriter()
    cdr.put("B", 0)
    cdr.put("H", 513)
    assert empty.decode(bytes(cdr.out)) == {
        "empty": {"structure_needs_at_least_one_member": 0}, "id": 513}


def check_truncated(folder):
    data, layout = assemble(state_chunks(50, 20), {"records_dropped": "0"})
    cut = (layout.chunk_offsets[1] + layout.data_end_offset) // 2  # inside the last chunk
    rec = comply.read_recording(write(folder, "cut.mcap", data[:cut]))
    assert rec.truncated and rec.statistics is None and rec.metadata == {}
    check_columns(rec["/comply/state"], range(20))
    assert rec.message_counts["/comply/state"] == 20
    # Cut between two records: complete records, but no footer.
    rec = comply.read_recording(write(folder, "cut_clean.mcap", data[:layout.chunk_offsets[1]]))
    assert rec.truncated and rec["/comply/state"].count == 20
    # Everything but the closing magic.
    rec = comply.read_recording(write(folder, "cut_magic.mcap", data[:-4]))
    assert rec.truncated and rec["/comply/state"].count == 50
    rec = comply.read_recording(write(folder, "magic_only.mcap", MAGIC))
    assert rec.truncated and len(rec) == 0


def check_crc_errors(folder):
    data, layout = assemble(state_chunks(10, 4), {})
    corrupt = bytearray(data)
    corrupt[layout.chunk_ends[1] - 10] ^= 0x01  # the last message's last field, uncompressed
    expect_error(write(folder, "bad_chunk.mcap", bytes(corrupt)), "CRC-32 mismatch",
                 f"chunk at offset {layout.chunk_offsets[1]}")
    corrupt = bytearray(data)
    corrupt[layout.data_end_offset + 9] ^= 0x01  # the data section's CRC in DataEnd
    expect_error(write(folder, "bad_data_crc.mcap", bytes(corrupt)), "CRC-32 mismatch",
                 "data section")
    corrupt = bytearray(data)
    corrupt[layout.chunk_ends[0] + 8] = 0x7F  # the message index's length, in a complete file
    expect_error(write(folder, "bad_length.mcap", bytes(corrupt)), "the file is corrupt",
                 f"offset {layout.chunk_ends[0]}")


def check_format_errors(folder):
    expect_error(write(folder, "text.mcap", b"name,value\n1,2\n"), "is not an MCAP file")
    expect_error(write(folder, "empty.mcap", b""), "is not an MCAP file")
    expect_error(write(folder, "no_header.mcap", MAGIC + record(0x0F, bytes(4))),
                 "is not an MCAP file", "not a Header")
    message = encode_state(state_values(3))
    cut_inside_position = message[:message.index(struct.pack("<d", 3.125))]
    data, _ = assemble([("", [(0, 1, message), (2, 2, cut_inside_position)])], {},
                       channels=((0, "/comply/state"), (2, "/comply/bad")))
    text = expect_error(write(folder, "mismatch.mcap", data), "/comply/bad", "field position",
                        SCHEMA_NAME)
    assert "/comply/state" not in text, text
    data, _ = assemble([("", [(0, 1, message)])], {}, schema_encoding="protobuf")
    path = write(folder, "protobuf.mcap", data)
    expect_error(path, "unknown encoding 'protobuf'", "/comply/state")


def main():
    with tempfile.TemporaryDirectory() as folder:
        check_decoder()
        check_complete(folder)
        check_truncated(folder)
        check_crc_errors(folder)
        check_format_errors(folder)
    print("ok")


if __name__ == "__main__":
    main()
