"""Reading a request's JSON body, in one place for every route."""

from __future__ import annotations

import json
from typing import Any

from voxfab.errors import InvalidShapeError


async def read_json(request: Any) -> Any:
    """The request's body as JSON (``None`` when empty), or a one-line error."""
    body = await request.body()
    try:
        return json.loads(body or b"null")
    except (ValueError, RecursionError):
        raise InvalidShapeError("request: the body is not JSON") from None
