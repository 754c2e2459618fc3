"""Limits on what a reader takes: part of the contract, each with a documented default
and an option that raises it.

A file past a limit is refused before the work it would cause, with one line naming the
limit and the option (:class:`LimitExceeded`, a ValueError): a drawing of a billion
copies (an SVG's nested ``<use>``, a DXF's nested block INSERTs) is counted, not
expanded; an endless stream (``/dev/zero``) is read no further than the limit.

* ``max_bytes``, 256 MiB (``--max-bytes``): bytes of the file (or of standard input);
* ``max_elements``, 20,000 (``--max-elements``): a drawing's elements once its references
  are expanded (SVG shapes and ``<use>`` copies, DXF entities and block INSERTs) and
  its parts (GeoJSON features, SVG shapes, DXF loops);
* ``max_vertices``, 500,000 (``--max-vertices``): vertices of a drawing's outlines (after
  flattening), and a mesh's triangles;
* :data:`MAX_PIXELS`, 100 million (fixed): pixels of an image.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..core._checks import check_int
from ..errors import FcgraspError

__all__ = ["Limits", "LimitExceeded", "DEFAULT_LIMITS", "MAX_PIXELS"]

#: Pixels of an image at most (a decompression bomb is refused before it is decoded).
MAX_PIXELS = 100_000_000


class LimitExceeded(FcgraspError, ValueError):
    """A file past one of the readers' limits (:class:`Limits`); the message names the
    limit and the option that raises it."""


@dataclass(frozen=True)
class Limits:
    """The readers' limits (see the module docstring).

    >>> Limits().max_elements
    20000
    >>> Limits(max_elements=10).elements(11, "elements")
    Traceback (most recent call last):
    ...
    fcgrasp.io.limits.LimitExceeded: elements: more than 10 (--max-elements raises the limit)
    """

    max_bytes: int = 256 * 2 ** 20
    max_elements: int = 20_000
    max_vertices: int = 500_000

    def __post_init__(self) -> None:
        for name in ("max_bytes", "max_elements", "max_vertices"):
            check_int(getattr(self, name), name, minimum=1)

    @staticmethod
    def given(max_bytes: int | None = None, max_elements: int | None = None,
              max_vertices: int | None = None) -> Limits:
        """The limits given, the defaults for those that are None."""
        d = DEFAULT_LIMITS
        return Limits(d.max_bytes if max_bytes is None else max_bytes,
                      d.max_elements if max_elements is None else max_elements,
                      d.max_vertices if max_vertices is None else max_vertices)

    @staticmethod
    def of_options(options: Mapping[str, Any]) -> Limits:
        """:meth:`given` of reading options (``load_part``'s keywords, a request's
        reading): their ``max_bytes``, ``max_elements`` and ``max_vertices``."""
        return Limits.given(options.get("max_bytes"), options.get("max_elements"),
                            options.get("max_vertices"))

    @staticmethod
    def of(value: Any) -> Limits:
        """``value`` as Limits: None gives the defaults."""
        if value is None:
            return DEFAULT_LIMITS
        if not isinstance(value, Limits):
            raise TypeError(f"limits must be a fcgrasp.io.limits.Limits, got "
                            f"{type(value).__name__}")
        return value

    def _over(self, count: int, limit: int, what: str, option: str) -> None:
        if count > limit:
            raise LimitExceeded(f"{what}: more than {limit:,} (--{option} raises the "
                                f"limit)")

    def bytes(self, count: int, what: str) -> None:
        """Refuse more than ``max_bytes``."""
        self._over(count, self.max_bytes, what, "max-bytes")

    def elements(self, count: int, what: str) -> None:
        """Refuse more than ``max_elements``."""
        self._over(count, self.max_elements, what, "max-elements")

    def vertices(self, count: int, what: str) -> None:
        """Refuse more than ``max_vertices``."""
        self._over(count, self.max_vertices, what, "max-vertices")


DEFAULT_LIMITS = Limits()
