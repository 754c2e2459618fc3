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

from ..errors import OutputError, RequestError

_TAG = ".fcgrasp-tmp-"


def _stale(target: Path) -> list[Path]:
    try:
        return [p for p in target.parent.glob(f".{target.name}{_TAG}*") if p.is_file()]
    except OSError:
        return []


def _temp_for(target: Path) -> str:
    try:
        # no folder is made: an output in a folder that does not exist is an error
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


def same_file(a: str, b: str) -> bool:
    """Whether two paths name one file: the same inode where both exist (through symlinks
    and hard links), else the same resolved path."""
    try:
        if os.path.exists(a) and os.path.exists(b):
            return os.path.samefile(a, b)
    except OSError:
        pass
    return os.path.realpath(a) == os.path.realpath(b)


def refuse_overwriting(outputs: list[tuple[str, str]], inputs: list[str]) -> None:
    """Raise :class:`ValueError` when an output (``(option, path)``; ``-`` is standard
    output) is one of the ``inputs`` (paths; ``-`` and ``demo:`` names are not files) or
    two outputs are one file: a run must never overwrite what it reads."""
    files = [(opt, path) for opt, path in outputs if path != "-"]
    for opt, path in files:
        for src in inputs:
            if not src.startswith("demo:") and src != "-" and same_file(path, src):
                raise ValueError(f"{opt} {path} is an input of this run: refusing to "
                                 f"overwrite it")
    for k, (opt, path) in enumerate(files):
        for opt2, path2 in files[k + 1:]:
            if same_file(path, path2):
                raise ValueError(f"{opt} and {opt2} name the same file {path!r}")


#: Figures a run can write.
FIGURE_SUFFIXES = (".png", ".svg", ".pdf")


def check_outputs(json: str | None, plot: str | None, inputs: list[str]) -> None:
    """Check a run's ``--json`` and ``--plot`` before any work: file names (``-`` is
    standard output, for the JSON only), the figure's format, and no output that is an
    input or the other output.  A :class:`~fcgrasp.errors.RequestError` naming the
    option (its ``field``) otherwise."""
    outs = [(f"--{k}", path) for k, path in (("json", json), ("plot", plot)) if path]
    for opt, path in outs:
        if path == "-" and opt == "--json":
            continue
        if path == "-" or path.endswith(os.sep) or os.path.isdir(path):
            raise RequestError(f"{opt} must be a file name, got {path!r}", opt[2:])
        folder = os.path.dirname(path) or "."
        if not os.path.isdir(folder):
            raise RequestError(f"{opt} {path}: the folder {folder} does not exist", opt[2:])
    try:
        refuse_overwriting(outs, inputs)
    except ValueError as exc:
        raise RequestError(str(exc), str(exc).split()[0][2:]) from None
    if plot and Path(plot).suffix.lower() not in FIGURE_SUFFIXES:
        raise RequestError(f"--plot must end in .png, .svg or .pdf, got {plot!r}", "plot")
