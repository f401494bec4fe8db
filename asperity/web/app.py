"""The web application: pages, job pages, static files, and errors as one line.

:func:`create_app` builds the ASGI application of ``asperity serve`` (FastAPI inside the
:class:`~asperity.web.security.Guard`).  Every error reaches the user as one line on the
page with a 4xx status: a form field that is not a number (400), an upload refused (400,
413), input the library refuses (422, its own one-line message), an unknown page (404);
a bug is one line too (500, its traceback in the server's log only with ASPERITY_DEBUG=1);
a client that goes away mid-request is no error at all.
"""
from __future__ import annotations

import contextlib
import logging
import os
from pathlib import Path

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, HTMLResponse, JSONResponse, RedirectResponse, Response
from fastapi.templating import Jinja2Templates
from starlette.exceptions import HTTPException
from starlette.requests import ClientDisconnect

from .. import __version__
from ..errors import AsperityError, InputError, one_line
from .common import form_again, status_of
from .runner import Runner
from .security import Guard, TooLarge
from . import labels, units
from .store import JOB_ID, Store, clock, duration

HERE = Path(__file__).resolve().parent
STATIC = {"app.js": "text/javascript", "style.css": "text/css"}
log = logging.getLogger("asperity.web")
#: job kind -> the page whose form made it
PAGE_OF = {"derive": "surface", "fit": "law", "gauge": "law", "slide": "motion",
           "risk": "motion", "crawl": "motion", "study": "studies"}


def plotly_js() -> Path:
    """plotly.min.js of the installed plotly package (found without importing plotly)."""
    import importlib.util
    spec = importlib.util.find_spec("plotly")
    if spec is None or not spec.submodule_search_locations:
        raise InputError("the plotly package is not installed (pip install plotly)")
    path = Path(list(spec.submodule_search_locations)[0]) / "package_data" / "plotly.min.js"
    if not path.is_file():
        raise InputError(f"plotly.min.js is missing from the plotly package ({path})")
    return path


class Web:
    """What the routes share: settings, store, runner, templates."""

    def __init__(self, settings):
        self.settings = settings
        self.store = Store(settings.data_dir)
        self.store.sweep()
        self.runner = Runner(self.store, settings.workers)
        self.templates = Jinja2Templates(directory=str(HERE / "templates"))
        self.templates.env.globals.update(version=__version__, data_dir=str(settings.data_dir))
        self.templates.env.filters["abs"] = abs
        self.templates.env.filters["duration"] = duration
        self.templates.env.globals.update(settings_of=labels.settings)
        units.register(self.templates.env)
        self.renderers: dict = {}           # job kind -> its form's page (pages register)

    def page(self, request: Request, name: str, status: int = 200, **context) -> HTMLResponse:
        context.setdefault("error", None)
        context.setdefault("values", {})
        context.setdefault("kept", {})
        return self.templates.TemplateResponse(request, name, context, status_code=status)

    def error_page(self, request: Request, status: int, message: str) -> HTMLResponse:
        if request.url.path.startswith("/api/") or "application/json" in \
                request.headers.get("accept", "") and "text/html" not in \
                request.headers.get("accept", ""):
            return JSONResponse({"error": one_line(message), "status": status}, status)
        return self.page(request, "error.html", status, error=one_line(message), page="")

    def render_bare(self, status: int, message: str) -> tuple[str, bytes]:
        """The error page without a request (for the Guard middleware): shown to anyone,
        also a visitor without the token, so it says nothing about the server (``bare``:
        no data folder in the footer)."""
        tpl = self.templates.env.get_template("error.html")
        html = tpl.render(error=one_line(message), page="", values={}, kept={}, bare=True)
        return "text/html; charset=utf-8", html.encode("utf-8")


def create_app(settings):
    """The ASGI application of ``settings`` (a :class:`~asperity.web.settings.Settings`)."""
    from . import pages, pages_crawl, pages_motion
    web = Web(settings)

    @contextlib.asynccontextmanager
    async def lifespan(app):
        await web.runner.start()
        try:
            yield
        finally:
            await web.runner.stop()

    app = FastAPI(title="asperity", version=__version__, lifespan=lifespan, docs_url=None,
                  redoc_url=None, openapi_url=None)
    app.state.web = web
    _errors(app, web)
    _static(app)
    _jobs(app, web)
    pages.register(app, web)
    pages_motion.register(app, web)
    pages_crawl.register(app, web)
    return Guard(Quiet(app), settings, web.render_bare)


class Quiet:
    """The application with no exception escaping to the server.  Starlette answers a bug
    with the ``bug`` handler's page (500, one line, logged in one line) and then raises it
    again for the server to log: uvicorn would print its traceback for every such request
    ("Exception in ASGI application").  The traceback is printed only with
    ASPERITY_DEBUG=1 (by the ``bug`` handler)."""

    def __init__(self, app):
        self.app = app

    def __getattr__(self, name):           # the application's state, routes, ...
        return getattr(self.app, name)

    async def __call__(self, scope, receive, send):
        try:
            await self.app(scope, receive, send)
        except Exception:                  # answered (and logged) by the bug handler
            pass


