"""The one exception hierarchy of voxfab.

Every error a user can cause derives from :class:`VoxfabError`; subclasses also
inherit the matching builtin so callers may catch either family.  The CLI turns
each class into a one-line message and its own exit code (see ``EXIT_CODES``).
"""

from __future__ import annotations

import re

__all__ = [
    "VoxfabError",
    "InvalidShapeError",
    "UnknownFormatError",
    "FormatError",
    "UnfoldError",
    "NoNetExistsError",
    "RecipeError",
    "RepositoryError",
    "MissingDependencyError",
    "FabricationError",
    "LimitError",
    "OutputError",
    "CancelledError",
    "VoxfabWarning",
    "EXIT_CODES",
    "quote",
    "one_line",
]

#: Characters of user input quoted in a message: enough to recognise it, never a
#: whole 10 KB expression.
QUOTE_LIMIT = 80
#: Longest error line the CLI prints.
MESSAGE_LIMIT = 600


def quote(value: object, limit: int = QUOTE_LIMIT) -> str:
    """``repr(value)`` cut to about ``limit`` characters, saying how long the input was.

    >>> quote("x" * 1000, 20)
    "'xxxxxxxxxxxxxxx...' (1000 characters)"
    """
    text = repr(value)
    if len(text) <= limit:
        return text
    size = f" ({len(value)} characters)" if isinstance(value, (str, bytes)) else ""
    close = text[-1] if text[-1] in "'\"" else ""
    return f"{text[: max(limit - 4, 1)]}...{close}{size}"


# A quoted run of more than QUOTE_LIMIT characters, in single or double quotes.
_QUOTED = re.compile(
    rf"'(?:[^'\\\n]|\\.){{{QUOTE_LIMIT},}}'|\"(?:[^\"\\\n]|\\.){{{QUOTE_LIMIT},}}\""
)


def one_line(message: object, limit: int = MESSAGE_LIMIT) -> str:
    """``message`` as one line: whitespace folded, long quoted input cut, at most ``limit`` characters.

    The CLI passes every error and warning through this, so no message repeats a
    huge input, whichever module wrote it.
    """
    text = " ".join(str(message).split())
    text = _QUOTED.sub(lambda m: f"{m.group(0)[: QUOTE_LIMIT - 4]}...{m.group(0)[-1]}", text)
    if len(text) > limit:
        text = f"{text[: limit - 3]}..."
    return text


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


class NoNetExistsError(UnfoldError):
    """A complete search proved that no net of the kind asked for fits the box (not a time-out).

    The message names what was proved: no one-piece net at all, or only no zipper
    net (a torus has one-piece nets, but its handle rules out every zipper).

    Attributes
    ----------
    box : (int, int) or None
        The box in faces, ``(width, height)``; None when the proof holds in any box.
    why : str
        The reason when it is known without a search (edge constraints that
        leave no room, a handle), else empty.
    kind : str
        What has none: ``"one-piece net"`` or ``"zipper net"``.
    """

    def __init__(self, width: int | None, height: int | None, why: str = "", kind: str = "one-piece net") -> None:
        if width is None or height is None:
            text = f"no {kind} of this shape exists, in any box (proved)"
        else:
            text = f"no {kind} of this shape fits {width}x{height} faces (proved)"
        super().__init__(f"{text}: {why}" if why else text)
        self.box = None if width is None or height is None else (width, height)
        self.why = why
        self.kind = kind

    def __reduce__(self) -> tuple:
        # Rebuilt from the box (batch workers pickle errors), not from the message.
        return (type(self), (*(self.box or (None, None)), self.why, self.kind))


class RecipeError(VoxfabError, ValueError):
    """A recipe with an unknown key, a wrong type or a bad value."""


class RepositoryError(VoxfabError, RuntimeError):
    """The shape repository refused an operation."""


class FabricationError(VoxfabError, RuntimeError):
    """A fabrication output cannot be made from valid input (e.g. a mesh check failed)."""


class LimitError(VoxfabError, ValueError):
    """Input over one of voxfab's documented size limits (see ``voxfab._shared.limits``)."""


class OutputError(InvalidShapeError):
    """An output that cannot be written where it was asked (no such folder, not a folder...).

    An output path is a parameter: its exit status is that of :class:`InvalidShapeError`.
    """


class CancelledError(VoxfabError):
    """Work stopped because it was asked to (the studio's Cancel, a server shutting down)."""


class VoxfabWarning(UserWarning):
    """Something the user should know that does not stop the run; the CLI prints it as one line."""


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
    LimitError: 12,
    NoNetExistsError: 13,
}
