"""The explorer's plans as jobs: each in a worker process of its own, answered within a
moment or polled, cancelled by a newer plan of its session, reading files under the
same limits (part of :mod:`fcgrasp.apps.serve`)."""

from __future__ import annotations

import os
import secrets
import threading
import time
from dataclasses import dataclass, field
from typing import Any

from ..errors import RequestError
from ..io.report import json_ready
from ._explorer_data import (
    _short,
    as_part,
    check_result,
    overlay,
    plan_request,
    read_upload,
)

#: How long ``POST /api/plan`` waits for the result before answering with a job to poll.
ANSWER_WITHIN = 0.05


#: The longest ``wait`` of ``GET /api/jobs/ID?wait=SECONDS`` (seconds).
MAX_WAIT = 1.0


#: Finished jobs kept for polling (the oldest are forgotten first).
KEEP_JOBS = 32


#: Seconds and bytes of memory the process reading an upload may take.
READ_SECONDS, READ_MEMORY = 30.0, 2 * 2 ** 30


@dataclass
class Job:
    """One plan being computed in a process of its own."""

    id: str
    owner: str = ""
    state: str = "running"
    progress: tuple[int, int] = (0, 0)
    result: dict[str, Any] | None = None
    error: str | None = None
    done: threading.Event = field(default_factory=threading.Event)
    started: float = field(default_factory=time.perf_counter)
    seconds: float | None = None
    process: Any = field(default=None, repr=False)

    def answer(self) -> dict[str, Any]:
        out: dict[str, Any] = {"job": self.id, "state": self.state,
                               "progress": list(self.progress), "seconds": self.seconds}
        if self.state == "done":
            out.update(self.result or {})
        elif self.state == "error":
            out["error"] = self.error
        return out


def _wait_of(raw: str | None) -> float:
    """The ``wait`` of ``GET /api/jobs/ID?wait=SECONDS``: 0 when not given, else a number
    of seconds in ``[0, MAX_WAIT]`` (:class:`~fcgrasp.errors.RequestError` otherwise)."""
    if raw is None:
        return 0.0
    try:
        wait = float(raw)
    except ValueError:
        wait = float("nan")
    if not 0.0 <= wait <= MAX_WAIT:            # nan too
        raise RequestError(f"wait must be a number of seconds from 0 to {MAX_WAIT:g}, "
                           f"got {_short(raw)}", "wait")
    return wait


def plan_result(polygon: Any, units: str, request: Any,
                progress: Any = None) -> dict[str, Any]:
    """Plan a part as ``fcgrasp plan`` does (:func:`fcgrasp.planning.plan_document` on
    the :func:`plan_request` of the page's options): the JSON report, the equivalent
    command-line options, the drawing data of every plan and its grasp-set overlay (None
    for a plan with none: the jaw's boxes, a solid's regions).  ``polygon`` is the part
    the page holds (:func:`~fcgrasp.apps._explorer_data.page_part`: an outline or a
    solid)."""
    from ..planning import plan_document

    doc = plan_document(request, part=as_part(polygon, request.part, units),
                        progress=progress)
    overlays = [json_ready(overlay(doc.polygon, p)) for p in doc.plans]
    # the report's JSON values (what fcgrasp plan --json writes, without the round trip
    # through text: 7 ms of a 2,000-edge plan), and a parallel gripper's plans as MoveIt
    # grasps (fcgrasp plan --moveit; None for other grippers)
    report = json_ready(doc.report)
    return {"report": report, "argv": request.to_argv(), "overlays": overlays,
            "moveit": _moveit(report)}


def _moveit(report: dict[str, Any]) -> list[dict[str, Any]] | None:
    """The report's plans as ``fcgrasp plan --moveit`` writes them, where they are a
    parallel gripper's (a jaw's or two fingers'; :mod:`fcgrasp.io.moveit`)."""
    from ..io.moveit import moveit_grasps, parallel_gripper

    if not report.get("grasps") or not parallel_gripper(report):
        return None
    return moveit_grasps(report)


