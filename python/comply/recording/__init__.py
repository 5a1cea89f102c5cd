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

The parts stand alone: McapReader (mcap) walks the records in file order and yields the
messages; parse_ros2msg() (ros2msg) reads a schema's .msg text; MessageDecoder (cdr) turns one
CDR message into a dict.
"""

from .cdr import MessageDecoder
from .errors import RecordingError
# MAGIC and the opcodes are imported for comply.recording.MAGIC and .OP_*, which users reach.
from .mcap import (MAGIC, OP_CHANNEL, OP_CHUNK, OP_DATA_END, OP_FOOTER, OP_HEADER, OP_MESSAGE,
                   OP_METADATA, OP_SCHEMA, OP_STATISTICS, Channel, McapReader, Schema, Statistics)
from .read import Recording, Topic, read_recording
from .ros2msg import MsgField, parse_ros2msg

__all__ = ["Channel", "McapReader", "MessageDecoder", "MsgField", "Recording", "RecordingError",
           "Schema", "Statistics", "Topic", "parse_ros2msg", "read_recording"]

# Tracebacks, reprs of the classes and pickles name the module users import these from, not the
# file that defines them.
for _name in __all__:
    globals()[_name].__module__ = __name__
del _name
