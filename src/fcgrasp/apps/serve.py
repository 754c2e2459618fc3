"""``fcgrasp serve``: the grasp explorer, a local web app (needs ``fcgrasp[serve]``).

The page (static HTML, JavaScript and CSS shipped in ``fcgrasp/explorer``, no build step)
draws the part to scale and lets the user drag, add and delete vertices, load a part file,
pick the gripper and its options, and read the ranked plans drawn as in the paper's
figure 1; it places fingers by hand and shows the verdict of theorem 6.1 with the escape
motion.  Everything it computes comes from the same public functions as the command line:

* a plan is :func:`fcgrasp.apps.cli.plan_document` on the options ``fcgrasp plan`` would parse,
  so the page's plans are exactly those of ``fcgrasp plan --no-clean`` on the same
  vertices;
* a hand-placed grasp is :meth:`fcgrasp.Grasp.explain` on the contacts of
  :func:`fcgrasp.io.parts.contacts_from_data` (the contacts file of ``fcgrasp check``);
* the grasp-set overlay is :func:`fcgrasp.grasp_set` on the plan's edges: the restricted
  edges ``e'_i`` of theorem 6.3 for two fingers, the parallelograms ``Pi_12``, ``Pi_34``
  and the two-sided sector ``C`` of algorithm 6.1 for four (three against gravity).

The explorer is a local web app, secured as one (Jupyter's model): every request's
``Host`` must name an address the server serves (a DNS-rebinding page's host is
refused), a request with an ``Origin`` must come from the server's own, and every API
call carries the session token of the page it was served in (``X-Fcgrasp-Token``; a new
one per page load, written into the page): a page on another origin can neither read
that token nor send it (a custom header asks the browser's preflight, which the server
never grants).  Job ids are unguessable and belong to the session that started them.
Uploads are read in a process of their own, killed past :data:`READ_SECONDS` and capped
at :data:`READ_MEMORY` bytes, and a request body must arrive within
:data:`BODY_SECONDS`.

The HTTP interface (JSON in and out; errors are ``{"error": message, "field": name}``
with status 400, 403, 404 or 413; the server answers every request and never stops on
one):

``GET /api/state``
    the starting part, the built-in parts, the ranking measures and the limits;
``GET /api/demo/NAME``, ``POST /api/part?name=FILE[&part=N|ID][&units=U]`` (the file's
    bytes as the body)
    a part: ``{"outer": [[x, y], ...], "holes": [...], "units": ..., "name": ...}`` (of a
    file, also its ``parts``, as ``fcgrasp parts`` lists them, and the ``part`` taken:
    the largest unless ``part`` names another; in ``units``, default mm); or a
    solid (a built-in solid, a mesh file): ``{"solid": true, "source": ..., "vertices":
    [[x, y, z], ...], "faces": [[i, j, k], ...], "units": ..., ...}``, which the page
    sends back to plan it (a built-in one is read again by its name) with the grippers
    of a solid (``"2"``: two soft fingers, ``"3"``: three fingers with friction,
    ``"jaw"``);
``POST /api/plan`` ``{"part": ..., "options": {...}, "replaces": null}``
    starts a plan in a process of its own (cancelling the job ``replaces`` first) and
    answers within :data:`ANSWER_WITHIN` seconds: the finished result, or
    ``{"job": id, "state": "running", "progress": [done, total]}`` to poll (429 when
    eight plans run already);
``GET /api/jobs/ID[?wait=SECONDS]``, ``DELETE /api/jobs/ID``
    a plan's state (``running``, ``done``, ``error``, ``cancelled``), and cancelling it
    (its process is killed at once, whatever planner runs); with ``wait`` (at most
    :data:`MAX_WAIT`), the state is given as soon as the plan ends, or after that long
    (a long poll: the page sees a plan the moment it is done, not at its next poll);
``POST /api/check`` ``{"part": ..., "contacts": [...], "gravity": null}``
    the verdict on a grasp, the failed closure and the escape twist ``(omega, vx, vy)``.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import secrets
import threading
from collections import OrderedDict
from importlib.resources import files
from typing import Any

from ..errors import RequestError
from ._explorer_data import (
    GRIPPERS,
    _short,
    check_result,
    demo_json,
    page_part,
    part_json,
    plan_request,
    polygon_of,
    solid_choices,
    stress_result,
)
from ._serve_jobs import (
    ANSWER_WITHIN,
    Jobs,
    _wait_of,
)

#: Largest accepted upload (a part file), bytes.
MAX_UPLOAD = 8 * 2 ** 20
#: Largest accepted JSON request body, bytes.
MAX_REQUEST = 4 * 2 ** 20
#: Host names the server answers to by default (it listens on the loopback): a request
#: naming another host (a DNS-rebinding page's) is refused.
LOCAL_HOSTS = ("127.0.0.1", "localhost", "::1")
#: Session tokens remembered (one per page load; the oldest are forgotten first).
KEEP_SESSIONS = 256
#: Seconds a request's body may take to arrive (a slow client is cut off).
BODY_SECONDS = 30.0
#: The request header that carries the page's session token.
TOKEN_HEADER = "x-fcgrasp-token"


class _Sessions:
    """The session tokens the server gave its pages (one per page load), the newest
    :data:`KEEP_SESSIONS`."""

    def __init__(self) -> None:
        self._tokens: OrderedDict[str, None] = OrderedDict()
        self._lock = threading.Lock()

    def new(self) -> str:
        token = secrets.token_urlsafe(24)
        with self._lock:
            self._tokens[token] = None
            while len(self._tokens) > KEEP_SESSIONS:
                self._tokens.popitem(last=False)
        return token

    def __contains__(self, token: object) -> bool:
        with self._lock:
            return isinstance(token, str) and token in self._tokens


def _host_name(value: str) -> str:
    """The host name of a ``Host`` header or of an origin's authority, without its port
    (``[::1]:8000`` -> ``::1``), lower case."""
    value = value.strip().lower()
    if value.startswith("["):
        return value[1:value.find("]")] if "]" in value else value
    return value.rsplit(":", 1)[0] if value.count(":") == 1 else value


def _refusal(scope_headers: dict[str, str], allowed: tuple[str, ...] | None) -> str | None:
    """Why a request must be refused (its ``Host`` or its ``Origin``), or None
    (``allowed`` None: any host, the server listening on every address)."""
    host = scope_headers.get("host", "")
    if allowed is not None and _host_name(host) not in allowed:
        return f"host {host!r} is not an address this server serves"
    origin = scope_headers.get("origin")
    if origin is not None:
        scheme, _, authority = origin.partition("://")
        if scheme != "http" or authority.lower() != host.lower():
            return f"requests from {origin!r} are not accepted (only from the page itself)"
    return None


class _Guard:
    """ASGI middleware: every HTTP request's ``Host`` and ``Origin`` checked
    (:func:`_refusal`), a 403 otherwise, pages, files and API alike."""

    def __init__(self, app: Any, allowed: tuple[str, ...] | None) -> None:
        self.app, self.allowed = app, allowed

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        if scope["type"] == "http":
            headers = {k.decode("latin-1").lower(): v.decode("latin-1")
                       for k, v in scope["headers"]}
            why = _refusal(headers, self.allowed)
            if why is not None:
                from starlette.responses import JSONResponse

                await JSONResponse({"error": why, "field": "origin"}, status_code=403)(
                    scope, receive, send)
                return
        await self.app(scope, receive, send)


# ----------------------------------------------------------------------------- the app


def create_app(start: Any = None, max_upload: int = MAX_UPLOAD,
               allowed_hosts: tuple[str, ...] | None = LOCAL_HOSTS) -> Any:
    """The explorer as an ASGI application (Starlette).  ``start`` is the first part shown:
    a :class:`fcgrasp.io.parts.Part` (default ``demo:blob``); ``allowed_hosts``: the host
    names requests may name (default the loopback's; None: any, for a server listening
    on every address, where the session token still guards the API)."""
    from starlette.applications import Starlette
    from starlette.requests import Request
    from starlette.responses import HTMLResponse, JSONResponse, Response
    from starlette.routing import Mount, Route
    from starlette.staticfiles import StaticFiles

    from ..io.parts import DEMO_PARTS, load_part, read_json
    from ..io.units import UNITS
    from ..model.ranking import MEASURES
    from ..spatial.solid import DEMO_SOLIDS

    if start is None:
        start = load_part("demo:blob")
    first = part_json(start.polygon, start.units, start.source, start.notes)
    static = str(files("fcgrasp") / "apps" / "explorer")
    jobs = Jobs()
    sessions = _Sessions()
    allowed = None if allowed_hosts is None else tuple(_host_name(h) for h in allowed_hosts)
    with open(os.path.join(static, "index.html"), encoding="utf-8") as fh:
        page = fh.read()

    def error(exc: RequestError) -> JSONResponse:
        return JSONResponse({"error": " ".join(str(exc).split()), "field": exc.field},
                            status_code=exc.status)

    async def body_of(request: Request, limit: int) -> bytes:
        length = request.headers.get("content-length")
        if length is not None and (not length.isdigit() or int(length) > limit):
            raise RequestError(f"the request is too large ({length} bytes; at most "
                               f"{limit} are accepted)", "file", 413)
        chunks, size = [], 0

        async def receive() -> None:
            nonlocal size
            async for chunk in request.stream():
                size += len(chunk)
                if size > limit:
                    raise RequestError(f"the request is too large (more than {limit} "
                                       f"bytes)", "file", 413)
                chunks.append(chunk)

        try:                                  # a slow client is cut off
            await asyncio.wait_for(receive(), BODY_SECONDS)
        except TimeoutError:
            raise RequestError(f"the request's body took more than {BODY_SECONDS:g} s to "
                               f"arrive", "file", 408) from None
        return b"".join(chunks)

    async def json_of(request: Request, keys: set[str]) -> dict[str, Any]:
        raw = await body_of(request, MAX_REQUEST)
        try:                                  # parsing a large body is not the loop's work
            data = await asyncio.to_thread(read_json, raw, "the request")
        except ValueError as exc:
            raise RequestError(str(exc)) from None
        if not isinstance(data, dict):
            raise RequestError(f"the request must be a JSON object, got {_short(data)}")
        extra = sorted(set(data) - keys)
        if extra:
            raise RequestError(f"unknown key {extra[0]!r} in the request (expected "
                               f"{', '.join(sorted(keys))})")
        return data

    def session(request: Request) -> str:
        """The page's session token (403 without a valid one)."""
        token = request.headers.get(TOKEN_HEADER, "")
        if token not in sessions:
            raise RequestError("this request carries no session token of this server's "
                               "pages (reload the page)", "token", 403)
        return token

    def guarded(handler: Any, api: bool = True) -> Any:
        async def endpoint(request: Request) -> Response:
            try:
                if api:
                    request.state.session = session(request)
                return await handler(request)
            except RequestError as exc:
                return error(exc)
            except (ValueError, TypeError) as exc:
                return error(RequestError(str(exc)))
            except Exception as exc:  # noqa: BLE001 - one bad request never stops the server
                return JSONResponse({"error": f"internal error: {type(exc).__name__}: {exc}",
                                     "field": "server"}, status_code=500)
        return endpoint

    async def index(request: Request) -> Response:
        # the page's own session token, written into it: no other origin can read it
        html = page.replace('<meta name="fcgrasp-token" content="">',
                            f'<meta name="fcgrasp-token" content="{sessions.new()}">')
        return HTMLResponse(html, headers={"Cache-Control": "no-store",
                                           "X-Frame-Options": "DENY",
                                           "Referrer-Policy": "no-referrer"})

    async def favicon(request: Request) -> Response:
        return Response(status_code=204)

    async def state(request: Request) -> Response:
        return JSONResponse({"part": first, "demos": list(DEMO_PARTS),
                             "solids": list(DEMO_SOLIDS), "measures": list(MEASURES),
                             "grippers": list(GRIPPERS),
                             "solid_grippers": list(solid_choices()),
                             "max_upload": max_upload, "answer_within": ANSWER_WITHIN})

    async def demo(request: Request) -> Response:
        return JSONResponse(await asyncio.to_thread(demo_json, request.path_params["name"]))

    async def upload(request: Request) -> Response:
        name = request.query_params.get("name", "upload")
        part = request.query_params.get("part")
        units = request.query_params.get("units")
        if units is not None and units not in UNITS:
            raise RequestError(f"units must be one of {', '.join(UNITS)}, got "
                               f"{_short(units)}", "units")
        body = await body_of(request, max_upload)
        if not body:
            raise RequestError("the file is empty", "file")
        out = await asyncio.to_thread(jobs.read, body, name, part, units)
        return JSONResponse(out)

    async def plan(request: Request) -> Response:
        data = await json_of(request, {"part", "options", "replaces"})
        old = data.get("replaces")
        if old is not None and (isinstance(old, bool) or not isinstance(old, (str, int))):
            raise RequestError(f"replaces must be the id of the page's previous job, got "
                               f"{_short(old)}", "replaces")
        # checking a large outline and the options is work: never on the event loop
        part = data.get("part")
        options = data.get("options", {})
        polygon, units, source = await asyncio.to_thread(page_part, part)
        request_ = await asyncio.to_thread(plan_request, options, source, units)
        owner = request.state.session
        if old is not None:                   # the page's previous plan, now stale
            try:
                await asyncio.to_thread(jobs.cancel, str(old), owner)
            except RequestError:
                pass
        job = await asyncio.to_thread(jobs.start, polygon, units, request_, owner)
        await asyncio.to_thread(job.done.wait, ANSWER_WITHIN)
        return JSONResponse(job.answer())

    async def job_state(request: Request) -> Response:
        job = jobs.get(request.path_params["id"], request.state.session)
        wait = _wait_of(request.query_params.get("wait"))
        if wait > 0 and not job.done.is_set():
            await asyncio.to_thread(job.done.wait, wait)
        return JSONResponse(job.answer())

    async def job_cancel(request: Request) -> Response:
        return JSONResponse(jobs.cancel(request.path_params["id"],
                                        request.state.session).answer())

    async def stress(request: Request) -> Response:
        data = await json_of(request, {"part", "plan"})
        polygon, units, _ = await asyncio.to_thread(page_part, data.get("part"))
        return JSONResponse(await asyncio.to_thread(stress_result, polygon, units,
                                                    data.get("plan")))

    async def check(request: Request) -> Response:
        data = await json_of(request, {"part", "contacts", "gravity"})
        polygon, _ = await asyncio.to_thread(polygon_of, data.get("part"))
        return JSONResponse(await asyncio.to_thread(check_result, polygon, data))

    routes = [
        Route("/", guarded(index, api=False)),
        Route("/favicon.ico", guarded(favicon, api=False)),
        Route("/api/state", guarded(state)),
        Route("/api/demo/{name}", guarded(demo)),
        Route("/api/part", guarded(upload), methods=["POST"]),
        Route("/api/plan", guarded(plan), methods=["POST"]),
        Route("/api/jobs/{id}", guarded(job_state), methods=["GET"]),
        Route("/api/jobs/{id}", guarded(job_cancel), methods=["DELETE"]),
        Route("/api/check", guarded(check), methods=["POST"]),
        Route("/api/stress", guarded(stress), methods=["POST"]),
        Mount("/static", app=StaticFiles(directory=static), name="static"),
    ]
    @contextlib.asynccontextmanager
    async def lifespan(app: Any) -> Any:
        await asyncio.to_thread(jobs.warm, 2)
        yield
        jobs.close()

    from starlette.middleware import Middleware

    return Starlette(routes=routes, lifespan=lifespan,
                     middleware=[Middleware(_Guard, allowed=allowed)])


def serve(start: Any = None, host: str = "127.0.0.1", port: int = 8000,
          announce: Any = print, open_browser: bool = False) -> None:
    """Run the explorer until interrupted; ``announce(url)`` is told where it listens
    (``port=0`` takes a free port)."""
    import socket

    import uvicorn

    wildcard = host in ("0.0.0.0", "::", "")
    app = create_app(start, allowed_hosts=None if wildcard else
                     tuple(dict.fromkeys((*LOCAL_HOSTS, host))))
    sock = socket.socket(socket.AF_INET6 if ":" in host else socket.AF_INET)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    sock.bind((host, port))
    sock.listen(128)             # connections wait from now on: the URL announced is live
    actual = sock.getsockname()[1]
    shown = f"[{host}]" if ":" in host else host
    url = f"http://{shown}:{actual}/"
    config = uvicorn.Config(app, log_level="warning", access_log=False)
    server = uvicorn.Server(config)
    announce(f"fcgrasp explorer: {url} (Ctrl-C to stop)")
    if open_browser:
        import webbrowser

        threading.Timer(0.5, webbrowser.open, args=(url,)).start()
    server.run(sockets=[sock])