def _worker(conn: Any) -> None:
    """A planning process: warms up (a small plan of each kind loads what planning
    loads), then plans each ``(polygon, units, request)`` it is sent, sending progress
    reports (at most every 50 ms) and then ``("done", result)`` or ``("error", text)``."""
    from ..io.parts import demo_part

    blob = demo_part("blob")
    for opts in ({"gripper": "2", "mu": 0.3}, {"gripper": "4", "along_boundary": False},
                 {"gripper": "3", "mu": 0.5, "along_boundary": False, "top": 1}):
        plan_result(blob, "mm", plan_request(opts))
    check_result(blob, {"contacts": [{"point": [21.0, -3.0], "mu": 0.3}]})
    last = [0.0]

    def progress(done: int, total: int) -> None:
        now = time.perf_counter()
        if now - last[0] >= 0.05 or done >= total:
            last[0] = now
            conn.send(("progress", (int(done), int(total))))

    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError):
            return
        if task is None:
            return
        try:
            polygon, units, request = task
            conn.send(("done", plan_result(polygon, units, request, progress=progress)))
        except (ValueError, TypeError) as exc:
            conn.send(("error", " ".join(str(exc).split())))
        except Exception as exc:  # noqa: BLE001 - reported to the page
            conn.send(("error", f"internal error: {type(exc).__name__}: {exc}"))


@dataclass
class _Process:
    process: Any
    conn: Any


