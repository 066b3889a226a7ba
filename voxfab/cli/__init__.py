"""The ``voxfab`` command: a thin shell over the library."""

from ._main import COMMANDS, main

__all__ = ["COMMANDS", "main"]
