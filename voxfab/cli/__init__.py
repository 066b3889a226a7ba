"""The ``voxfab`` command: a thin shell over the library."""

from ._common import STRICT_EXIT
from ._main import COMMANDS, main

__all__ = ["COMMANDS", "STRICT_EXIT", "main"]
