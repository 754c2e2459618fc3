"""The command line's helpers: option values parsed from text, outputs checked and
written as a set, parts read as the options say, progress bars and result tables (part
of :mod:`fcgrasp.apps.cli`)."""

from __future__ import annotations

import sys
from typing import Any

from ..errors import RequestError as CliError

# ----------------------------------------------------------------------------- helpers


def _floats(text: str, n: int, name: str) -> tuple[float, ...]:
    import math

    parts = [t for t in text.replace(" ", "").split(",") if t]
    try:
        vals = tuple(float(t) for t in parts)
    except ValueError:
        raise CliError(f"{name} must be {n} comma-separated numbers, got {text!r}") from None
    if len(vals) != n or not all(math.isfinite(v) for v in vals):
        raise CliError(f"{name} must be {n} comma-separated finite numbers, got {text!r}")
    return vals


_SIZES = {"": 1, "b": 1, "k": 2 ** 10, "kb": 2 ** 10, "m": 2 ** 20, "mb": 2 ** 20,
          "g": 2 ** 30, "gb": 2 ** 30, "t": 2 ** 40, "tb": 2 ** 40}


def _seconds(text: str) -> float:
    """A time limit: seconds >= 0 (0: no limit)."""
    import math

    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not value >= 0 or not math.isfinite(value):
        raise CliError(f"--time-limit must be a number of seconds >= 0 (0: no limit), got "
                       f"{text!r}")
    return value


def _memory(text: str, name: str = "--max-memory") -> int:
    """A memory size: bytes, or a number with K, M, G or T (powers of 1024)."""
    t = text.strip().lower().replace("i", "")
    num = t.rstrip("kmgtb")
    unit = t[len(num):]
    try:
        value = float(num)
    except ValueError:
        value = float("nan")
    if unit not in _SIZES or not value > 0 or value == float("inf"):
        raise CliError(f"{name} must be a size such as 500M or 2G, got {text!r}")
    return int(value * _SIZES[unit])


def _progress(enabled: bool) -> Any:
    if not enabled:
        return None

    def show(done: int, total: int) -> None:
        width = 30
        frac = done / max(total, 1)
        bar = "#" * int(width * frac)
        print(f"\r[{bar:<{width}}] {100 * frac:5.1f}% candidate edge sets", end="",
              file=sys.stderr, flush=True)
        if done >= total:
            print("\r" + " " * (width + 32) + "\r", end="", file=sys.stderr, flush=True)

    return show


def _check_outputs(args: Any, inputs: list[str]) -> None:
    """Validate the output options of ``check`` and ``parts`` before any work: file
    names, the figure's format, and no output that is an input or another output."""
    from ..io.outputs import check_outputs

    if sum(1 for src in inputs if src == "-") > 1:
        raise CliError("only one input can be read from standard input ('-')")
    check_outputs(getattr(args, "json", None), getattr(args, "plot", None), inputs)
    _check_plot(getattr(args, "plot", None))


def _check_plot(plot: str | None) -> None:
    """A figure needs matplotlib (its name is checked with the other outputs)."""
    if plot:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise CliError("--plot needs matplotlib: pip install 'fcgrasp[plot]'") from None


def _reading(args: Any) -> dict[str, Any]:
    """The reading options of the command line, as :func:`fcgrasp.io.parts.list_parts`
    keywords."""
    return {"units": args.units, "file_units": args.file_units, "flatten": args.flatten,
            "layer": args.layer, "gap": args.gap, "pixel_size": args.pixel_size,
            "threshold": args.threshold, "y_down": args.y_down, "clean": not args.no_clean,
            "simplify": args.simplify,
            "max_bytes": None if args.max_bytes is None else _memory(args.max_bytes,
                                                                     "--max-bytes"),
            "max_elements": args.max_elements, "max_vertices": args.max_vertices}


def _load(args: Any, say: Any = "stderr") -> Any:
    """The part asked for; when the file holds several, which one was taken is said with
    ``say`` (default on stderr unless --quiet; None: nowhere)."""
    from ..io.parts import load_part

    part = load_part(args.part, args.select, **_reading(args))
    if say == "stderr":
        say = None if args.quiet else _stderr
    if say is not None:
        for line in part.notices():
            say(line)
    return part


def _json_out(args: Any) -> bool:
    return getattr(args, "json", None) == "-"


def _write_outputs(outputs: list[tuple[str, str]], figure: Any = None) -> None:
    """Write text outputs (``-``: standard output) and an optional figure as a set."""
    from ..io.outputs import OutputSet

    stdout = [text for path, text in outputs if path == "-"]
    with OutputSet() as out:
        for path, text in outputs:
            if path != "-":
                out.add_text(path, text)
        if figure is not None:
            figure(out)
    for text in stdout:
        sys.stdout.write(text)
        sys.stdout.flush()


def _stderr(text: str) -> None:
    print(text, file=sys.stderr)


def _batch_progress(enabled: bool) -> Any:
    if not enabled:
        return None
    import time

    from ..io.report import duration

    t0 = time.perf_counter()

    def show(done: int, total: int) -> None:
        width = 30
        frac = done / max(total, 1)
        el = time.perf_counter() - t0
        rate = done / el if el > 0 else 0.0
        left = (total - done) / rate if rate > 0 else float("nan")
        eta = duration(left) if left == left else "?"
        print(f"\r[{'#' * int(width * frac):<{width}}] {done}/{total} parts, "
              f"{rate:.2f}/s, {eta} left   ", end="", file=sys.stderr, flush=True)
        if done >= total:
            print("", file=sys.stderr)

    return show
