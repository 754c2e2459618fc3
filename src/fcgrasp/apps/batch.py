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
import time
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

from ..errors import PartTimeout

__all__ = ["plan_many", "run_batch", "part_files", "BatchSummary", "cluster",
           "GROUP_SIZE", "SMALL_PART_BYTES", "LARGE_EDGES"]

#: Parts smaller than this (bytes of their file) are sent to a cluster in groups.
SMALL_PART_BYTES = 200_000
#: How many small parts make one cluster task.
GROUP_SIZE = 8
#: Polygons with this many edges are split across a cluster's workers.
LARGE_EDGES = 500

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


@dataclass
class _Task:
    index: int
    path: str
    item: Any            # a path, or a Polygon
    request: Any         # the PlanRequest of this part
    deadline: float | None
    figures: str | None
    digest: str = ""
    parameters: dict[str, Any] = field(default_factory=dict)
    refused: str = ""    # why this part's request cannot be planned (a mesh with a jaw...)


def _plan_one(task: _Task, map: Any = None) -> dict[str, Any]:
    """Plan one part (in a worker, or with ``map`` on the client of a cluster that solves
    its candidate batches); every failure becomes the result's error."""
    t0 = time.perf_counter()
    out: dict[str, Any] = {"path": task.path, "hash": task.digest,
                           "parameters": task.parameters, "grasps": None, "reason": None,
                           "units": None, "seconds": 0.0, "error": None}
    try:
        from ..io.parts import Part
        from ..model.polygon import Polygon
        from ..planning import plan_document

        if task.refused:
            raise ValueError(task.refused)
        part = None
        if isinstance(task.item, Polygon):
            part = Part(task.item, task.path, "polygon", units=task.request.units or "mm")
        limit = None if task.deadline is None else t0 + task.deadline

        def progress(done: int, total: int) -> None:
            if limit is not None and time.perf_counter() > limit:
                raise PartTimeout(f"part timeout: more than {task.deadline:g} s")

        doc = plan_document(task.request, part=part, progress=progress, map=map)
        out["grasps"] = doc.report["grasps"]
        out["reason"] = doc.report["reason"]
        out["complete"] = doc.report.get("complete", True)
        if "gap" in doc.report:
            out["gap"] = doc.report["gap"]
        out["units"] = doc.units
        if task.figures:
            from ..plotting import document_figure

            stem = os.path.splitext(os.path.basename(task.path))[0] or "part"
            document_figure(doc, os.path.join(task.figures, f"{task.index:05d}-{stem}.png"))
    except Exception as exc:  # noqa: BLE001 - a part's failure is its result
        msg = " ".join(str(exc).split()) or type(exc).__name__
        out["error"] = msg if isinstance(exc, (ValueError, PartTimeout)) else \
            f"{type(exc).__name__}: {msg}"
    out["seconds"] = time.perf_counter() - t0
    return out


#: Seconds a part on a cluster may run past its ``part_timeout`` (the planner's own
#: check ends a plan first) before it is recorded as timed out and its group goes on.
TIMEOUT_GRACE = 5.0


def _plan_group(tasks: list[_Task]) -> list[dict[str, Any]]:
    """Plan a cluster task's parts one after the other; a part with a timeout in a
    thread of its own, given up once it runs past its timeout and :data:`TIMEOUT_GRACE`
    (a read that never ends, of a pipe, has no check of its own): it is recorded as
    timed out and the group's other parts are planned."""
    import threading

    out = []
    for t in tasks:
        if t.deadline is None:
            out.append(_plan_one(t))
            continue
        got: list[dict[str, Any]] = []
        t0 = time.perf_counter()
        worker = threading.Thread(target=lambda t=t, got=got: got.append(_plan_one(t)),
                                  daemon=True, name="fcgrasp-part")
        worker.start()
        worker.join(t.deadline + TIMEOUT_GRACE)
        out.append(got[0] if got else _failed(
            t, f"part timeout: more than {t.deadline:g} s", time.perf_counter() - t0))
    return out


# ----------------------------------------------------------------------------- local pool


def _die_with(parent: int) -> None:
    """End this worker when the process ``parent`` dies, even killed with SIGKILL while
    this worker plans: on Linux the kernel sends SIGKILL (``PR_SET_PDEATHSIG``); anywhere,
    a daemon thread checks the parent every half second."""
    import threading

    try:
        import ctypes
        import signal

        ctypes.CDLL(None, use_errno=True).prctl(1, int(signal.SIGKILL))   # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass

    def watch() -> None:
        while True:
            if os.getppid() != parent:
                os._exit(1)
            time.sleep(0.5)

    threading.Thread(target=watch, daemon=True, name="fcgrasp-parent-watch").start()


