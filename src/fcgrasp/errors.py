"""Every exception class fcgrasp raises of its own (shapely keeps its in ``errors.py`` too).

Bad arguments to a library function are plain :class:`ValueError` or :class:`TypeError`
naming the argument and the value received; the classes here are for what a caller may
want to catch by kind.  Each is a :class:`ValueError` but :class:`PartTimeout`.
"""

from __future__ import annotations

__all__ = ["RequestError", "SearchTooLarge", "OutputError", "PartTimeout"]


class RequestError(ValueError):
    """A plan request that does not fit together (options of another gripper, a bad value,
    an output that would overwrite an input): one line for the user, the ``field`` it is
    about and the HTTP ``status`` the explorer answers with."""

    def __init__(self, message: str, field: str = "request", status: int = 400) -> None:
        super().__init__(message)
        self.field = field
        self.status = status


class SearchTooLarge(ValueError):
    """A search that cannot fit its memory budget (raised before any work)."""


class OutputError(ValueError):
    """An output file could not be written (names the user's path, not the temporary)."""


class PartTimeout(Exception):
    """A part of a batch ran past its deadline."""
