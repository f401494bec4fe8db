"""Who may talk to the server, and how much: an ASGI middleware in front of the app.

* **Token** (``--allow-remote``): every request carries the access token printed at
  start, as Jupyter does: ``?token=...`` once (it sets an HttpOnly cookie for the port
  and redirects to the same page without it), then the cookie; or a header
  ``Authorization: token ...``.
  Without it: 401, one line.
* **Host** (a loopback server without a token): the ``Host`` header must name a loopback
  address or ``localhost``; a page of another site cannot reach the server through a DNS
  name pointed at 127.0.0.1 (DNS rebinding).  403, one line.
* **Origin**: a form sent from a page of another site is refused (403, one line).
* **Size**: a request body over ``--max-upload`` is refused with 413 as soon as it is
  known: at once from ``Content-Length``, else when the stream passes the limit.
"""
from __future__ import annotations

import secrets
from urllib.parse import parse_qsl, urlencode

from .settings import is_loopback

COOKIE = "asperity_token"
UNSAFE = {"POST", "PUT", "PATCH", "DELETE"}


class TooLarge(Exception):
    """The request body passed the upload limit."""


def _host_name(value: str) -> str:
    """The host part of a Host header: ``127.0.0.1:8765`` -> ``127.0.0.1``."""
    v = value.strip()
    if v.startswith("["):
        return v[1:v.find("]")] if "]" in v else v
    return v.rsplit(":", 1)[0] if v.count(":") == 1 else v


def _cookie_name(scope) -> str:
    """The token's cookie, one per port (browsers share cookies between the ports of a
    host, and two servers have two tokens)."""
    server = scope.get("server") or ("", 0)
    return f"{COOKIE}_{server[1] or 0}"


class Guard:
    """The ASGI middleware (see the module docstring).  ``render(status, message)`` gives
    the (content type, body) of the one-line error page."""

    def __init__(self, app, settings, render):
        self.app = app
        self.token = settings.token
        self.limit = settings.max_upload
        self.render = render

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        headers = {k.decode("latin-1").lower(): v.decode("latin-1")
                   for k, v in scope.get("headers", [])}
        host = headers.get("host", "")
        if self.token is None and not is_loopback(_host_name(host)):
            return await self._error(send, 403, f"this server answers requests for localhost "
                                                f"only, not for {host[:80]!r}")
        if scope["method"] in UNSAFE:
            origin = headers.get("origin")
            if origin and origin != "null" and origin.split("://", 1)[-1] != host:
                return await self._error(send, 403, "a form sent from another site is refused")
        if self.token is not None:
            pairs = parse_qsl(scope.get("query_string", b"").decode("latin-1"))
            given = dict(pairs).get("token")
            cookie = _cookie_name(scope)
            if given is not None and secrets.compare_digest(given, self.token):
                rest = urlencode([(k, v) for k, v in pairs if k != "token"])
                return await self._redirect(send, scope["path"] + ("?" + rest if rest else ""),
                                            cookie)
            if not self._has_token(headers, cookie):
                return await self._error(send, 401, "this server needs its access token: "
                                                    "open the link that asperity serve "
                                                    "printed at start (...?token=...)")
        length = headers.get("content-length")
        if length is not None:
            try:
                n = int(length)
            except ValueError:
                return await self._error(send, 400, "the request's Content-Length is not a "
                                                    "number")
            if n > self.limit:
                return await self._error(send, 413, self._too_large())
        return await self._limited(scope, receive, send)

    def _too_large(self) -> str:
        return (f"the upload is larger than the server's limit of "
                f"{self.limit / 2**20:.4g} MB (asperity serve --max-upload MB)")

    def _has_token(self, headers: dict, cookie: str) -> bool:
        auth = headers.get("authorization", "")
        for prefix in ("token ", "bearer "):
            if auth.lower().startswith(prefix) and secrets.compare_digest(
                    auth[len(prefix):].strip(), self.token):
                return True
        for part in headers.get("cookie", "").split(";"):
            name, _, value = part.strip().partition("=")
            if name == cookie and secrets.compare_digest(value, self.token):
                return True
        return False

    async def _limited(self, scope, receive, send):
        seen = 0
        started = False

        async def counted():
            nonlocal seen
            msg = await receive()
            if msg["type"] == "http.request":
                seen += len(msg.get("body", b""))
                if seen > self.limit:
                    raise TooLarge(self._too_large())
            return msg

        async def watch(msg):
            nonlocal started
            if msg["type"] == "http.response.start":
                started = True
            await send(msg)

        try:
            await self.app(scope, counted, watch)
        except TooLarge as exc:
            if not started:
                await self._error(send, 413, str(exc))

    async def _error(self, send, status: int, message: str):
        ctype, body = self.render(status, message)
        await send({"type": "http.response.start", "status": status,
                    "headers": [(b"content-type", ctype.encode()),
                                (b"content-length", str(len(body)).encode())]})
        await send({"type": "http.response.body", "body": body})

    async def _redirect(self, send, location: str, name: str):
        cookie = f"{name}={self.token}; HttpOnly; SameSite=Strict; Path=/"
        await send({"type": "http.response.start", "status": 303,
                    "headers": [(b"location", location.encode("latin-1")),
                                (b"set-cookie", cookie.encode("latin-1")),
                                (b"content-length", b"0")]})
        await send({"type": "http.response.body", "body": b""})
