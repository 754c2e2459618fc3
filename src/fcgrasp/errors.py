"""Every exception class fcgrasp raises of its own (shapely keeps its in ``errors.py`` too).

All derive from :class:`FcgraspError`, which carries the ``field`` an error is about
(an argument, an option, an input; None when it is about none), and each is also the
built-in exception a caller would expect: a bad argument is an :class:`ArgumentError`
(a :class:`ValueError`) or an :class:`ArgumentTypeError` (a :class:`TypeError`), naming
the argument and the value received; the others are :class:`ValueError` but
:class:`PartTimeout` and :class:`~fcgrasp.core.budget.BudgetExhausted`.

>>> from fcgrasp.core._checks import check_scalar
>>> try:
...     check_scalar(-1.0, "margin", nonnegative=True)
... except FcgraspError as exc:
...     print(exc.field, isinstance(exc, ValueError))
margin True
"""

from __future__ import annotations

from typing import Any

__all__ = ["FcgraspError", "ArgumentError", "ArgumentTypeError", "RequestError",
           "SearchTooLarge", "OutputError", "PartTimeout"]


class FcgraspError(Exception):
    """The base of every exception fcgrasp raises of its own: ``field`` names the
    argument, option or input it is about (None: none in particular)."""

    def __init__(self, message: str = "", field: str | None = None) -> None:
        super().__init__(message)
        self.field = field

    def __reduce__(self) -> tuple[Any, ...]:
        # pickled whole (a batch worker's or the explorer's planning process raises
        # them): the message and the field
        return type(self), (str(self), self.field)


class ArgumentError(FcgraspError, ValueError):
    """An argument with a value out of range, of the wrong shape or not finite
    (``field``: the argument)."""

    def __init__(self, message: str, field: str) -> None:
        super().__init__(message, field)


class ArgumentTypeError(FcgraspError, TypeError):
    """An argument of the wrong type (``field``: the argument)."""

    def __init__(self, message: str, field: str) -> None:
        super().__init__(message, field)


class RequestError(FcgraspError, ValueError):
    """A plan request that does not fit together (options of another gripper, a bad value,
    an output that would overwrite an input): one line for the user, the ``field`` it is
    about and the HTTP ``status`` the explorer answers with."""

    field: str

    def __init__(self, message: str, field: str = "request", status: int = 400) -> None:
        super().__init__(message, field)
        self.status = status

    def __reduce__(self) -> tuple[Any, ...]:
        return type(self), (str(self), self.field, self.status)


class SearchTooLarge(FcgraspError, ValueError):
    """A search that cannot fit its memory budget (raised before any work)."""


class OutputError(FcgraspError, ValueError):
    """An output file could not be written (names the user's path, not the temporary)."""


class PartTimeout(FcgraspError):
    """A part of a batch ran past its deadline."""
