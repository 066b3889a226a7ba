"""unfold: a net of a voxel shape, in one piece or in several: the options checked, then the search they ask for."""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
import numpy.typing as npt

from voxfab._shared.progress import meter
from voxfab._shared.validate import as_grid, check_choice
from voxfab.errors import InvalidShapeError, NoNetExistsError, UnfoldError
from voxfab.shape import cavity_count, component_count, fill_cavities, surface_graph

from ._constraints import EdgeConstraints, Resolved, check_one_piece, resolve
from ._job import (
    FIT_STEPS_PER_FACE,
    Job,
    Pieces,
    Strategy,
    growth_settings,
    orientations,
    seed_of,
    surface_parts,
)
from ._layout import build_net, count_without_tab_room
from ._net import Net
from ._onepiece import one_piece
from ._searchboard import SearchBoard

__all__ = ["unfold"]


#: Longest side of a box a net is searched in, faces (far beyond any voxfab surface's net).
MAX_FIT_SIDE = 4096


def _check_fit(fit: tuple[int, int] | None) -> tuple[int, int] | None:
    if fit is None:
        return None
    try:
        w, h = (int(v) for v in fit)
    except (TypeError, ValueError):
        raise InvalidShapeError(f"fit: expected (width, height) in voxels, got {fit!r}") from None
    if w < 1 or h < 1 or w > MAX_FIT_SIDE or h > MAX_FIT_SIDE:
        raise InvalidShapeError(f"fit: expected sides in 1..{MAX_FIT_SIDE} voxels, got {w}x{h}")
    return w, h


def _prepare(grid: npt.ArrayLike, fill: bool, pieces: Pieces) -> npt.NDArray[np.bool_]:
    g = as_grid(grid)
    parts = component_count(g)
    if parts > 1 and pieces is Pieces.ONE:
        raise UnfoldError(
            f"the shape is not 6-connected: it has {parts} pieces joined at most by edges or "
            "corners, so no one-piece net exists; keep the largest piece or ask for "
            "pieces='auto' (CLI --pieces auto) for one net per part, or join the parts (CLI --join)"
        )
    return fill_cavities(g) if fill else g


def _refuse_parts(g: npt.NDArray[np.bool_], parts: int) -> None:
    """Explain why a 6-connected solid has ``parts`` > 1 separate surfaces."""
    cav = cavity_count(g)
    raise UnfoldError(
        f"the solid has {cav} enclosed cavit{'y' if cav == 1 else 'ies'}, so it has {parts} "
        "separate surfaces and no one-piece net exists; fill the cavities "
        "(fill=True, CLI --fill) or ask for one net per surface (pieces='auto', "
        "CLI --pieces auto)"
    )


