"""Reading a request's JSON body, in one place for every route, and checking it whole.

Every field of a body is either one the endpoint uses or refused: a key dropped
without a word would leave the artist believing it had its effect.  Numbers are
checked by the option declarations the CLI uses (:func:`declared`), so a value out
of range is refused with the option's own message, whatever its size.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

from voxfab.errors import InvalidShapeError


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
