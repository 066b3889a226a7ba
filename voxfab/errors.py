"""The one exception hierarchy of voxfab.

Every error a user can cause derives from :class:`VoxfabError`; subclasses also
inherit the matching builtin so callers may catch either family.  The CLI turns
each class into a one-line message and its own exit code (see ``EXIT_CODES``).
"""

from __future__ import annotations

__all__ = [
    "VoxfabError",
    "InvalidShapeError",
    "UnknownFormatError",
    "FormatError",
    "UnfoldError",
    "RecipeError",
    "RepositoryError",
    "MissingDependencyError",
    "FabricationError",
    "EXIT_CODES",
]


class VoxfabError(Exception):
    """Base class of every error caused by input rather than by a bug."""


class InvalidShapeError(VoxfabError, ValueError):
    """A voxel grid or a parameter is not what the operation needs."""


class UnknownFormatError(VoxfabError, ValueError):
    """A file extension, maker or output name that no registry knows."""


class FormatError(VoxfabError, ValueError):
    """A file that is corrupt, truncated or not of the format its name says."""


class UnfoldError(VoxfabError, RuntimeError):
    """Valid input for which no net was found (or none can exist)."""


class RecipeError(VoxfabError, ValueError):
    """A recipe with an unknown key, a wrong type or a bad value."""


class RepositoryError(VoxfabError, RuntimeError):
    """The shape repository refused an operation."""


class FabricationError(VoxfabError, RuntimeError):
    """A fabrication output cannot be made from valid input (e.g. a mesh check failed)."""


class MissingDependencyError(VoxfabError, ImportError):
    """An optional package needed for this feature is not installed."""

    def __init__(self, package: str, feature: str) -> None:
        super().__init__(
            f"{feature} needs the package '{package}': pip install {package}"
        )


#: Exit status of the CLI per error class (the most specific class wins).
EXIT_CODES: dict[type[VoxfabError], int] = {
    VoxfabError: 1,
    InvalidShapeError: 3,
    UnknownFormatError: 4,
    FormatError: 5,
    UnfoldError: 6,
    RecipeError: 7,
    RepositoryError: 8,
    MissingDependencyError: 9,
    FabricationError: 10,
}
