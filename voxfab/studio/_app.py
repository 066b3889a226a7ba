"""The studio's HTTP API and page, on Starlette.

Requests carry the whole shape (25³ bits are 2 kB), so the server keeps no
shape state: only the jobs of the session (nets to pick from, files to
download) in memory and in the session's work folder.

Security, as a local server must have it:

* only requests whose ``Host`` is the server's own address get through, and a
  request with an ``Origin`` must come from the server's own page (DNS
  rebinding, cross-site forms);
* request bodies are limited (:data:`MAX_BODY`);
* no request names a file: the page is a fixed table of packaged files, shapes
  come from the repository by ``VVVVV.NNN`` name, downloads by job id and index;
* every input goes through the CLI's validation and comes back as
  ``{"error": "one line"}`` with status 400; an unexpected failure is a 500
  with one line, never a traceback.
"""

from __future__ import annotations

import io
import re
import shutil
import tempfile
import time
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Route

from voxfab.errors import InvalidShapeError, VoxfabError

from . import _bodies, _fits, _grid, _specs, _work
from ._edit import edit_route
from ._http import only_fields, read_json, read_object
from ._jobs import Jobs

#: Thumbnails kept in memory (oldest dropped first).
MAX_THUMBS = 2000

#: Largest request body in bytes (an uploaded bitmap is at most 4 MB, as base64 in JSON).
MAX_BODY = 6 * 1024 * 1024

_TYPES = {".html": "text/html; charset=utf-8", ".js": "text/javascript; charset=utf-8",
          ".css": "text/css; charset=utf-8", ".png": "image/png", ".svg": "image/svg+xml"}
_DOWNLOAD_TYPES = {".svg": "image/svg+xml", ".pdf": "application/pdf", ".png": "image/png", ".gif": "image/gif",
                   ".zip": "application/zip", ".json": "application/json", ".dxf": "application/dxf",
                   ".3mf": "model/3mf", ".stl": "model/stl", ".toml": "application/toml"}
_JOB_ID = re.compile(r"^[0-9a-f]{16}$")
_HEADERS = {
    "X-Content-Type-Options": "nosniff",
    "X-Frame-Options": "DENY",
    "Referrer-Policy": "no-referrer",
    "Content-Security-Policy": "default-src 'self'; img-src 'self' data: blob:; style-src 'self'; "
                               "script-src 'self'; connect-src 'self'; frame-ancestors 'none'",
}


@dataclass(frozen=True)
class Settings:
    """How the studio runs.

    Attributes
    ----------
    repo : Path
        The repository database (created on the first save).
    hosts : frozenset of str
        Accepted ``Host`` values (``host:port``); ``Origin`` must be ``http://`` one of them.
    work : Path or None
        The session's work folder (a fresh temporary folder when None, removed at shutdown).
    warm_up : bool
        Compile the numba kernels in the background at start (see :func:`_work.warm_kernels_here`).
    initial : InitialShape or None
        The shape the page opens with (``voxfab studio SHAPE``); None: the page starts from its drawing.
    """

    repo: Path
    hosts: frozenset[str]
    work: Path | None = None
    warm_up: bool = True
    initial: _grid.InitialShape | None = None


def allowed_hosts(host: str, port: int) -> frozenset[str]:
    """The ``Host`` values of a server bound to ``host:port``: its own name, and the loopback names.

    A loopback or wildcard address (``0.0.0.0``, ``::``) also answers to ``127.0.0.1``,
    ``localhost`` and ``[::1]``; any other address only to itself.
    """
    local = ("127.0.0.1", "localhost", "::1", "0.0.0.0", "::")
    names = {host, "127.0.0.1", "localhost", "[::1]"} if host in local else {host}
    names = {f"[{n}]" if ":" in n and not n.startswith("[") else n for n in names}
    return frozenset(f"{n}:{port}" for n in names)