def _errors(app: FastAPI, web: Web) -> None:
    @app.exception_handler(HTTPException)
    async def http_error(request: Request, exc: HTTPException):
        import http
        path = request.url.path[:100]
        own = {404: f"no page at {path}",
               405: f"{request.method[:10]} is not allowed at {path}"}
        try:
            phrase = http.HTTPStatus(exc.status_code).phrase
        except ValueError:
            phrase = ""
        msg = exc.detail if isinstance(exc.detail, str) and exc.detail not in ("", phrase) \
            else own.get(exc.status_code, phrase or "request refused")
        return web.error_page(request, exc.status_code, msg)

    @app.exception_handler(RequestValidationError)
    async def invalid(request: Request, exc: RequestValidationError):
        first = exc.errors()[0] if exc.errors() else {}
        where = ".".join(str(x) for x in first.get("loc", ()) if x not in ("body", "query"))
        return web.error_page(request, 422, f"{where}: {first.get('msg', 'invalid input')}")

    async def refused(request: Request, exc: Exception):
        return web.error_page(request, status_of(exc), str(exc))

    @app.exception_handler(ClientDisconnect)
    async def gone(request: Request, exc: ClientDisconnect):
        """The client went away during its request (a closed tab, a lost connection
        mid-upload): nobody reads the answer, nothing to log."""
        return Response(status_code=400)

    app.add_exception_handler(TooLarge, refused)
    app.add_exception_handler(AsperityError, refused)

    @app.exception_handler(Exception)
    async def bug(request: Request, exc: Exception):
        log.error("internal error on %s: %s: %s", request.url.path, type(exc).__name__, exc,
                  exc_info=bool(os.environ.get("ASPERITY_DEBUG")))
        return web.error_page(request, 500, f"internal error: {type(exc).__name__}: "
                                            f"{one_line(exc, 200)} (please report it)")


def _static(app: FastAPI) -> None:
    js = plotly_js()

    @app.get("/static/plotly.min.js", include_in_schema=False)
    async def plotly():
        return FileResponse(js, media_type="text/javascript",
                            headers={"Cache-Control": "max-age=86400"})

    @app.get("/static/{name}", include_in_schema=False)
    async def static(name: str):
        if name not in STATIC:
            raise HTTPException(404, f"no file /static/{name[:80]}")
        return FileResponse(HERE / "static" / name, media_type=STATIC[name])

    @app.get("/favicon.ico", include_in_schema=False)
    async def favicon():
        return HTMLResponse("", status_code=204)


def _jobs(app: FastAPI, web: Web) -> None:
    store = web.store

    def job_or_404(jid: str) -> dict:
        rec = store.read(jid)
        if rec is None:
            raise HTTPException(404, f"no result {jid[:40]!r} (it may have been deleted)")
        return rec

    @app.get("/", response_class=HTMLResponse)
    async def home(request: Request):
        return web.page(request, "index.html", page="home", jobs=store.jobs(limit=10))

    @app.get("/jobs", response_class=HTMLResponse)
    async def jobs(request: Request):
        gone = request.query_params.get("deleted", "")
        notice = f"result {gone} deleted, with its files" if JOB_ID.match(gone) and \
            store.read(gone) is None else None
        return web.page(request, "jobs.html", page="jobs", jobs=store.jobs(limit=500),
                        notice=notice, delete=True)

    @app.get("/api/jobs/{jid}")
    async def job_status(jid: str):
        rec = job_or_404(jid)
        prog = store.progress(jid)
        return {"id": jid, "kind": rec["kind"], "status": rec["status"],
                "fraction": 1.0 if rec["status"] == "done" else prog.get("fraction", 0.0),
                "label": prog.get("label", ""), "error": rec.get("error"),
                "files": rec.get("files", []), **clock(rec, prog)}

    @app.get("/api/jobs/{jid}/result")
    async def job_result(jid: str):
        rec = job_or_404(jid)
        if rec["status"] != "done":
            raise HTTPException(409, f"result {jid} is {rec['status']}, not done")
        return store.result(jid) or {}

    @app.get("/jobs/{jid}", response_class=HTMLResponse)
    async def job_page(request: Request, jid: str):
        rec = job_or_404(jid)
        page = PAGE_OF.get(rec["kind"], "")
        if rec["status"] in ("queued", "running"):
            prog = store.progress(jid)
            return web.page(request, "progress.html", page=page, job=rec, progress=prog,
                            clock=clock(rec, prog))
        if rec["status"] == "done":
            result = store.result(jid)
            if result is not None:
                name = "result_fit.html" if rec["kind"] == "gauge" else f"result_{rec['kind']}.html"
                return web.page(request, name, page=page, job=rec, result=result)
            rec = {**rec, "error": "the result file of this job is missing or damaged; run it "
                                   "again", "error_status": 500}
        return await form_again(web, request, rec)

    @app.get("/jobs/{jid}/files/{name:path}")
    async def job_file(jid: str, name: str):
        job_or_404(jid)
        path = store.job_file(jid, name)
        if path is None:
            raise HTTPException(404, f"result {jid} has no file {name[:80]!r}")
        shown = labels.download_name((store.result(jid) or {}).get("downloads"), name)
        return FileResponse(path, filename=shown)

    @app.get("/jobs/{jid}/delete", response_class=HTMLResponse)
    async def delete_page(request: Request, jid: str):
        rec = job_or_404(jid)
        return web.page(request, "delete.html", page="jobs", job=rec,
                        busy=rec["status"] in ("queued", "running"))

    @app.post("/jobs/{jid}/delete")
    async def delete(jid: str):
        rec = job_or_404(jid)
        if rec["status"] in ("queued", "running"):
            raise HTTPException(409, f"result {jid} is {rec['status']}: stop it first (the "
                                     f"button on its page), then delete it")
        if not store.delete(jid):
            raise HTTPException(404, f"no result {jid!r} (it may have been deleted)")
        return RedirectResponse(f"/jobs?deleted={jid}", status_code=303)

    @app.post("/jobs/{jid}/cancel")
    async def cancel(jid: str):
        job_or_404(jid)
        web.runner.cancel(jid)
        return RedirectResponse(f"/jobs/{jid}", status_code=303)
