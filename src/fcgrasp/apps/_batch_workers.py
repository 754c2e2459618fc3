"""A batch's workers: parts planned in processes of their own (small parts in groups),
each under its timeout and killed with its parent, or on a Dask cluster (part of
:mod:`fcgrasp.apps.batch`)."""

from __future__ import annotations

import os
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

from ..errors import PartTimeout

#: Parts smaller than this (bytes of their file) are sent to a cluster in groups.
SMALL_PART_BYTES = 200_000


#: How many small parts make one cluster task.
GROUP_SIZE = 8


#: Polygons with this many edges are split across a cluster's workers.
LARGE_EDGES = 500


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
        for key in ("gap", "hand", "scene"):   # a pick with a hand: its hand and scene
            if key in doc.report:
                out[key] = doc.report[key]
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