def unfold(
    grid: npt.ArrayLike,
    *,
    rng: np.random.Generator | int,
    strategy: str | Strategy = "default",
    timeout: float = 60.0,
    fit: tuple[int, int] | None = None,
    tab_aware: bool = True,
    fill: bool = False,
    pieces: str | Pieces = "one",
    compact: bool = False,
    constraints: EdgeConstraints | None = None,
    min_box: bool = False,
    zipper: bool = False,
) -> Net | list[Net]:
    """Find a net of a voxel shape: its surface cut along voxel edges and laid flat.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        A 6-connected shape, indexed ``[x, y, z]``.
    rng : int or numpy Generator
        Seed.  The same int seed gives the identical net (unless the search runs
        into ``timeout``); different seeds give different nets.
    strategy : {"default", "paper", "exact"}
        ``"default"``: ruin-and-recreate growth (a dead end removes the subtree on
        the blocking cell and lays the blocked face there), then tab-room
        repair.  ``"paper"``: the published random growth with leaf swaps,
        subtree drops and restarts, for comparison.  ``"exact"``: a complete
        search (CP-SAT, needs the ``ortools`` package) inside ``fit``, or for the
        least-area box with ``min_box``: it finds a net or proves that none
        exists (:class:`~voxfab.errors.NoNetExistsError`); the same net on every
        run, whatever ``rng``, and no tab-room repair.  With neither (nor
        ``zipper``), in a box that holds every one-piece net of the surface
        (:func:`voxfab.unfold._exact.any_box`), where a net always exists.
    timeout : float
        Budget in seconds for the whole call.
    fit : (int, int) or None
        A box of ``width × height`` cells (face units) the net must lie in,
        turned by 90 degrees if that fits better.  The search grows the net
        inside the box (its walls steer growth towards a compact layout) and
        keeps it there while making tab room.
    tab_aware : bool
        Drive the seams without tab room towards zero (default strategy only);
        the final count is in ``Net.seams_without_tab_room``.
    fill : bool
        Fill enclosed cavities first (their surfaces cannot join the outer one).
    pieces : {"one", "auto", "flat", "bands"}
        ``"one"``: return one Net or raise UnfoldError.  ``"auto"``: always return a
        list of Nets, as few pieces as the budget allows: one per separate
        surface part (cavity walls, separate components), and when no one-piece
        net fits ``fit`` few large pieces that each fit it, none of a surface
        part's pieces under a tenth of its largest (UnfoldError when no such
        split is found).  ``"flat"``: like ``"auto"``, but the pieces are grown
        from whole flat patches of the surface, each as compact as the surface
        itself, with room for a tab at every seam: more pieces that pack densely
        on sheets (with constraints or without ``fit``, as ``"auto"``).  ``"bands"``: like ``"flat"``, but
        the side faces across an axis are cut into rows round the shape, each laid flat as a straight
        strip, strips stacked into rectangles where the wall goes straight on (:mod:`._bands`); the
        axis with the fewest seams wins.  Face ``i`` of a piece is then
        *not* face ``i`` of the surface graph: faces are identified by
        ``(voxel, normal)``.
    compact : bool
        Shrink the net's bounding box: new nets are grown inside ever smaller
        boxes (the longer side first) while one is found within a fixed growth
        budget; tab-room repair then stays inside the final box.  One-piece
        results only.
    constraints : EdgeConstraints, optional
        Edges to cut (never folds) and edges to keep (always folds: the faces
        they join move as one rigid group during the search).
    zipper : bool
        Exact strategy only: the cut edges must form one path (an unzipping);
        without ``fit`` or ``min_box``, in a box of any size
        (:mod:`voxfab.unfold._zipper`).
    min_box : bool
        Exact strategy only, instead of ``fit``: the net whose bounding box has
        the least area, every smaller area proved to have none (``compact``
        without ``fit`` means the same to the exact strategy).

    Returns
    -------
    Net or list of Net
        Face ``i`` of a one-piece net is face ``i`` of ``surface_graph(grid)``.

    Raises
    ------
    NoNetExistsError
        Exact strategy: no one-piece net fits ``fit`` (proved).
    NoFitError
        No one-piece net fits ``fit`` within the budget; ``best_extent`` gives
        the most compact layout found.
    UnfoldError
        The shape has cavities or several components (with ``pieces="one"``),
        kept edges cannot all be folds, or the budget ran out; the message says
        what was tried.
    InvalidShapeError
        A bad option, or a constrained edge that is not an edge of the surface.
    """
    strat = check_choice(strategy, Strategy, name="strategy")
    mode = check_choice(pieces, Pieces, name="pieces")
    fit = _check_fit(fit)
    min_box = _check_exact(strat, mode, fit, compact, min_box)
    if zipper and strat is not Strategy.EXACT:
        raise InvalidShapeError("zipper (CLI --zipper) needs strategy 'exact'")
    if not float(timeout) > 0:
        raise InvalidShapeError(f"timeout: expected a positive number of seconds, got {timeout!r}")
    seed = seed_of(rng)
    if constraints is not None and not isinstance(constraints, EdgeConstraints):
        raise InvalidShapeError(
            f"constraints: expected EdgeConstraints, got {type(constraints).__name__}")
    g = _prepare(grid, fill, mode)
    deadline = time.monotonic() + float(timeout)
    sg = surface_graph(g)
    resolved = resolve(constraints, sg)  # every named edge must be on this surface
    asked = fit
    if strat is Strategy.EXACT and fit is None and not (min_box or zipper):
        from ._exact import any_box

        # No box in particular: one that holds every net of the surface, so the
        # search finds one (the same on every run) and has nothing to prove.
        fit = any_box(sg.face_count)
    if strat is Strategy.EXACT and fit is not None:
        try:  # each is a proof that no net fits the box, found without a search
            _check_groups_fit(resolved, fit)
            check_one_piece(sg, resolved)
        except UnfoldError as exc:
            raise NoNetExistsError(*(asked or (None, None)), why=str(exc)) from None
    _check_groups_fit(resolved, fit)
    job = Job(g, sg, seed, strat, fit, tab_aware, compact, deadline, float(timeout), constraints,
              mode is Pieces.FLAT, mode is Pieces.BANDS)
    parts = surface_parts(sg)
    if strat is Strategy.EXACT:
        if len(parts) > 1:
            _refuse_parts(g, len(parts))
        check_one_piece(sg, resolved)
        return dataclasses.replace(_exact_piece(job, parts[0], resolved, min_box, bool(zipper)), filled=fill)
    if mode is Pieces.ONE:
        if len(parts) > 1:
            _refuse_parts(g, len(parts))
        check_one_piece(sg, resolved)  # in milliseconds, not after the whole budget
        return dataclasses.replace(one_piece(job, parts[0]), filled=fill)
    from ._pieces import split  # here: a search for one piece (a command's usual one) never cuts pieces

    nets: list[Net] = []
    for t, part in enumerate(parts):
        remaining = max(deadline - time.monotonic(), 0.0)
        part_job = dataclasses.replace(job, seed=seed + t,
                                       deadline=time.monotonic() + remaining / (len(parts) - t))
        nets.extend(split(part_job, part))
    return [dataclasses.replace(n, filled=fill) for n in nets]


