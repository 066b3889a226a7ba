"""Optional dependencies: find them without importing, and say how to install them."""

from __future__ import annotations

import importlib.util

from voxfab.errors import MissingDependencyError

#: Optional feature group → (import name, pip requirement).
EXTRAS: dict[str, tuple[str, str]] = {
    "cad": ("build123d", "voxfab[cad]"),
}


def has_extra(extra: str) -> bool:
    """Whether the packages of an optional feature group (``"cad"``) are installed."""
    module, _ = EXTRAS[extra]
    return importlib.util.find_spec(module) is not None


def require_extra(extra: str, feature: str) -> None:
    """Raise :class:`MissingDependencyError` before any work when ``feature`` cannot run.

    Parameters
    ----------
    extra : str
        The optional feature group, e.g. ``"cad"`` (build123d, for ``--label`` and ``--step``).
    feature : str
        What the user asked for, named as they asked (``"--step (STEP plates)"``).
    """
    if has_extra(extra):
        return
    module, requirement = EXTRAS[extra]
    error = MissingDependencyError(module, feature)
    # The install hint names the extra, which pins a build123d that voxfab was tested with.
    message = f"{feature} needs {module}, an optional part of voxfab: pip install '{requirement}'"
    error.args = (message,)
    error.msg = message  # ImportError's str() reads msg
    raise error
