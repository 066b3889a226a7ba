"""What every route shares at the HTTP edge: reading a JSON body and checking it whole, and the answers.

Every field of a body is either one the endpoint uses or refused: a key dropped
without a word would leave the artist believing it had its effect.  Numbers are
checked by the option declarations the CLI uses (:func:`declared`), so a value out
of range is refused with the option's own message, whatever its size.  Every
answer carries :data:`SAFETY_HEADERS`; an error is ``{"error": ...}`` in the
artist's words (:func:`error_response`).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

from voxfab.errors import InvalidShapeError

#: Headers on every answer: no sniffing, no framing, no referrer, and only the page's own scripts and styles.
SAFETY_HEADERS = {
    "X-Content-Type-Options": "nosniff",
    "X-Frame-Options": "DENY",
    "Referrer-Policy": "no-referrer",
    "Content-Security-Policy": "default-src 'self'; img-src 'self' data: blob:; style-src 'self'; "
                               "script-src 'self'; connect-src 'self'; frame-ancestors 'none'",
}


#: Media types of the files a job offers for download, by suffix (others are sent as bytes).
DOWNLOAD_TYPES = {".svg": "image/svg+xml", ".pdf": "application/pdf", ".png": "image/png", ".gif": "image/gif",
                  ".zip": "application/zip", ".json": "application/json", ".dxf": "application/dxf",
                  ".3mf": "model/3mf", ".stl": "model/stl", ".toml": "application/toml"}


def download_type(name: str) -> str:
    """The media type of a download called ``name``."""
    from pathlib import PurePath

    return DOWNLOAD_TYPES.get(PurePath(name).suffix, "application/octet-stream")


def plain_response(status: int, text: str) -> Any:
    """A one-line text answer (refusals outside the API: a foreign Host, a page file that does not exist)."""
    from starlette.responses import Response

    return Response(text + "\n", status_code=status, media_type="text/plain", headers=SAFETY_HEADERS)


def error_response(status: int, message: str) -> Any:
    """``{"error": the artist's words}``, plus ``"detail"``: the technical line, when it differs (a tooltip)."""
    from starlette.responses import JSONResponse

    from ._words import explained

    said = explained(" ".join(message.split()))
    body = {"error": said["text"], **({"detail": said["detail"]} if "detail" in said else {})}
    return JSONResponse(body, status_code=status, headers=SAFETY_HEADERS)


async def read_json(request: Any) -> Any:
    """The request's body as JSON (``None`` when empty), or a one-line error."""
    body = await request.body()
    try:
        return json.loads(body or b"null")
    except (ValueError, RecursionError):
        raise InvalidShapeError("request: the body is not JSON") from None


async def read_object(request: Any, fields: tuple[str, ...], *, example: str) -> dict[str, Any]:
    """The request's body as a JSON object of only ``fields``, or a one-line error naming the first stray key."""
    data = await read_json(request)
    if not isinstance(data, dict):
        raise InvalidShapeError(f"request: expected {example}")
    only_fields(data, fields, where="request")
    return data


def only_fields(data: Mapping[str, Any], fields: tuple[str, ...], *, where: str, hint: str = "") -> None:
    """Refuse a key of ``data`` that is not one of ``fields`` (``hint`` says where it may belong)."""
    from voxfab._shared.options import quote

    extra = sorted(str(k) for k in data if k not in fields)
    if extra:
        raise InvalidShapeError(f"{where}: unknown field {quote(extra[0], 40)}; expected {', '.join(fields)}"
                                + (f" ({hint})" if hint else ""))


def declared(cls: type, name: str, value: Any) -> Any:
    """``value`` checked by the declaration of option ``name`` of the options dataclass ``cls``.

    The type, the range and the words are the option's own, as on the command line
    (``count: expected an integer from 1 to 1000, got 1000…``); a JSON integer of any
    size is a value out of range, never an OverflowError.
    """
    from voxfab._shared.options import check_values

    return check_values(cls, {name: value})[name]
