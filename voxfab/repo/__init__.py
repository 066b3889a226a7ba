"""The shape repository: the artist's named shapes in one SQLite file.

A well-formed shape is named ``VVVVV.NNN``: its volume (voxel count) zero-padded
to five digits, then its three-digit rank among the shapes of that volume in
insertion order.  Names are stable: removing a shape renumbers nothing and its
name is never given again.  Shapes that are not well formed may be kept as drafts
(``draft-N``), and any shapes as a named range (``RANGE:MEMBER``, such as a
census's ``polycubes-8:08-000001``).  Equal shapes, up to translation (or up to the 48 cube symmetries
on request), are stored once, found through indexed canonical keys.

Only this package touches :mod:`sqlite3`.  See :class:`Repository`.
"""

from typing import TYPE_CHECKING

from voxfab._shared.lazy import lazy_names

from ._load import LoadedShape, load_shape
from ._records import (
    DRAFT_PATTERN,
    MAX_RANK,
    MEMBER_PATTERN,
    NAME_PATTERN,
    decode_bits,
    encode_bits,
    format_name,
    is_shape_name,
)

if TYPE_CHECKING:
    from ._ranges import RangeInfo
    from ._repository import DEFAULT_PATH, AddResult, Entry, Repository
    from ._sqlite import SCHEMA_VERSION

#: Names whose modules (and sqlite3) load on first use: a command that reads a shape file opens no database.
_LAZY = {"RangeInfo": "_ranges", "DEFAULT_PATH": "_repository", "AddResult": "_repository", "Entry": "_repository",
         "Repository": "_repository", "SCHEMA_VERSION": "_sqlite"}

__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())

__all__ = [
    "Repository",
    "LoadedShape",
    "load_shape",
    "AddResult",
    "Entry",
    "RangeInfo",
    "DEFAULT_PATH",
    "SCHEMA_VERSION",
    "MAX_RANK",
    "NAME_PATTERN",
    "DRAFT_PATTERN",
    "MEMBER_PATTERN",
    "is_shape_name",
    "format_name",
    "encode_bits",
    "decode_bits",
]