def _worker(conn: Any, parent: int | None = None) -> None:
    """A local worker: plans the tasks it receives until it receives None; it dies with
    its ``parent`` (the batch's process).  Ctrl-C is the parent's to handle (a terminal
    sends it to every process of the group): a worker ignores it and is stopped by it."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if parent is not None:
        _die_with(parent)
    while True:
        try:
            task = conn.recv()
        except EOFError:
            return
        if task is None:
            return
        conn.send(_plan_one(task))


class _Slot:
    def __init__(self, ctx: Any) -> None:
        parent, child = ctx.Pipe()
        self.conn = parent
        self.proc = ctx.Process(target=_worker, args=(child, os.getpid()), daemon=True)
        self.proc.start()
        child.close()
        self.task: _Task | None = None
        self.started = 0.0

    def stop(self, kill: bool = False) -> None:
        if kill:
            self.proc.kill()
        else:
            try:
                self.conn.send(None)
            except (OSError, EOFError):
                pass
        self.proc.join(timeout=5)
        if self.proc.is_alive():
            self.proc.kill()
            self.proc.join()
        self.conn.close()


def _failed(task: _Task, error: str, seconds: float) -> dict[str, Any]:
    return {"path": task.path, "hash": task.digest, "parameters": task.parameters,
            "grasps": None, "reason": None, "units": None, "seconds": seconds,
            "error": error}


def _local(tasks: list[_Task], workers: int) -> Iterator[dict[str, Any]]:
    """Run tasks on a pool of worker processes, each part under its deadline."""
    import multiprocessing as mp
    from multiprocessing.connection import wait

    ctx = mp.get_context("fork" if "fork" in mp.get_all_start_methods() else "spawn")
    pending = list(reversed(tasks))
    slots = [_Slot(ctx) for _ in range(max(1, min(workers, len(tasks))))]
    try:
        while pending or any(s.task is not None for s in slots):
            for s in slots:
                if s.task is None and pending:
                    s.task, s.started = pending.pop(), time.perf_counter()
                    s.conn.send(s.task)
            busy = [s for s in slots if s.task is not None]
            now = time.perf_counter()
            waits = [s.started + s.task.deadline - now for s in busy
                     if s.task is not None and s.task.deadline is not None]
            timeout = max(0.0, min(waits)) if waits else None
            ready = wait([s.conn for s in busy], timeout=timeout)
            for k, s in enumerate(slots):
                task = s.task
                if task is None:
                    continue
                elapsed = time.perf_counter() - s.started
                if s.conn in ready:
                    try:
                        result = s.conn.recv()
                    except (EOFError, OSError):
                        s.proc.join(timeout=5)
                        code = s.proc.exitcode
                        why = "killed (out of memory?)" if code == -9 else \
                            f"exit code {code}"
                        result = _failed(task, f"the worker died planning this part: {why}",
                                         elapsed)
                        s.stop(kill=True)
                        slots[k] = s = _Slot(ctx)
                    s.task = None
                    yield result
                elif task.deadline is not None and elapsed > task.deadline:
                    s.stop(kill=True)
                    slots[k] = _Slot(ctx)
                    yield _failed(task, f"part timeout: more than {task.deadline:g} s",
                                  elapsed)
    finally:
        for s in slots:
            s.stop(kill=s.task is not None)


# ----------------------------------------------------------------------------- dask


def _large(task: _Task) -> bool:
    """A part worth splitting across a cluster's workers: a file of at least
    :data:`SMALL_PART_BYTES`, or a polygon of at least :data:`LARGE_EDGES` edges."""
    from ..model.polygon import Polygon

    if isinstance(task.item, Polygon):
        return task.item.n_edges >= LARGE_EDGES
    if not isinstance(task.item, str) or task.item.startswith("demo:"):
        return False
    try:
        return os.path.getsize(task.item) >= SMALL_PART_BYTES
    except OSError:
        return False


def _groups(tasks: list[_Task]) -> list[list[_Task]]:
    """Small parts in groups of :data:`GROUP_SIZE`."""
    out: list[list[_Task]] = []
    small: list[_Task] = []
    for t in tasks:
        small.append(t)
        if len(small) == GROUP_SIZE:
            out.append(small)
            small = []
    if small:
        out.append(small)
    return out


def _dask(tasks: list[_Task], client: Any) -> Iterator[dict[str, Any]]:
    from distributed import as_completed

    def solve_on_cluster(function: Any, batches: Any) -> Any:
        return client.gather(client.map(function, list(batches), pure=False))

    large = [t for t in tasks if _large(t)]
    groups = {client.submit(_plan_group, g, pure=False): g
              for g in _groups([t for t in tasks if not _large(t)])}
    # a large part is planned here, its candidate batches solved by the cluster's
    # workers (the public candidates -> solve -> rank pipeline), while the small
    # parts' groups run
    for t in large:
        yield _plan_one(t, map=solve_on_cluster)
    for fut in as_completed(list(groups)):
        try:
            results = fut.result()
        except Exception as exc:  # noqa: BLE001 - a lost worker fails its parts only
            msg = " ".join(str(exc).split())
            results = [_failed(t, f"the cluster lost this part: {type(exc).__name__}: {msg}",
                               0.0) for t in groups[fut]]
        yield from results


def cluster(scheduler: str, workers: int) -> Any:
    """A Dask client: on an existing scheduler, or on a new local cluster."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise ValueError("a Dask scheduler needs fcgrasp[distributed] (pip install "
                         "'fcgrasp[distributed]')") from None
    if scheduler == "local":
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        return Client(cluster)
    return Client(scheduler)


# ----------------------------------------------------------------------------- API


def _tasks(parts: Iterable[Any], options: dict[str, Any], part_timeout: float | None,
           figures: str | None) -> list[_Task]:
    from ..io.meshes import is_solid_source
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
            # a mesh among drawings is planned with the batch's friction, top and margin
            # for two soft fingers (two fingers) or three point fingers with friction; a
            # drawing among meshes for point fingers (or its own error)
            solid = is_solid_source(path)
            soft = solid and template.gripper == "fingers" and template.fingers in (None, 2)
            try:
                request = template.replace(part=path, soft=soft)
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
