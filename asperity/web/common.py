"""What every form of ``asperity serve`` shares: reading it, saving its uploads,
submitting its job and showing it again, filled in, with a one-line message when the job
fails (each page registers its form in ``web.renderers``)."""
from __future__ import annotations

import os

from fastapi import Request
from fastapi.responses import HTMLResponse, RedirectResponse

from ..errors import AsperityError
from .forms import Form, FormError, at, field_of
from .labels import page_pressures
from .security import TooLarge
from .store import JOB_ID, UploadError, display_name
from .words import FILE_FIELDS, MULTIPLE, WEDGE, page_words

MAX_FIELDS = 200
MAX_FILES = 200
#: most bytes of a TOML upload read as text (a study, assembly or body file)
MAX_TOML = 1 << 20


async def read_form(request: Request) -> Form:
    """The submitted form; a body that holds no field at all is refused (400)."""
    form = await request.form(max_files=MAX_FILES, max_fields=MAX_FIELDS)
    if not form and request.headers.get("content-length", "0") not in ("", "0"):
        raise FormError("the form arrived empty or malformed; send it again from the page")
    return Form(form)


async def save_upload(web, upload) -> dict:
    """Store an uploaded file under a generated name (its client name only shown); its
    metadata.  UploadError for a name without a format suffix, an empty file; TooLarge
    past the limit."""
    uid, path = web.store.new_upload_path(upload.filename)
    tmp = path.with_name(path.name + ".part")
    size = 0
    try:
        with open(tmp, "wb") as fh:
            while True:
                chunk = await upload.read(1 << 20)
                if not chunk:
                    break
                size += len(chunk)
                if size > web.settings.max_upload:
                    raise TooLarge(f"{display_name(upload.filename)!r} is larger than the "
                                   f"server's limit of {web.settings.max_upload / 2**20:.4g} MB "
                                   f"(asperity serve --max-upload MB)")
                fh.write(chunk)
        if size == 0:
            raise UploadError(f"{display_name(upload.filename)!r} is empty")
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
    return web.store.finish_upload(uid, upload.filename, size)


async def keep_uploads(web, form: Form, kept: dict, saved: list) -> None:
    """Every file of the form stored now, before any field is read (a refusal then keeps
    it: the page offers it again and the next submission reuses it), else the one stored
    before (sent back in its hidden field); ``kept``: key -> metadata, a list for a field
    of several files (a file chosen again replaces the kept one of the same name);
    ``saved``: the metadata of the files stored by this request."""
    first = None
    for name, (key, hidden) in FILE_FIELDS.items():
        try:
            with at(name):
                await _keep(web, form, kept, saved, name, key, hidden)
        except (AsperityError, TooLarge) as exc:     # the other files are kept all the same
            first = first or exc
    if first is not None:
        raise first


async def _keep(web, form: Form, kept: dict, saved: list, name: str, key: str,
                hidden: str) -> None:
    if name in MULTIPLE:
        old = {}
        for uid in form.form.getlist(hidden):
            meta = web.store.upload_meta(str(uid))
            old[meta["name"]] = meta
        try:
            for up in form.files(name):
                meta = await save_upload(web, up)
                saved.append(meta)
                old[meta["name"]] = meta
        finally:
            if old:
                kept[key] = list(old.values())
        return
    up = form.file(name)
    if up is not None:
        kept[key] = await save_upload(web, up)
        saved.append(kept[key])
    elif form.text(hidden):
        kept[key] = web.store.upload_meta(form.text(hidden))


def drop_upload(web, uid: str) -> None:
    """Remove a stored upload (and its metadata) from the data folder."""
    path = web.store.upload_path(uid)
    for p in (path, path.with_name(path.name + ".json")):
        p.unlink(missing_ok=True)


async def submit(web, request: Request, kind: str, params: dict, title: str):
    """Create the job, hand it to the runner, wait up to ``quick_wait`` s: a failure is
    shown at once on the form (4xx), anything else goes to the job's page."""
    rec = web.store.new_job(kind, params, title)
    web.runner.submit(rec["id"])
    rec = await web.runner.wait(rec["id"], web.settings.quick_wait)
    if rec is not None and rec["status"] == "failed":
        return await form_again(web, request, rec)
    return RedirectResponse(f"/jobs/{rec['id'] if rec else ''}", status_code=303)


async def post_form(web, request: Request, kind: str, build, render):
    """A form's POST: its files stored (:func:`keep_uploads`), then ``build(web, form,
    kept) -> (params, title)`` checks it; a refusal redraws the form with ``render``, what
    was typed and the files kept, and its one-line error next to its field (4xx), else
    the job is submitted with the form's values."""
    form = await read_form(request)
    values, kept, saved = form.values(), {}, []
    try:
        await keep_uploads(web, form, kept, saved)
        params, title = await build(web, form, kept)
    except (AsperityError, TooLarge) as exc:
        if getattr(exc, "discard", False):    # refused for what its files hold: none kept
            kept = {}
            for meta in saved:
                drop_upload(web, meta["id"])
        return render(web, request, status=status_of(exc), values=values, kept=kept,
                      error=page_pressures(str(exc)), error_field=field_of(exc))
    params.update(form=values, kept=kept)
    return await submit(web, request, kind, params, title)


async def form_again(web, request: Request, rec: dict) -> HTMLResponse:
    """The form that made job ``rec``, filled in again, with its error (or its note)."""
    params = rec.get("params", {})
    ctx = dict(values=params.get("form", {}), kept=params.get("kept", {}),
               need_units=bool(rec.get("needs_units")))
    if rec["status"] == "cancelled":
        ctx["notice"] = f"result {rec['id']} was stopped ({rec.get('error') or 'stopped'})"
        status = 200
    else:
        ctx["error"], ctx["error_field"] = page_words(
            rec.get("error") or "the computation failed", rec["kind"], params)
        status = int(rec.get("error_status") or 422)
    render = web.renderers.get(rec["kind"]) or web.renderers["derive"]
    return render(web, request, status=status, **ctx)


#: finished results offered as inputs on a form
DONE_LIMIT = 30


def wedge_source(form: Form, prefix: str = "") -> dict:
    return {"kind": "wedge", **{k: form.number(prefix + k, label=label)
                                for k, label in WEDGE.items()}}


def wedge_title(src: dict) -> str:
    return (f"wedge {src['alpha_deg']:g}/{src['beta_deg']:g} deg, mu "
            f"{src['mu_alpha']:g}/{src['mu_beta']:g}")


def done_job(web, jid: str, kinds, what: str, field: str) -> dict:
    """The finished job ``jid`` of one of ``kinds`` chosen in the select ``field``."""
    rec = web.store.read(jid) if JOB_ID.match(jid or "") else None
    if rec is None or rec["kind"] not in kinds:
        raise FormError(f"no {what} {jid[:40]!r}; pick one from the list", field)
    if rec["status"] != "done":
        raise FormError(f"{what} {jid} is {rec['status']}; pick a finished one", field)
    return rec


def status_of(exc: BaseException) -> int:
    if isinstance(exc, TooLarge):
        return 413
    return 400 if isinstance(exc, (FormError, UploadError)) else 422


def stored_text(web, meta: dict, what: str) -> str:
    """The text of a stored TOML upload (at most 1 MB)."""
    path = web.store.upload_path(meta["id"])
    if path.stat().st_size > MAX_TOML:
        raise UploadError(f"{meta['name']!r} is too large for {what} (1 MB)")
    return path.read_text(encoding="utf-8", errors="replace")
