"""Settings of the net search kernels, shared by their compiled and plain-Python copies."""

from __future__ import annotations

from typing import NamedTuple

MODE_RUIN = 0  # ruin-and-recreate, never restart
MODE_PAPER = 1  # published method: leaf swap, smallest subtree, restart


class Growth(NamedTuple):
    """How to grow: ``mode``, candidates per ``tour``nament, blocked options
    ``samples``d per dead end, chance ``p_lift`` of ruining further up the tree,
    repairs without progress before a paper-mode restart, and whether a dead
    end with no cheap repair may ruin a large subtree or ``restart`` (else
    growth stops there)."""

    mode: int
    tour: int
    samples: int
    p_lift: float
    restart_after: int
    restart: bool = True


class Annealing(NamedTuple):
    """Move schedule: temperatures ``t0`` to ``t1`` (in seams) over ``total``
    moves, growth steps a regrowth may spend, and the largest subtree a move
    may remove: ``ruin_cap`` mostly, ``big_cap`` with chance ``p_big`` (a seam
    whose faces and tab cells all lie on the trunk of the tree needs it), and
    the ``patience``: moves without a new best count after which the run ends
    early (0: never), since a fresh net then fixes its last seams sooner."""

    total: int
    t0: float
    t1: float
    regrow_steps: int
    ruin_cap: int
    big_cap: int = 0
    p_big: float = 0.0
    patience: int = 0
