"""Planning a catalogue of parts: ``fcgrasp batch`` and :func:`plan_many`.

Every part is planned by :func:`fcgrasp.planning.plan_document` on a
:class:`~fcgrasp.planning.PlanRequest` (the function and the request behind ``fcgrasp
plan``), so a batch's results are exactly what ``plan --json`` gives.

* **Local** (default): a pool of worker processes, one per core unless ``workers`` says
  otherwise, nothing to install beyond fcgrasp.  Each part runs under a deadline
  (``part_timeout``): a worker past it, or one that dies (out of memory, a crash), is
  killed and replaced, and the part is recorded with its error.
* **Dask** (``fcgrasp[distributed]``): ``client`` (a ``distributed.Client``), or on the
  command line ``--scheduler tcp://HOST:PORT`` for an existing cluster and ``--scheduler
  local`` for a ``LocalCluster`` on this machine.  Small parts are sent in groups of
  :data:`GROUP_SIZE` (one task each group); a large part is planned on the client with
  its candidate batches solved across the workers (``plan(..., map=...)``: the public
  candidates -> solve -> rank pipeline; the single-edge searches split, the two-finger
  stretch search and three fingers with friction run whole).  On a cluster the deadline
  is cooperative: it is checked between candidate batches of the search.
* **Nothing lost, nothing done twice**: :func:`run_batch` appends each result to a JSON
  Lines file as it finishes (written, flushed and synced line by line), and skips the
  parts whose path, content hash and parameters already have a line, so a batch that was
  interrupted finishes the rest when run again; a torn last line (a kill while
  writing) is cut off first.

A result is a dict: ``path``, ``hash`` (SHA-256 of the file's bytes, or of the polygon's
coordinates), ``parameters`` (the request's options,
:meth:`~fcgrasp.planning.PlanRequest.options`), ``grasps``, ``reason``, ``complete``
and, for a search that stopped early, ``gap`` (as in ``plan --json``), ``units``,
``seconds`` and ``error`` (None, or one line).
"""

from __future__ import annotations

import glob
import hashlib
import json
import os
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

from ._batch_workers import (
    GROUP_SIZE,
    LARGE_EDGES,
    SMALL_PART_BYTES,
    _dask,
    _local,
    _Task,
    cluster,
)

__all__ = ["plan_many", "run_batch", "part_files", "BatchSummary", "cluster",
           "GROUP_SIZE", "SMALL_PART_BYTES", "LARGE_EDGES"]

def part_files(pattern: str, outputs: tuple[str | None, str | None] = (None, None)
               ) -> list[str]:
    """The part files of a folder and its subfolders, or of a glob pattern: every file of
    a format fcgrasp reads (by its extension: a README or a table beside the parts is
    not a part), hidden files and folders left out, sorted.  ``outputs``: a batch's
    results file and figures folder, never read as parts (:func:`is_output`)."""
    found = _part_files(pattern)
    out, figures = outputs
    return [p for p in found if out is None or not is_output(p, out, figures)]


def is_output(path: str, out: str, figures: str | None) -> bool:
    """Whether a part file found for a batch is one of its outputs: the results file of
    an earlier run (a part named as the results file is still a part, and the batch
    refuses to overwrite it), or a file inside the figures folder."""
    if os.path.exists(out) and os.path.samefile(path, out):
        return is_results_file(out)
    if figures is None:
        return False
    folder = os.path.realpath(figures)
    return os.path.commonpath([os.path.realpath(path), folder]) == folder


def _part_files(pattern: str) -> list[str]:
    """:func:`part_files` without the outputs left out."""
    from ..io.meshes import MESH_SUFFIXES
    from ..io.parts import FORMATS

    def is_part(path: str) -> bool:
        name = os.path.basename(path)
        suffix = os.path.splitext(name)[1].lower()
        return (not name.startswith(".") and (suffix in FORMATS or suffix in MESH_SUFFIXES)
                and os.path.isfile(path))

    if os.path.isdir(pattern):
        found = []
        for root, dirs, names in os.walk(pattern):
            dirs[:] = sorted(d for d in dirs if not d.startswith("."))
            found += [os.path.join(root, n) for n in names if is_part(os.path.join(root, n))]
        return sorted(found)
    return sorted(p for p in glob.glob(pattern, recursive=True) if is_part(p))