class Guard:
    """ASGI middleware: Host and Origin checks, body size limit, safety headers."""

    def __init__(self, app: Any, hosts: frozenset[str], max_body: int = MAX_BODY) -> None:
        self.app, self.hosts, self.max_body = app, hosts, max_body
        self.origins = frozenset(f"http://{h}" for h in hosts)

    async def __call__(self, scope: dict, receive: Callable, send: Callable) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope["headers"]}
        if headers.get("host", "") not in self.hosts:
            await _plain(403, "voxfab studio: unknown Host; open the address the studio printed")(scope, receive, send)
            return
        origin = headers.get("origin")
        if origin is not None and origin not in self.origins:
            await _plain(403, "voxfab studio: requests from other sites are refused")(scope, receive, send)
            return
        length = headers.get("content-length")
        if length is not None and (not length.isdigit() or int(length) > self.max_body):
            await _error(413, f"request larger than {self.max_body // (1024 * 1024)} MB")(scope, receive, send)
            return
        # The body is read here, whole, so an oversized one never reaches the application.
        chunks, seen, more = [], 0, True
        while more:
            message = await receive()
            if message["type"] != "http.request":
                return  # the client went away
            chunks.append(message.get("body", b""))
            seen += len(chunks[-1])
            more = message.get("more_body", False)
            if seen > self.max_body:
                await _error(413, f"request larger than {self.max_body // (1024 * 1024)} MB")(scope, receive, send)
                return
        body = b"".join(chunks)
        replayed = False

        async def replay() -> dict:
            nonlocal replayed
            if not replayed:
                replayed = True
                return {"type": "http.request", "body": body, "more_body": False}
            return await receive()

        async def secured(message: dict) -> None:
            if message["type"] == "http.response.start":
                message["headers"] = list(message.get("headers", [])) + [
                    (k.lower().encode(), v.encode()) for k, v in _HEADERS.items()]
            await send(message)

        await self.app(scope, replay, secured)


def _plain(status: int, text: str) -> Response:
    return Response(text + "\n", status_code=status, media_type="text/plain", headers=_HEADERS)


def _error(status: int, message: str) -> JSONResponse:
    """``{"error": the artist's words}``, plus ``"detail"``: the technical line, when it differs (a tooltip)."""
    from ._words import explained

    said = explained(" ".join(message.split()))
    body = {"error": said["text"], **({"detail": said["detail"]} if "detail" in said else {})}
    return JSONResponse(body, status_code=status, headers=_HEADERS)


def _static_table() -> dict[str, tuple[bytes, str]]:
    """The page's files, read once from the package: the only files a URL can reach besides downloads."""
    root = resources.files("voxfab.studio") / "static"
    table: dict[str, tuple[bytes, str]] = {}

    def walk(node: Any, prefix: str) -> None:
        for child in node.iterdir():
            if child.is_dir():
                walk(child, f"{prefix}{child.name}/")
            elif Path(child.name).suffix in _TYPES:
                table[prefix + child.name] = (child.read_bytes(), _TYPES[Path(child.name).suffix])

    walk(root, "")
    return table