class Jobs:
    """The plans being computed, in a pool of warmed-up planning processes (one plan
    each at a time): cancelling a job kills its process, whatever planner runs, and a
    fresh one takes its place.  At most ``workers`` plans run at once (more: 429);
    ``KEEP_JOBS`` finished jobs are remembered for polling.

    Processes come from a fork server (started once, fcgrasp loaded): safe to start from
    the server's threads, a few milliseconds each."""

    def __init__(self, workers: int = 4) -> None:
        import multiprocessing

        self._ctx = multiprocessing.get_context("forkserver")
        # the fork server also compiles (or loads) numba's kernels, once for every
        # planning process (fcgrasp.apps._warm)
        self._ctx.set_forkserver_preload(["fcgrasp.apps.serve", "fcgrasp.planning",
                                          "fcgrasp.apps._warm"])
        self._jobs: dict[str, Job] = {}
        self._idle: list[_Process] = []
        self._lock = threading.Lock()
        self.workers = workers
        self._closed = False

    def _spawn(self) -> _Process:
        mine, theirs = self._ctx.Pipe()
        proc = self._ctx.Process(target=_worker, args=(theirs,), daemon=True,
                                 name="fcgrasp-planner")
        proc.start()
        theirs.close()
        return _Process(proc, mine)

    def warm(self, n: int = 1) -> None:
        """Start ``n`` planning processes now (the first one also starts the fork
        server: about a second), so that the first plans do not wait for them."""
        fresh = [self._spawn() for _ in range(n)]
        with self._lock:
            self._idle += fresh

    def start(self, polygon: Any, units: str, request: Any, owner: str = "") -> Job:
        """Start planning ``request`` (a :func:`plan_request`) on ``polygon`` for the
        session ``owner``; a page's options dict is checked first (a bad option is an
        answer now, not a job).  The job's id is unguessable."""
        if isinstance(request, dict):
            request = plan_request(request)
        with self._lock:
            busy = sum(not j.done.is_set() for j in self._jobs.values())
            if busy >= self.workers:
                raise RequestError(f"{busy} plans are running already: cancel one or wait",
                                   "job", 429)
            job = Job(id=secrets.token_urlsafe(16), owner=owner)
            self._jobs[job.id] = job
            finished = [k for k, j in self._jobs.items() if j.done.is_set()]
            for k in finished[:max(0, len(self._jobs) - KEEP_JOBS)]:
                del self._jobs[k]
            worker = self._idle.pop() if self._idle else None
        worker = worker or self._spawn()
        try:
            worker.conn.send((polygon, units, request))
        except OSError:                       # an idle process died: take a fresh one
            worker.process.kill()
            worker = self._spawn()
            worker.conn.send((polygon, units, request))
        job.process = worker.process

        def watch() -> None:
            alive = False
            try:
                while True:
                    kind, value = worker.conn.recv()
                    if kind == "progress":
                        job.progress = value
                        continue
                    alive = True
                    if job.state == "running":
                        job.state = kind
                        if kind == "done":
                            job.result = value
                        else:
                            job.error = value
                    break
            except (EOFError, OSError):
                if job.state == "running":    # died without a word: out of memory?
                    job.state = "error"
                    job.error = (f"the planning process stopped (exit code "
                                 f"{worker.process.exitcode}; out of memory?)")
            job.seconds = time.perf_counter() - job.started
            with self._lock:
                keep = alive and not self._closed and len(self._idle) < self.workers
                if keep:
                    self._idle.append(worker)
            if not keep:
                worker.process.kill()
                worker.process.join(5)
                worker.conn.close()
                if not alive and not self._closed:
                    self.warm()               # a warm process for the next plan
            job.done.set()

        threading.Thread(target=watch, name=f"fcgrasp-job-{job.id}", daemon=True).start()
        return job

    def get(self, job_id: str, owner: str | None = None) -> Job:
        """The job ``job_id`` of the session ``owner`` (None: any session's)."""
        with self._lock:
            job = self._jobs.get(job_id)
        if job is None or (owner is not None and job.owner != owner):
            raise RequestError(f"no job {job_id!r} (finished jobs are kept for a while)",
                               "job", 404)
        return job

    def cancel(self, job_id: str, owner: str | None = None) -> Job:
        job = self.get(job_id, owner)
        if not job.done.is_set():
            job.state = "cancelled"
            job.process.kill()
        return job

    def read(self, body: bytes, name: str, part: str | None = None,
             units: str | None = None) -> dict[str, Any]:
        """:func:`~fcgrasp.apps._explorer_data.read_upload` in a process of its own,
        killed past :data:`READ_SECONDS` and capped at :data:`READ_MEMORY` bytes: a file
        that would take the server's memory or time takes only its own process."""
        mine, theirs = self._ctx.Pipe()
        proc = self._ctx.Process(target=_reader, args=(theirs, body, name, part, units),
                                 daemon=True, name="fcgrasp-reader")
        proc.start()
        theirs.close()
        try:
            if not mine.poll(READ_SECONDS):
                raise RequestError(f"cannot read {os.path.basename(name) or 'upload'}: "
                                   f"reading took more than {READ_SECONDS:g} s", "file", 413)
            kind, value = mine.recv()
        except (EOFError, OSError):
            raise RequestError(f"cannot read {os.path.basename(name) or 'upload'}: the "
                               f"reader stopped (more than {READ_MEMORY // 2 ** 20} MB of "
                               f"memory?)", "file", 413) from None
        finally:
            proc.kill()
            proc.join(5)
            mine.close()
        if kind == "error":
            raise RequestError(value, "file")
        return value

    def close(self) -> None:
        """Stop every planning process (the server is stopping)."""
        with self._lock:
            self._closed = True
            idle, self._idle = self._idle, []
            jobs = list(self._jobs.values())
        for job in jobs:
            if not job.done.is_set():
                job.state = "cancelled"
                job.process.kill()
        for w in idle:
            w.process.kill()
            w.conn.close()


def _reader(conn: Any, body: bytes, name: str, part: str | None = None,
            units: str | None = None) -> None:
    """An upload's reading process: its memory capped, its answer sent once."""
    try:
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (READ_MEMORY, READ_MEMORY))
    except (ImportError, ValueError, OSError):    # not on this platform: time still bounds
        pass
    try:
        conn.send(("done", read_upload(body, name, part, units)))
    except RequestError as exc:
        conn.send(("error", str(exc)))
    except MemoryError:
        conn.send(("error", f"cannot read {os.path.basename(name) or 'upload'}: more than "
                            f"{READ_MEMORY // 2 ** 20} MB of memory"))
    except Exception as exc:  # noqa: BLE001 - reported to the page
        conn.send(("error", f"cannot read {os.path.basename(name) or 'upload'}: "
                            f"{type(exc).__name__}: {exc}"))
