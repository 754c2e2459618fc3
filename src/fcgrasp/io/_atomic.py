"""Atomic file output: write to a temporary file beside the target, then rename.

:class:`OutputSet` writes the outputs of one run as a set: every file is first written
to a hidden temporary beside its target, and only when all of them succeeded are they
renamed onto their targets, so a failed or interrupted run leaves no partial file and no
JSON without its figure.  Temporaries left by a run that was killed are recognised by
their name and removed the next time the same target is written.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from pathlib import Path

_TAG = ".fcgrasp-tmp-"


class OutputError(ValueError):
    """An output file could not be written (names the user's path, not the temporary)."""


def _stale(target: Path) -> list[Path]:
    try:
        return [p for p in target.parent.glob(f".{target.name}{_TAG}*") if p.is_file()]
    except OSError:
        return []


def _temp_for(target: Path) -> str:
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        for old in _stale(target):          # left behind by a run that was killed
            old.unlink(missing_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}{_TAG}", suffix=target.suffix,
                                   dir=target.parent)
    except OSError as exc:
        raise OutputError(f"{target}: cannot write ({exc.strerror or exc})") from None
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)           # the mode a plain open() would give
    return tmp


class OutputSet:
    """Write several files all or none.

    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> with OutputSet() as out:
    ...     out.add_text(d / "a.txt", "A")
    ...     out.add_text(d / "b.txt", "B")
    >>> sorted(p.name for p in d.iterdir())
    ['a.txt', 'b.txt']
    """

    def __init__(self) -> None:
        self._staged: list[tuple[str, Path]] = []

    def add(self, path: str | os.PathLike[str], writer: Callable[[str], None]) -> None:
        """Call ``writer(tmp_path)`` now; the file reaches ``path`` on :meth:`commit`."""
        target = Path(path)
        tmp = _temp_for(target)
        self._staged.append((tmp, target))
        try:
            writer(tmp)
        except OSError as exc:
            raise OutputError(f"{target}: cannot write ({exc.strerror or exc})") from None

    def add_text(self, path: str | os.PathLike[str], text: str) -> None:
        """Stage ``text`` (UTF-8) for ``path``."""
        def _write(tmp: str) -> None:
            with open(tmp, "w", encoding="utf-8", newline="\n") as fh:
                fh.write(text)
        self.add(path, _write)

    def commit(self) -> None:
        """Rename every staged file onto its target."""
        try:
            for tmp, target in self._staged:
                try:
                    os.replace(tmp, target)
                except OSError as exc:
                    raise OutputError(f"{target}: cannot write ({exc.strerror or exc})") \
                        from None
        finally:
            self.discard()

    def discard(self) -> None:
        """Remove every staged temporary that was not renamed."""
        for tmp, _ in self._staged:
            try:
                os.unlink(tmp)
            except FileNotFoundError:
                pass
        self._staged = []

    def __enter__(self) -> OutputSet:
        return self

    def __exit__(self, exc_type: object, exc: object, tb: object) -> None:
        if exc_type is None:
            self.commit()
        else:
            self.discard()
