"""read_recording(): a whole recording decoded into a Recording, one Topic of numpy columns per
channel."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from .cdr import MessageDecoder, _check_encapsulation, _check_rest
from .cdr_steps import _collector_paused, _Deferred, _Mismatch
from .errors import RecordingError
from .mcap import McapReader, Statistics


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
