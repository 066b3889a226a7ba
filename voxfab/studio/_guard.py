"""The studio's gate: only its own page on its own address gets through, with a body of bounded size.

A local server must refuse what a web page elsewhere could send it: a request
whose ``Host`` is not the server's own address (DNS rebinding), one whose
``Origin`` is another site (cross-site forms and scripts), and a body larger than
:data:`MAX_BODY`.  Every answer gets :data:`._http.SAFETY_HEADERS`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from voxfab._shared.numbers import is_digits

from ._http import SAFETY_HEADERS, error_response, plain_response

#: Largest request body in bytes (an uploaded bitmap is at most 4 MB, as base64 in JSON).
MAX_BODY = 6 * 1024 * 1024


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
        refusal = self._refusal(headers)
        if refusal is not None:
            await refusal(scope, receive, send)
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
                await self._too_large()(scope, receive, send)
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
                    (k.lower().encode(), v.encode()) for k, v in SAFETY_HEADERS.items()]
            await send(message)

        await self.app(scope, replay, secured)

    def _refusal(self, headers: dict[str, str]) -> Any:
        """The answer to a request refused on its headers alone, or None when it may go on."""
        if headers.get("host", "") not in self.hosts:
            return plain_response(403, "voxfab studio: unknown Host; open the address the studio printed")
        origin = headers.get("origin")
        if origin is not None and origin not in self.origins:
            return plain_response(403, "voxfab studio: requests from other sites are refused")
        length = headers.get("content-length")
        if length is not None and (not is_digits(length) or len(length) > 18 or int(length) > self.max_body):
            return self._too_large()
        return None

    def _too_large(self) -> Any:
        return error_response(413, f"request larger than {self.max_body // (1024 * 1024)} MB")