def _check_exact(strat: Strategy, mode: Pieces, fit: tuple[int, int] | None, compact: bool,
                 min_box: bool) -> bool:
    """Refuse options the exact strategy has no meaning for, before any work; return ``min_box``.

    ``compact`` without a box asks the exact strategy for the least-area box
    (what compactness means to it), so callers that shrink a net (the sheet's
    automatic face size) work with it unchanged.
    """
    if strat is not Strategy.EXACT:
        if min_box:
            raise InvalidShapeError("min_box (CLI --min-box) needs strategy 'exact'")
        return False
    if mode is not Pieces.ONE:
        raise InvalidShapeError("strategy 'exact' finds one-piece nets only: pieces must be 'one'")
    if fit is not None and min_box:
        raise InvalidShapeError("strategy 'exact': give a box (fit, CLI --box WxH) or min_box (CLI --min-box), "
                                "not both")
    return min_box or (compact and fit is None)


def _exact_piece(job: Job, faces: npt.NDArray[np.int64], resolved: Resolved | None, min_box: bool,
                 zipper: bool) -> Net:
    """The exact strategy's net of one surface part (no seed: recorded as 0)."""
    from ._exact import exact_layout, min_box_layout
    from ._validate import validate

    with meter(1, desc="net: exact search") as bar:
        if min_box:
            lay = min_box_layout(job.sg, faces, resolved, job.deadline, zipper)
        elif job.fit is None:  # a zipper net in any box
            from ._zipper import zipper_layout

            if resolved is not None:
                raise InvalidShapeError("strategy 'exact': a zipper net with edge constraints needs a box "
                                        "(fit, CLI --box WxH)")
            lay = zipper_layout(job.sg, faces, job.deadline)
        else:
            hint = None if zipper else _growth_hint(job, faces, resolved)
            lay = exact_layout(job.sg, faces, resolved, job.fit, job.deadline, zipper, hint)
        bar.update()
    net = build_net(job.sg, faces, lay.cell, lay.rot, lay.parent, seed=0, strategy=Strategy.EXACT.value)
    # The independent refold: a net the model let through but the validator
    # refuses would be a bug in the model, never a net to hand out.
    net = dataclasses.replace(net, seams_without_tab_room=count_without_tab_room(job.grid, net))
    validate(job.grid, net, constraints=job.constraints, strict=True)
    return net


def _growth_hint(job: Job, faces: npt.NDArray[np.int64], resolved: Resolved | None):  # noqa: ANN202
    """A net in the box from ruin-and-recreate growth with seed 0, or None: the exact search's starting point.

    A fixed seed and a fixed budget of growth steps in each orientation (no
    clock) make the hint, and so the exact result, the same on every run.
    """
    from ._exact import ExactLayout

    n = int(faces.size)
    w, h = job.fit
    if w * h < n:
        return None
    for t, box in enumerate(orientations((w, h))):
        b = SearchBoard(job.sg, faces, [0, t], box, resolved)
        # Bounded by steps, not by the clock: a slow run must not change the hint.
        if not b.grow(growth_settings(Strategy.DEFAULT, n), math.inf, FIT_STEPS_PER_FACE * n):
            continue
        x, y = b.pos % b.width - 1, b.pos // b.width - 1  # inside the board's wall
        rot, par = b.rot.copy(), b.par.copy()
        if t == 1:  # grown in the box turned: turn the net back a quarter turn clockwise
            x, y = y, h - 1 - x
            rot = (rot + 3) % 4
        cell = np.stack([x, y], axis=1)
        return ExactLayout(cell, rot, par, (w, h))
    return None


def _check_groups_fit(resolved: Resolved | None, fit: tuple[int, int] | None) -> None:
    """Refuse kept groups that cannot lie inside ``fit`` in either orientation."""
    if resolved is None or fit is None:
        return
    for g in range(resolved.start.size - 1):
        m = resolved.members[resolved.start[g]:resolved.start[g + 1]]
        w = int(np.ptp(resolved.gx[m])) + 1
        h = int(np.ptp(resolved.gy[m])) + 1
        if not ((w <= fit[0] and h <= fit[1]) or (h <= fit[0] and w <= fit[1])):
            raise UnfoldError(
                f"the {m.size} faces kept together by the constraints span {w}x{h} cells laid "
                f"flat, so they do not fit inside {fit[0]}x{fit[1]}")