def create_app(settings: Settings) -> Starlette:
    """The studio application for ``settings`` (see :class:`Settings`)."""
    static = _static_table()
    state: dict[str, Any] = {}
    thumbs: dict[str, bytes] = {}

    def work() -> Path:
        if "work" not in state:
            folder = settings.work or Path(tempfile.mkdtemp(prefix="voxfab-studio-"))
            folder.mkdir(parents=True, exist_ok=True)
            state["work"] = folder
            state["jobs"] = Jobs(folder)
        return state["work"]

    def jobs() -> Jobs:
        work()
        return state["jobs"]

    def repository() -> Any:
        from voxfab.repo import Repository

        return Repository(settings.repo)

    def private(message: str) -> str:
        """The message with the repository named, not its folder: the page never learns paths on disk."""
        for path in sorted({str(settings.repo.resolve()), str(settings.repo)}, key=len, reverse=True):
            message = message.replace(path, settings.repo.name)
        return message

    def api(handler: Callable[[Request], Awaitable[Any]]) -> Callable[[Request], Awaitable[Response]]:
        async def endpoint(request: Request) -> Response:
            try:
                out = await handler(request)
            except VoxfabError as exc:
                return _error(400, private(str(exc)))
            except Exception as exc:  # noqa: BLE001 - one line for the page, never a traceback
                return _error(500, private(f"internal error ({type(exc).__name__}): {exc}"))
            return out if isinstance(out, Response) else JSONResponse(out)

        return endpoint

    # --- the page -----------------------------------------------------------------------------

    async def page(request: Request) -> Response:
        body, kind = static["index.html"]
        return Response(body, media_type=kind)

    async def static_file(request: Request) -> Response:
        hit = static.get(request.path_params["name"])
        if hit is None:
            return _plain(404, "not found")
        return Response(hit[0], media_type=hit[1], headers={"Cache-Control": "no-cache"})

    # --- shapes -------------------------------------------------------------------------------

    async def info(request: Request) -> dict[str, Any]:
        from voxfab._version import __version__
        from voxfab.fabricate.netdraw import SHEETS

        try:
            from voxfab.unfold import EdgeConstraints  # noqa: F401

            constraints = True
        except ImportError:
            constraints = False
        return {"version": __version__, "repository": settings.repo.name, "side": _grid.SIDE,
                "max_body": MAX_BODY, "constraints": constraints, "artefacts": _work.artefacts(),
                "max_nets": _work.MAX_NETS, "sheets": {k: list(v) for k, v in SHEETS.items()}}

    async def initial(request: Request) -> dict[str, Any]:
        return {"shape": None if settings.initial is None else settings.initial.answer()}

    async def preview(request: Request) -> dict[str, Any]:
        spec = await read_json(request)

        def run() -> dict[str, Any]:
            t0 = time.perf_counter()
            grid, _ = _specs.make_grid(spec, work())
            grid = _grid.centred(grid)
            return {"grid": _grid.pack(grid), "facts": _grid.facts(grid),
                    "ms": round(1000 * (time.perf_counter() - t0), 1)}

        return await run_in_threadpool(run)

    async def check(request: Request) -> dict[str, Any]:
        data = await read_object(request, _bodies.CHECK, example='{"grid": ...}')
        grid = _grid.unpack(data.get("grid"))
        return {"facts": await run_in_threadpool(_grid.facts, grid)}

    async def recipe(request: Request) -> Response:
        data = await read_object(request, _bodies.RECIPE, example='{"shape": ..., "name": ..., "pitch": MM}')
        name = data.get("name") or "studio"
        pitch = _bodies.pitch(data.get("pitch"))

        def run() -> tuple[str, bytes]:
            # made once here, so a recipe that fails to build is never handed out
            _specs.make_grid(data.get("shape"), work())
            text = _specs.drawing_recipe(data.get("shape"), name=name, pitch=pitch)
            if not text.files:
                return f"{text.name}.toml", text.toml.encode()
            buf = io.BytesIO()
            import zipfile

            with zipfile.ZipFile(buf, "w", compression=zipfile.ZIP_DEFLATED) as zf:
                for fname, raw in ((f"{text.name}.toml", text.toml.encode()), *text.files):
                    zf.writestr(zipfile.ZipInfo(f"{text.name}/{fname}", date_time=(1980, 1, 1, 0, 0, 0)), raw)
            return f"{text.name}.zip", buf.getvalue()

        fname, raw = await run_in_threadpool(run)
        return Response(raw, media_type=_DOWNLOAD_TYPES[Path(fname).suffix],
                        headers={"Content-Disposition": f'attachment; filename="{fname}"'})

    async def animate(request: Request) -> dict[str, Any]:
        data = await read_object(request, _bodies.ANIMATE, example='{"shape": ..., "steps": N}')
        steps = _bodies.steps(data.get("steps", 24))

        def run() -> dict[str, Any]:
            from voxfab.render import tube_frames

            params, folder = _specs.tube_params(data.get("shape"), work())
            try:
                frames = tube_frames(params, steps=int(steps), base_dir=folder)
            finally:
                shutil.rmtree(folder, ignore_errors=True)
            return {"frames": [_grid.pack(f) for f in frames]}

        return await run_in_threadpool(run)

    # --- the repository -----------------------------------------------------------------------

    async def repo_list(request: Request) -> dict[str, Any]:
        after = request.query_params.get("after") or None
        if after is not None:
            after = _name(request, "after")
        text = request.query_params.get("limit", "120")
        # at most 4 digits read: int() of a 5000-digit string would be an error of its own
        limit = _bodies.whole(int(text) if text.isdigit() and len(text) <= 4 else text, name="limit", lo=1, hi=500)

        def run() -> dict[str, Any]:
            if not settings.repo.exists():
                return {"shapes": [], "more": False}
            with repository() as repo:
                # one page more than asked tells whether another page follows
                entries = repo.list(after=after, limit=int(limit) + 1)
            # named shapes by volume, as the repository orders them; drafts after them
            return {"shapes": [{"name": e.name, "volume": e.volume, "extents": list(e.extents), "draft": e.draft}
                               for e in entries[: int(limit)]], "more": len(entries) > limit}

        return await run_in_threadpool(run)

    def _name(request: Request, key: str = "name") -> str:
        from voxfab.repo import DRAFT_PATTERN, NAME_PATTERN

        name = request.query_params.get(key, "")
        if not (NAME_PATTERN.match(name) or DRAFT_PATTERN.match(name)):
            raise InvalidShapeError(f"{key}: expected a repository name such as 00797.001, got {name[:40]!r}")
        return name

    async def repo_shape(request: Request) -> dict[str, Any]:
        name = _name(request)

        def run() -> dict[str, Any]:
            with repository() as repo:
                grid = _grid.centred(repo.get(name))
            return {"name": name, "grid": _grid.pack(grid), "facts": _grid.facts(grid)}

        return await run_in_threadpool(run)

    async def repo_thumb(request: Request) -> Response:
        name = _name(request)

        def run() -> bytes:
            from voxfab.render import png_bytes, render

            # names are never given twice, so a name's picture never changes
            if name not in thumbs:
                with repository() as repo:
                    grid = repo.get(name)
                if len(thumbs) >= MAX_THUMBS:
                    thumbs.pop(next(iter(thumbs)))
                thumbs[name] = png_bytes(render(grid, size=120))
            return thumbs[name]

        return Response(await run_in_threadpool(run), media_type="image/png")

    async def repo_add(request: Request) -> dict[str, Any]:
        data = await read_object(request, _bodies.REPO_ADD, example='{"grid": ..., "draft": false}')
        grid = _grid.unpack(data.get("grid"))
        draft = _bodies.flag(data.get("draft"), name="draft")

        def run() -> dict[str, Any]:
            if not grid.any():
                raise InvalidShapeError("shape: empty; draw or add voxels first")
            with repository() as repo:
                result = repo.add(grid, draft=draft)
            from ._words import plain

            return {"name": result.name, "created": result.created, "draft": result.draft,
                    "reasons": [plain(r) for r in result.reasons]}

        return await run_in_threadpool(run)

    # --- nets and files -----------------------------------------------------------------------

    async def nets(request: Request) -> dict[str, Any]:
        data = await read_json(request)
        if not isinstance(data, dict):
            raise InvalidShapeError("request: expected {\"grid\": ..., \"count\": N, \"options\": {...}}")
        only_fields(data, _bodies.NETS, where="request", hint='net and drawing options go in "options"')
        grid = _grid.unpack(data.get("grid"))
        # Checked by the library's option declarations: the CLI's bounds and words.
        count = _bodies.count(data.get("count", 8), _work.MAX_NETS)
        seed = _bodies.seed(data.get("seed", 0))
        net, drawing = _bodies.gallery_options(data.get("options"), defaults=_work.GALLERY_DEFAULTS)
        constraints = _work.edge_constraints(data.get("constraints"))
        from voxfab.shape import well_formed_reasons

        reasons = well_formed_reasons(grid)
        if any("piece" in r for r in reasons) or not grid.any():
            raise InvalidShapeError("shape: a net needs one piece of face-connected voxels: "
                                    + "; ".join(reasons or ["the shape is empty"]))
        job = jobs().submit("nets", lambda j: _work.net_gallery(
            j, grid, count=int(count), seed=int(seed), net=net, drawing=drawing, constraints=constraints))
        return {"job": job.id}

    def _job(job_id: str) -> Any:
        job = jobs().get(job_id) if _JOB_ID.match(job_id) else None
        if job is None:
            raise InvalidShapeError(f"job: no job {job_id[:20]!r} in this session")
        return job

    async def make(request: Request) -> dict[str, Any]:
        data = await read_object(request, _bodies.MAKE, example='{"grid": ..., "artefact": ...}')
        artefact = data.get("artefact")
        if artefact not in _work.artefacts():
            raise InvalidShapeError(f"artefact: expected one of {', '.join(_work.artefacts())}, got {artefact!r:.40}")
        grid = _grid.unpack(data.get("grid"))
        if not grid.any():
            raise InvalidShapeError("shape: empty; draw or add voxels first")
        pitch = _bodies.pitch(data.get("pitch"))
        title = data.get("title") or "studio"
        if not isinstance(title, str) or not re.fullmatch(r"[A-Za-z0-9_.\- ]{1,64}", title):
            raise InvalidShapeError(f"title: letters, digits, space, _ . - (at most 64), got {str(title)[:70]!r}")
        opts = data.get("options") or {}
        if not isinstance(opts, dict):
            raise InvalidShapeError("options: expected an object")
        # Checked now, by the output's own options dataclass: the same bounds and words as the CLI.
        settings = _work.download_settings(artefact, opts)
        net = None
        pick = data.get("net")
        if pick is not None:
            from voxfab.fabricate import output_for_download

            if output_for_download(artefact).name not in _bodies.NET_OUTPUTS:
                raise InvalidShapeError(f"net: {artefact} is made from the shape, not from a chosen net")
            if not isinstance(pick, dict) or not isinstance(pick.get("job"), str):
                raise InvalidShapeError("net: expected {\"job\": ID, \"index\": N}")
            only_fields(pick, _bodies.NET_PICK, where="net")
            chosen = _job(pick["job"]).data.get("nets", [])
            if not chosen:
                raise InvalidShapeError("net: that gallery has no nets")
            net = chosen[_bodies.whole(pick.get("index"), name="net.index", lo=0, hi=len(chosen) - 1)]
        placement = data.get("placement")
        if placement is not None:
            if net is None:
                raise InvalidShapeError("placement: pick a net first (\"net\": {\"job\": ID, \"index\": N})")
            from voxfab.fabricate.netdraw._placement import Placement

            placement = Placement.from_dict(placement)
        tube = None
        if artefact != "animation.gif" and data.get("shape") is not None:
            raise InvalidShapeError(f"shape: only animation.gif remakes the drawn shape; {artefact} is made from "
                                    "\"grid\"")
        if artefact == "animation.gif":
            tube = await run_in_threadpool(_specs.tube_params, data.get("shape"), work())
        job = jobs().submit("make", lambda j: _work.make_files(
            j, grid, artefact=artefact, title=title, pitch=pitch, net=net, settings=settings, tube=tube,
            placement=placement))
        return {"job": job.id}

    async def job_status(request: Request) -> dict[str, Any]:
        job = _job(request.path_params["job"])
        since = request.query_params.get("since")
        if since is None:
            return job.status()
        # The items the page has not drawn yet: a gallery's nets, each as soon as it is made.
        if not since.isdigit() or len(since) > 6:
            raise InvalidShapeError(f"since: expected the number of items already read, got {since[:20]!r}")
        return job.status(since=int(since))

    async def job_cancel(request: Request) -> dict[str, Any]:
        job = _job(request.path_params["job"])
        jobs().cancel(job)
        return job.status()

    async def download(request: Request) -> Response:
        job = _job(request.path_params["job"])
        index = request.path_params["index"]
        if job.state != "done" or not 0 <= index < len(job.files):
            raise InvalidShapeError(f"file: job {job.id} has no file {index}")
        name, path = job.files[index]
        return FileResponse(path, filename=name, media_type=_DOWNLOAD_TYPES.get(Path(name).suffix,
                                                                                 "application/octet-stream"))

    async def not_found(request: Request, exc: Exception) -> Response:
        if request.url.path.startswith("/api/"):
            return _error(404, f"no such endpoint: {request.method} {request.url.path[:80]}")
        return _plain(404, "not found")

    async def method_not_allowed(request: Request, exc: Exception) -> Response:
        return _error(405, f"{request.method} is not allowed on {request.url.path[:80]}")

    async def server_error(request: Request, exc: Exception) -> Response:
        return _error(500, f"internal error ({type(exc).__name__})")

    def cleanup() -> None:
        if "jobs" in state:
            state["jobs"].shutdown()
        if "work" in state and settings.work is None:
            shutil.rmtree(state["work"], ignore_errors=True)

    from contextlib import asynccontextmanager

    @asynccontextmanager
    async def lifespan(app: Starlette):  # noqa: ANN202 - Starlette's protocol
        work()
        if settings.warm_up:
            import threading

            threading.Thread(target=_work.warm_kernels_here, name="studio-warm-up", daemon=True).start()
        try:
            yield
        finally:
            cleanup()

    routes = [
        Route("/", page),
        Route("/favicon.ico", lambda request: Response(status_code=204)),
        Route("/static/{name:path}", static_file),
        Route("/api/info", api(info)),
        Route("/api/initial", api(initial)),
        Route("/api/preview", api(preview), methods=["POST"]),
        Route("/api/check", api(check), methods=["POST"]),
        Route("/api/recipe", api(recipe), methods=["POST"]),
        Route("/api/animate", api(animate), methods=["POST"]),
        Route("/api/repo", api(repo_list)),
        Route("/api/repo", api(repo_add), methods=["POST"]),
        Route("/api/repo/shape", api(repo_shape)),
        Route("/api/repo/thumb", api(repo_thumb)),
        Route("/api/nets", api(nets), methods=["POST"]),
        Route("/api/nets/edit", api(edit_route(jobs)), methods=["POST"]),
        Route("/api/fits", api(_fits.endpoint(jobs)), methods=["POST"]),
        Route("/api/make", api(make), methods=["POST"]),
        Route("/api/jobs/{job}", api(job_status)),
        Route("/api/jobs/{job}/cancel", api(job_cancel), methods=["POST"]),
        Route("/api/files/{job}/{index:int}", api(download)),
    ]
    app = Starlette(routes=routes, lifespan=lifespan,
                    exception_handlers={404: not_found, 405: method_not_allowed, 500: server_error})
    app.state.cleanup = cleanup
    app.state.cancel_jobs = lambda: state["jobs"].cancel_all() if "jobs" in state else None
    return Guard(app, settings.hosts)  # type: ignore[return-value]