def _content_hash(item: Any) -> str:
    from ..model.polygon import Polygon

    h = hashlib.sha256()
    if isinstance(item, Polygon):
        h.update(b"polygon")
        for ring in (item.vertices, *item.holes):
            h.update(ring.astype("<f8").tobytes())
            h.update(b"|")
        return h.hexdigest()
    name = str(item)
    if name.startswith("demo:"):
        h.update(name.encode())
        return h.hexdigest()
    if os.path.exists(name) and not os.path.isfile(name):
        # a pipe or a device has no content to hash (reading it may never end): keyed
        # by its path, it is read only by its part's worker, under its timeout
        h.update(b"special:" + name.encode())
        return h.hexdigest()
    with open(name, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


# ----------------------------------------------------------------------------- API


def _tasks(parts: Iterable[Any], options: dict[str, Any], part_timeout: float | None,
           figures: str | None) -> list[_Task]:
    from ..model.polygon import Polygon
    from ..planning import template_request

    template = template_request(options)
    parameters = template.options()
    out = []
    for k, item in enumerate(parts):
        if isinstance(item, Polygon):
            path = f"polygon:{k}"
        elif isinstance(item, (str, os.PathLike)):
            path = os.fspath(item)
        else:
            raise TypeError(f"parts must hold paths or Polygons, got {type(item).__name__}")
        refused = ""
        if isinstance(item, Polygon):
            request = template
        else:
            # a mesh among drawings is planned by the batch's gripper as it plans solids
            # (two fingers as soft fingers), a drawing among meshes as it plans drawings
            try:
                request = template.replace(part=path)
            except ValueError as exc:
                request, refused = template, str(exc)
        out.append(_Task(k, path, item if isinstance(item, Polygon) else path, request,
                         part_timeout, figures, parameters=parameters, refused=refused))
    return out


def _digest(task: _Task) -> str:
    try:
        return _content_hash(task.item)
    except OSError:
        # an unreadable file: keyed by its path, so that a fixed file is planned again
        return "unreadable:" + hashlib.sha256(task.path.encode()).hexdigest()


def plan_many(parts: Iterable[Any], *, workers: int | None = None, client: Any = None,
              part_timeout: float | None = None, figures: str | None = None,
              **options: Any) -> Iterator[dict[str, Any]]:
    """Plan many parts, yielding each part's result as it finishes (see the module's
    docstring for what a result holds).

    ``parts``: paths (any format ``fcgrasp plan`` reads, or ``demo:NAME``) or
    :class:`~fcgrasp.Polygon` objects; ``options``: the options of ``fcgrasp plan`` as
    keywords, typed as :class:`~fcgrasp.planning.PlanRequest` takes them (``fingers=3,
    mu=0.5, top=5``, ``stroke=(10, 50)``); ``workers``: local
    worker processes (default: every core); ``client``: a ``distributed.Client`` to run
    on instead; ``part_timeout``: seconds per part; ``figures``: a folder for a figure
    of each part.

    >>> from fcgrasp.io.parts import demo_part
    >>> [r["grasps"][0]["edges"] for r in plan_many([demo_part("quad")], fingers=2, top=1,
    ...                                             workers=1)]
    [[0, 2]]
    """
    yield from _run(_prepared(parts, options, part_timeout, figures), workers, client)


def _prepared(parts: Iterable[Any], options: dict[str, Any], part_timeout: float | None,
              figures: str | None) -> list[_Task]:
    """The tasks of the parts, each with its content hash (the options parsed once)."""
    if "top" in options and options["top"] is None:
        raise ValueError("top=None (every plan) is not planned in a batch, as in fcgrasp "
                         "plan: give a number of plans, got top=None")
    tasks = _tasks(parts, options, part_timeout, figures)
    if figures:
        os.makedirs(figures, exist_ok=True)
    for t in tasks:
        t.digest = _digest(t)
    return tasks


def _run(tasks: list[_Task], workers: int | None, client: Any
         ) -> Iterator[dict[str, Any]]:
    if not tasks:
        return
    if client is not None:
        yield from _dask(tasks, client)
    else:
        yield from _local(tasks, workers or os.cpu_count() or 1)


@dataclass
class BatchSummary:
    """What a batch did: parts ``planned``, ``skipped`` (already in the results),
    ``failed`` (among the planned) and ``failed_before`` (among the skipped: their
    recorded result is an error), and the seconds each planned part took."""

    planned: int = 0
    skipped: int = 0
    failed: int = 0
    failed_before: int = 0
    seconds: list[float] = field(default_factory=list)

    def table(self) -> str:
        """A small table of the counts and the time per part."""
        import statistics

        per = (f"{statistics.mean(self.seconds):.3g} s mean, "
               f"{statistics.median(self.seconds):.3g} s median, "
               f"{max(self.seconds):.3g} s max") if self.seconds else "-"
        rows = [("planned", str(self.planned)), ("skipped (done before)", str(self.skipped)),
                ("failed", str(self.failed)), ("failed before (skipped)",
                                               str(self.failed_before)),
                ("time per part", per)]
        return "\n".join(f"{k:<24} {v}" for k, v in rows)


def is_results_file(path: str) -> bool:
    """Whether a file is a batch's results (its first line a result: ``path``, ``hash``
    and ``parameters``), read no further than its first 64 KiB."""
    try:
        with open(path, "rb") as f:
            first = f.read(65536).split(b"\n", 1)[0]
        r = json.loads(first)
    except (OSError, ValueError):
        return False
    return isinstance(r, dict) and {"path", "hash", "parameters"} <= set(r)


def _key(path: Any, digest: Any, parameters: Any) -> tuple[str, str, str]:
    """What makes a result the result of a task: the part's path, its content and the
    parameters (two identical files are two parts, each with its own line)."""
    return (str(path), str(digest), json.dumps(parameters, sort_keys=True))


def _done(out: str, retry_failed: bool = False) -> dict[tuple[str, str, str], bool]:
    """The (path, hash, parameters) already in a results file, each with whether its result is
    an error.  A torn last line (a kill while writing) is cut off; with
    ``retry_failed`` the failed results are removed (the file rewritten atomically)."""
    if not os.path.exists(out):
        return {}
    with open(out, "rb+") as f:
        data = f.read()
        end = data.rfind(b"\n") + 1
        if end < len(data):                 # a line cut short by a kill: drop it
            f.truncate(end)
            data = data[:end]
    done: dict[tuple[str, str, str], bool] = {}
    kept = []
    for line in data.splitlines(keepends=True):
        try:
            r = json.loads(line)
        except ValueError:
            continue
        if retry_failed and r.get("error") is not None:
            continue
        kept.append(line)
        done[_key(r.get("path"), r.get("hash"), r.get("parameters"))] = \
            r.get("error") is not None
    if retry_failed and len(kept) < len(data.splitlines()):
        from ..io.outputs import OutputSet

        with OutputSet() as files:
            files.add_text(out, b"".join(kept).decode())
    return done


def run_batch(parts: list[Any], out: str, *, workers: int | None = None,
              client: Any = None, part_timeout: float | None = None,
              figures: str | None = None, progress: Any = None, retry_failed: bool = False,
              **options: Any) -> BatchSummary:
    """Plan ``parts`` into the JSON Lines file ``out``: results appended as they finish
    (each line written whole, flushed and synced), the parts already there with the same
    path, content and parameters skipped (with ``retry_failed``, those whose result is an error
    are planned again, their old line removed).  ``progress(done, total)`` is called as
    parts finish.  Returns a :class:`BatchSummary`.  ``out`` must not be one of the parts
    (a ValueError, through symlinks and hard links too: results never overwrite a part)."""
    from ..io.outputs import refuse_overwriting

    refuse_overwriting([("out", os.fspath(out))],
                       [os.fspath(p) for p in parts if isinstance(p, (str, os.PathLike))])
    done = _done(out, retry_failed)
    todo, summary = [], BatchSummary()
    for task in _prepared(parts, options, part_timeout, figures):
        key = _key(task.path, task.digest, task.parameters)
        if key in done:
            summary.skipped += 1
            summary.failed_before += done[key]
        else:
            todo.append(task)
    total = len(todo)
    if progress is not None:
        progress(0, total)
    with open(out, "ab") as f:
        for k, r in enumerate(_run(todo, workers, client)):
            line = json.dumps(r, sort_keys=True, allow_nan=False).encode() + b"\n"
            f.write(line)
            f.flush()
            os.fsync(f.fileno())
            summary.planned += 1
            summary.failed += r["error"] is not None
            summary.seconds.append(r["seconds"])
            if progress is not None:
                progress(k + 1, total)
    return summary
