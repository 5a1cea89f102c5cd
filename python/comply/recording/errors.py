"""The error every part of the recording reader raises."""


class RecordingError(ValueError):
    """A file that is not a readable comply recording; the message says where and why."""
