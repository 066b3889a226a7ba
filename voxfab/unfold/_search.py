"""unfold / unfold_many: search for single-piece nets of a voxel surface."""

from __future__ import annotations

import dataclasses
import enum
import math
import time
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from voxfab._shared.progress import Meter, check_cancelled, meter
from voxfab._shared.rng import as_rng
from voxfab._shared.validate import as_grid, check_choice
from voxfab.errors import InvalidShapeError, NoNetExistsError, UnfoldError
from voxfab.shape import SurfaceGraph, cavity_count, component_count, fill_cavities, surface_graph

from ._constraints import EdgeConstraints, Resolved, check_one_piece, resolve
from ._layout import build_net, count_without_tab_room
from ._net import Net
from ._outline import outline_key
from ._params import MODE_PAPER, MODE_RUIN, Annealing, Growth

__all__ = ["NoFitError", "Strategy", "Pieces", "unfold", "unfold_many"]

#: Surfaces up to this many faces are searched by the plain-Python kernels.
_PURE_FACES = 150
#: Largest board side for a free (unfitted) net; past it growth meets a wall.
MAX_BOARD = 1021
#: Growth steps per compiled call between two clock checks.
_CHUNK = 4000
#: Tab-room repair: moves per face over all rounds (each round from a fresh
#: net), at most per round, and without a new best count before a round gives
#: up (its last seams are then cheaper to fix in a new net); moves per compiled
#: call between two clock checks.
_BUDGET_PER_FACE = 120
_MOVES_PER_FACE = 15
_PATIENCE_PER_FACE = 1.5
#: (The run continues across calls, so any chunk gives the same net; 500 moves of the queen take
#: about 10 ms, 40 ms on a busy machine, so the clock and a cancel are seen that soon.)
_ANNEAL_CHUNK = 500
#: Largest subtree one annealing move may remove.
_RUIN_CAP = 20  # most moves
_BIG_CAP = 200
_P_BIG = 0.1
#: Growth steps an annealing move may spend regrowing before it is undone.
_REGROW_STEPS = 2000
#: Annealing temperatures (in seams without tab room) at the start and the end.
#: A round mostly ends by patience within its first fifth of moves, so it runs
#: near ``_T0``: hot enough to accept most moves that add a seam, which walks
#: out of a crowded corner far sooner than a cooler search.
_T0, _T1 = 3.0, 0.05
#: Fitting a box: tries (alternating the two orientations) and growth steps per face each.
_FIT_TRIES = 6
_FIT_STEPS_PER_FACE = 200
#: Default overall budget of ``unfold_many`` in seconds.
DEFAULT_BUDGET = 60.0
#: Compactness: box-shrinking trials, and growth steps per face each trial may use.
_COMPACT_TRIES = 24
_COMPACT_STEPS_PER_FACE = 100


class Strategy(enum.StrEnum):
    """Search strategies."""

    DEFAULT = "default"
    PAPER = "paper"
    EXACT = "exact"


class Pieces(enum.StrEnum):
    """How many pieces a result may have."""

    ONE = "one"
    AUTO = "auto"
    FLAT = "flat"


def _settings(strategy: Strategy, faces: int) -> Growth:

    if strategy is Strategy.PAPER:
        return Growth(MODE_PAPER, 1, 0, 0.0, max(50, faces // 4))
    return Growth(MODE_RUIN, 3, 3, 0.05, 0)


def _surface(sg: SurfaceGraph, resolved: Resolved | None, kernels):  # noqa: ANN001, ANN202
    f = sg.face_count
    if resolved is None:
        none = np.zeros(0, dtype=np.int64)
        resolved = Resolved(np.zeros((f, 4), dtype=np.int8), np.full(f, -1, dtype=np.int64),
                            none, none, none, none, np.zeros(1, dtype=np.int64))
    return kernels.make_surface(sg.neighbor, sg.neighbor_edge, resolved.edge, resolved.group, resolved.gx,
                        resolved.gy, resolved.grot, resolved.members, resolved.start)


def _kernels(faces: int) -> tuple:
    """The kernel modules: compiled, or their plain-Python copy for small surfaces.

    Both run the same source with the same integer arithmetic, so a seed gives
    the same net either way; the copy only saves numba's start-up.
    """
    if faces > _PURE_FACES:
        from . import _board, _growth, _tabroom

        return _board, _growth, _tabroom
    import importlib
    import sys
    import types

    name = f"{__package__}._pure"
    if name not in sys.modules:
        pkg = types.ModuleType(name)
        pkg.__path__ = list(sys.modules[__package__].__path__)  # the same files, loaded again
        sys.modules[name] = pkg
    return tuple(importlib.import_module(f"{name}.{m}") for m in ("_board", "_growth", "_tabroom"))


def _quiet() -> np.errstate:
    # The plain-Python kernels' random numbers wrap around uint64 on purpose.
    return np.errstate(over="ignore")


def count_seams(board: _Board) -> int:
    """Seams without tab room of a board's complete net (used after a fallback)."""
    k = board.k
    face, half, b, cnt, _ = board.b
    n = int(k.track_seams(board.sf.link, face, half, b, cnt))
    cnt[k.C_TRACK] = 0
    return n


class _Board:
    """Search state for the faces of one piece on one board."""

    def __init__(self, sg: SurfaceGraph, faces: npt.NDArray[np.int64], seed: int | list[int],
                 fit: tuple[int, int] | None, resolved: Resolved | None = None,
                 kernel_faces: int | None = None) -> None:
        # ``kernel_faces`` picks the kernels by a larger search than this board
        # (the pieces of one surface): many small boards add up.
        _board, _growth, _tabroom = _kernels(faces.size if kernel_faces is None else kernel_faces)
        self.k = _board
        self.growth = _growth
        self.tabroom = _tabroom
        if fit is None:
            side = min(2 * faces.size + 1, MAX_BOARD)
            w, h = side, side
        else:
            w, h = fit
        self.width = w + 2
        board = np.full((h + 2, w + 2), -2, dtype=np.int64)
        board[1:-1, 1:-1] = -1
        if fit is None:
            cells = np.array([(h // 2 + 1) * self.width + w // 2 + 1], dtype=np.int64)
        else:
            ys, xs = np.nonzero(board == -1)
            cells = (ys * self.width + xs).astype(np.int64)
        state = np.random.SeedSequence(seed).generate_state(1, dtype=np.uint64)[0]
        self.sf = _surface(sg, resolved, _board)
        self.b = _board.make_board(faces, sg.face_count, board.ravel(), self.width, cells,
                                   int(state), resolved is not None)
        self.cnt = self.b.cnt
        self.faces = faces
        self.started = self.restart()

    def restart(self) -> bool:
        """Empty the board and lay a random root; False when no root fits."""
        self.cnt[self.k.C_ROOT] = -1  # grow starts a board without a root
        with _quiet():
            self.growth.grow(*self.sf, *self.b, _settings(Strategy.DEFAULT, 1), 0, False)
        return int(self.cnt[self.k.C_ROOT]) >= 0

    @property
    def pos(self) -> npt.NDArray[np.int64]:
        return self.b.face[:, self.k.POS]

    @property
    def rot(self) -> npt.NDArray[np.int64]:
        return self.b.face[:, self.k.ROT]

    @property
    def par(self) -> npt.NDArray[np.int64]:
        return self.b.face[:, self.k.PAR]

    @property
    def unplaced(self) -> int:
        return int(self.cnt[self.k.C_UNPLACED])

    @property
    def best(self) -> int:
        return int(self.cnt[self.k.C_BEST])

    def grow(self, gw, deadline: float, max_steps: int | None = None, bar: Meter | None = None) -> bool:
        """Grow until every face is placed; False when the clock or ``max_steps`` runs out.

        ``bar`` counts the faces of the largest partial net so far.
        """
        spent = 0
        if not self.started:
            return False
        while self.unplaced > 0:
            check_cancelled()  # between compiled chunks: a cancelled job stops within milliseconds
            if time.monotonic() > deadline or (max_steps is not None and spent >= max_steps):
                return False
            chunk = _CHUNK if max_steps is None else min(_CHUNK, max_steps - spent)
            with _quiet():
                done = self.growth.grow(*self.sf, *self.b, gw, chunk, False)
            if not done and self.unplaced == self.faces.size:
                return False  # a restart found no room for a root
            spent += chunk
            if bar is not None:
                bar.update(max(self.best, int(self.faces.size) - self.unplaced) - bar.done)
        return True

    def extent(self) -> tuple[int, int]:
        """Width and height in cells of the placed faces."""
        placed = self.pos[self.pos >= 0]
        x, y = placed % self.width, placed // self.width
        return int(x.max() - x.min() + 1), int(y.max() - y.min() + 1)

    def anneal_budget(self) -> int:
        """Moves of tab-room repair allowed for this many faces (over all rounds)."""
        return _BUDGET_PER_FACE * int(self.faces.size)

    def exclude_unplaced(self) -> None:
        """Make the placed faces a whole piece: the others are left out for good."""
        with _quiet():
            self.k.exclude_unplaced(*self.sf, *self.b[:4])
        self.faces = np.flatnonzero(self.pos >= 0)

    def anneal(self, gw, deadline: float, bar: Meter | None = None) -> int:
        """Drive seams without tab room to zero; return the count reached.

        Rounds of annealing, each from a freshly grown net when the one before
        got stuck (the last few seams are often cheaper to fix in a new net than
        in an old one), all within a fixed number of moves, so the outcome
        depends on the seed alone unless the clock runs out first.  The state
        ends at the best net seen.  ``bar`` counts the moves tried.
        """
        face, half, board, cnt, _ = self.b
        best = np.zeros((face.shape[0], 3), dtype=np.int64)
        kept: tuple[int, np.ndarray, int] | None = None
        left = -1
        grown = (self.pos.copy(), self.rot.copy(), self.par.copy())
        budget = self.anneal_budget()
        spent = 0
        while spent < budget:
            if spent:
                self.restart()
                if not self.grow(gw, deadline, _FIT_STEPS_PER_FACE * int(self.faces.size)):
                    break
            left, used = self._anneal_round(gw, deadline, best, budget - spent, bar)
            spent += max(used, 1)
            if not self._whole():
                break  # never keep a broken tree (a safety net: should not happen)
            if kept is None or left < kept[0]:
                kept = (left, best.copy(), int(cnt[self.k.C_ROOT]))
            if left == 0 or time.monotonic() > deadline:
                break
        if kept is None:  # no round ended whole: back to the net as grown
            self.k.restore(face, half, board, cnt, np.stack(grown, axis=1))
            return count_seams(self)
        if kept[0] < left or not self._whole():
            self.k.restore(face, half, board, cnt, kept[1])
            cnt[self.k.C_ROOT] = kept[2]
        return kept[0]

    def _whole(self) -> bool:
        """Whether the placed faces are all the faces and form one tree."""
        pos, par = self.pos[self.faces], self.par
        if (pos < 0).any():
            return False
        up = par[self.faces]
        if np.count_nonzero(up < 0) != 1 or (self.pos[up[up >= 0]] < 0).any():
            return False
        anc = np.where(par >= 0, par, -1)
        for _ in range(int(self.faces.size).bit_length() + 1):  # pointer doubling finds cycles
            anc = np.where(anc >= 0, anc[np.maximum(anc, 0)], -1)
        return bool((anc < 0).all())

    def _anneal_round(self, gw, deadline: float, best: np.ndarray, most: int,
                      bar: Meter | None) -> tuple[int, int]:
        """One annealing run of at most ``most`` moves; returns the best count and the moves used."""
        tr = self.tabroom
        face, half, board, cnt, _ = self.b
        n = int(self.faces.size)
        total = min(_MOVES_PER_FACE * n, most)
        sched = Annealing(total, _T0, _T1, _REGROW_STEPS, _RUIN_CAP, _BIG_CAP, _P_BIG,
                          int(_PATIENCE_PER_FACE * n))
        gw = gw._replace(restart=False)  # a move that cannot regrow cheaply is undone instead
        cnt[self.k.C_TRACK] = 0
        done = spent = 0
        while True:
            check_cancelled()
            step = min(_ANNEAL_CHUNK, total - done)
            with _quiet():
                used = tr.anneal(*self.sf, *self.b, gw, sched, step, done, best)
            if bar is not None:
                bar.update(used)
            done += step
            spent += used
            if not cnt[self.k.C_TRACK]:
                break  # the run ended: no seam left, its last move done, or out of patience
            if time.monotonic() > deadline:
                tr.finish(face, half, board, cnt, best)
                break
        return int(cnt[self.k.C_BESTBAD]), spent

    def net(self, sg: SurfaceGraph, *, faces: npt.NDArray[np.int64] | None = None,
            seed: int, strategy: str) -> Net:
        cell = np.stack([self.pos % self.width, self.pos // self.width], axis=1)
        chosen = np.flatnonzero(self.pos >= 0) if faces is None else faces
        return build_net(sg, chosen, cell, self.rot, self.par, seed=seed, strategy=strategy)


def _surface_parts(sg: SurfaceGraph, faces: npt.NDArray[np.int64] | None = None) -> list[npt.NDArray[np.int64]]:
    """Face indices of each connected part of the surface (or of ``faces``), in order of first face."""
    f = sg.face_count
    inside = np.ones(f, dtype=bool)
    if faces is not None:
        inside[:] = False
        inside[faces] = True
    nb = sg.neighbor
    joined = inside[:, None] & inside[nb]
    # Each face takes the smallest label among itself and its neighbours, with
    # pointer jumping; plain numpy keeps scipy.sparse out of the start-up time.
    label = np.arange(f)
    while True:
        new = np.minimum(label, np.where(joined, label[nb], f).min(axis=1))
        new = new[new]
        if np.array_equal(new, label):
            break
        label = new
    chosen = np.flatnonzero(inside)
    return [chosen[label[chosen] == lab] for lab in dict.fromkeys(label[chosen].tolist())]


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
            "pieces='auto' (CLI --pieces auto) for one net per surface"
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


def _seed_of(rng: np.random.Generator | int) -> int:
    if isinstance(rng, (int, np.integer)) and not isinstance(rng, bool):
        as_rng(rng)  # validates the seed
        return int(rng)
    return int(as_rng(rng).integers(0, 2**31 - 1))


class NoFitError(UnfoldError):
    """No one-piece net fits the requested box within the budget.

    Attributes
    ----------
    best_extent : (int, int)
        Sides in cells of the most compact net layout found, the shorter first.
    """

    def __init__(self, message: str, best_extent: tuple[int, int]) -> None:
        super().__init__(message)
        self.best_extent = best_extent


@dataclasses.dataclass(frozen=True)
class _Job:
    """One search: the shape, its surface and the options every step reads."""

    grid: npt.NDArray[np.bool_]
    sg: SurfaceGraph
    seed: int
    strategy: Strategy
    fit: tuple[int, int] | None
    tab_aware: bool
    compact: bool
    deadline: float
    timeout: float
    constraints: EdgeConstraints | None
    flat: bool = False

    def growth(self, faces: int):
        return _settings(self.strategy, faces)

    def resolved(self, faces: npt.NDArray[np.int64]) -> Resolved | None:
        return resolve(self.constraints, self.sg, faces)

    def net(self, board: _Board, faces: npt.NDArray[np.int64]) -> Net:
        net = board.net(self.sg, faces=faces, seed=self.seed, strategy=self.strategy.value)
        return dataclasses.replace(net, seams_without_tab_room=count_without_tab_room(self.grid, net))


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
        run, whatever ``rng``, and no tab-room repair.
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
    pieces : {"one", "auto", "flat"}
        ``"one"``: return one Net or raise UnfoldError.  ``"auto"``: always return a
        list of Nets, as few pieces as the budget allows: one per separate
        surface part (cavity walls, separate components), and when no one-piece
        net fits ``fit`` few large pieces that each fit it, none of a surface
        part's pieces under a tenth of its largest (UnfoldError when no such
        split is found).  ``"flat"``: like ``"auto"``, but the pieces are grown
        from whole flat patches of the surface, each as compact as the surface
        itself, with room for a tab at every seam: more pieces that pack densely
        on sheets (with constraints or without ``fit``, as ``"auto"``).  Face ``i`` of a piece is then
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
    min_box = _check_exact(strat, mode, fit, compact, min_box, bool(zipper))
    if zipper and strat is not Strategy.EXACT:
        raise InvalidShapeError("zipper (CLI --zipper) needs strategy 'exact'")
    if not float(timeout) > 0:
        raise InvalidShapeError(f"timeout: expected a positive number of seconds, got {timeout!r}")
    seed = _seed_of(rng)
    if constraints is not None and not isinstance(constraints, EdgeConstraints):
        raise InvalidShapeError(
            f"constraints: expected EdgeConstraints, got {type(constraints).__name__}")
    g = _prepare(grid, fill, mode)
    deadline = time.monotonic() + float(timeout)
    sg = surface_graph(g)
    resolved = resolve(constraints, sg)  # every named edge must be on this surface
    if strat is Strategy.EXACT and fit is not None:
        try:  # each is a proof that no net fits the box, found without a search
            _check_groups_fit(resolved, fit)
            check_one_piece(sg, resolved)
        except UnfoldError as exc:
            raise NoNetExistsError(*fit, why=str(exc)) from None
    _check_groups_fit(resolved, fit)
    job = _Job(g, sg, seed, strat, fit, tab_aware, compact, deadline, float(timeout), constraints,
               mode is Pieces.FLAT)
    parts = _surface_parts(sg)
    if strat is Strategy.EXACT:
        if len(parts) > 1:
            _refuse_parts(g, len(parts))
        check_one_piece(sg, resolved)
        return dataclasses.replace(_exact_piece(job, parts[0], resolved, min_box, bool(zipper)), filled=fill)
    if mode is Pieces.ONE:
        if len(parts) > 1:
            _refuse_parts(g, len(parts))
        check_one_piece(sg, resolved)  # in milliseconds, not after the whole budget
        return dataclasses.replace(_one_piece(job, parts[0]), filled=fill)
    # Imported here: the piece splitter builds on this module's boards and jobs.
    from ._pieces import split

    nets: list[Net] = []
    for t, part in enumerate(parts):
        remaining = max(deadline - time.monotonic(), 0.0)
        part_job = dataclasses.replace(job, seed=seed + t,
                                       deadline=time.monotonic() + remaining / (len(parts) - t))
        nets.extend(split(part_job, part))
    return [dataclasses.replace(n, filled=fill) for n in nets]


def _check_exact(strat: Strategy, mode: Pieces, fit: tuple[int, int] | None, compact: bool,
                 min_box: bool, zipper: bool = False) -> bool:
    """Refuse options the exact strategy has no meaning for, before any work; return ``min_box``.

    ``compact`` without a box asks the exact strategy for the least-area box
    (what compactness means to it), so callers that shrink a net (the sheet's
    automatic face size) work with it unchanged.  ``zipper`` needs no box: any
    zipper net, or a proof that the shape has none.
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
    min_box = min_box or (compact and fit is None)
    if fit is None and not min_box and not zipper:
        raise InvalidShapeError("strategy 'exact' needs a box: fit=(W, H) (CLI --box WxH) or min_box "
                                "(CLI --min-box)")
    return min_box


def _exact_piece(job: _Job, faces: npt.NDArray[np.int64], resolved: Resolved | None, min_box: bool,
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


def _growth_hint(job: _Job, faces: npt.NDArray[np.int64], resolved: Resolved | None):  # noqa: ANN202
    """A net in the box from ruin-and-recreate growth with seed 0, or None: the exact search's starting point.

    A fixed seed and a fixed budget of growth steps in each orientation (no
    clock) make the hint, and so the exact result, the same on every run.
    """
    from ._exact import ExactLayout

    n = int(faces.size)
    w, h = job.fit
    if w * h < n:
        return None
    for t, box in enumerate(_orientations((w, h))):
        b = _Board(job.sg, faces, [0, t], box, resolved)
        # Bounded by steps, not by the clock: a slow run must not change the hint.
        if not b.grow(_settings(Strategy.DEFAULT, n), math.inf, _FIT_STEPS_PER_FACE * n):
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


def _one_piece(job: _Job, faces: npt.NDArray[np.int64]) -> Net:
    p = job.growth(faces.size)
    resolved = job.resolved(faces)
    if job.fit is not None:
        b = _grow_to_fit(job, faces, resolved)
    else:
        b = _Board(job.sg, faces, job.seed, None, resolved)
        with meter(int(faces.size), desc="net: faces placed") as bar:
            grown = b.grow(p, job.deadline, bar=bar)
        if not grown:
            raise UnfoldError(
                f"no one-piece net of the {faces.size}-face surface in {job.timeout:g} s with "
                f"strategy {job.strategy.value!r}: {int(b.cnt[b.k.C_DEADENDS])} dead ends repaired, "
                f"{int(b.cnt[b.k.C_RESTARTS])} restarts, best partial net {b.best} of "
                f"{faces.size} faces; raise the timeout, try another seed, or allow several "
                "pieces (pieces='auto', CLI --pieces auto)"
            )
    if job.compact:
        b = _compact(job, faces, b, resolved)
    if job.tab_aware and job.strategy is Strategy.DEFAULT:
        with meter(b.anneal_budget(), desc="net: tab room, moves (at most)") as bar:
            b.anneal(p, job.deadline, bar=bar)
    return job.net(b, faces)


def _orientations(fit: tuple[int, int]) -> list[tuple[int, int]]:
    w, h = fit
    return [(w, h)] if w == h else [(w, h), (h, w)]


def _grow_to_fit(job: _Job, faces: npt.NDArray[np.int64], resolved: Resolved | None) -> _Board:
    """Grow a net inside the fit box (either way round); NoFitError when none fits.

    The box's walls steer growth: ruin-and-recreate packs the faces into it.
    Each try has a fixed budget of growth steps, so the outcome depends on the
    seed alone unless the clock runs out first.
    """
    n = int(faces.size)
    p = job.growth(n)
    fit = job.fit
    if fit[0] * fit[1] >= n:
        with meter(_FIT_TRIES, desc="net: tries to fit the box") as bar:
            for t in range(_FIT_TRIES):
                box = _orientations(fit)[t % len(_orientations(fit))]
                trial = _Board(job.sg, faces, job.seed if t == 0 else [job.seed, 1000 + t], box, resolved)
                if trial.grow(p, job.deadline, _FIT_STEPS_PER_FACE * n):
                    return trial
                bar.update()
                if time.monotonic() > job.deadline:
                    break
    extent = _best_extent(job, faces, resolved)
    why = (f"the surface has {n} faces, more than the {fit[0]}x{fit[1]} = {fit[0] * fit[1]} cells "
           "of the box" if fit[0] * fit[1] < n else
           f"no one-piece net of the {n}-face surface fits {fit[0]}x{fit[1]} cells (either way "
           "round) within the budget")
    raise NoFitError(
        f"{why}; the most compact net found spans {extent[0]}x{extent[1]} cells: use a larger "
        "sheet, smaller faces, or several pieces (pieces='auto')", extent)


def _best_extent(job: _Job, faces: npt.NDArray[np.int64], resolved: Resolved | None) -> tuple[int, int]:
    """Sides (shorter first) of the most compact net found within the budget."""
    free = _Board(job.sg, faces, job.seed, None, resolved)
    if not free.grow(job.growth(faces.size), job.deadline):
        raise UnfoldError(
            f"no one-piece net of the {faces.size}-face surface in {job.timeout:g} s, so none "
            f"that fits {job.fit[0]}x{job.fit[1]}; raise the timeout or try another seed")
    w, h = _compact(job, faces, free, resolved).extent()
    return (min(w, h), max(w, h))


def _compact(job: _Job, faces: npt.NDArray[np.int64], board: _Board, resolved: Resolved | None) -> _Board:
    """Shrink the net's bounding box while a fixed growth budget still fits it.

    Each trial grows a new net inside the current box with its longer side cut
    by about a tenth; two failures in a row end the search.  Budgets are counted
    in growth steps, so the result depends on the seed alone (unless the clock
    runs out first).
    """
    p = job.growth(faces.size)
    best = board
    failures = 0
    for t in range(_COMPACT_TRIES):
        w, h = best.extent()
        if (w >= h) != (failures % 2 == 1):
            w = min(w - 1, int(w * 0.9))
        else:
            h = min(h - 1, int(h * 0.9))
        if w < 1 or h < 1 or w * h < faces.size or time.monotonic() > job.deadline:
            break
        trial = _Board(job.sg, faces, [job.seed, t + 1], (w, h), resolved)
        if trial.grow(p, job.deadline, _COMPACT_STEPS_PER_FACE * int(faces.size)):
            best, failures = trial, 0
        else:
            failures += 1
            if failures == 2:
                break
    return best


def unfold_many(
    grid: npt.ArrayLike,
    *,
    count: int,
    rng: np.random.Generator | int,
    budget: float = DEFAULT_BUDGET,
    progress: Callable[[int, int], None] | None = None,
    **options: object,
) -> list[Net]:
    """Find up to ``count`` nets that look different on the sheet.

    Net ``t`` is ``unfold(grid, rng=seed_t, **options)`` for seeds drawn from
    ``rng``; a net whose outline (the cells it covers and where it is folded or
    cut, see :func:`outline_key`) matches an earlier one's under the 8 rotations
    and mirrors of the sheet is skipped.  ``timeout`` (in ``options``) bounds
    each net, ``budget`` the whole call.

    Parameters
    ----------
    count : int
        Nets wanted.
    budget : float
        Seconds for the whole call.  The search also stops after ``4 * count +
        8`` seeds, so a surface with few nets ends early.
    progress : callable, optional
        ``progress(found, count)`` after each new net.

    Returns
    -------
    list of Net
        Between 1 and ``count`` nets with pairwise different outlines; its
        length says how many were found.

    Raises
    ------
    UnfoldError
        Not a single net was found within the budget.
    """
    n = _check_count(count)
    if not float(budget) > 0:
        raise InvalidShapeError(f"budget: expected a positive number of seconds, got {budget!r}")
    if options.get("pieces", "one") != "one":
        raise InvalidShapeError("unfold_many: pieces must be 'one'")
    if str(options.get("strategy", "default")) == Strategy.EXACT.value:
        raise InvalidShapeError("strategy 'exact' gives one net, the same every run: ask for one net")
    gen = np.random.default_rng(_seed_of(rng))
    end = time.monotonic() + float(budget)
    timeout = float(options.pop("timeout", 60.0))  # type: ignore[arg-type]
    nets: list[Net] = []
    seen: set[bytes] = set()
    tries = 0
    last_error: UnfoldError | None = None
    with meter(n, desc="nets") as bar:
        while len(nets) < n and tries < 4 * n + 8:
            left = end - time.monotonic()
            if left <= 0:
                break
            tries += 1
            seed = int(gen.integers(0, 2**31 - 1))
            try:
                net = unfold(grid, rng=seed, timeout=min(timeout, left), **options)  # type: ignore[arg-type]
            except NoFitError:
                raise
            except UnfoldError as exc:
                last_error = exc
                continue
            key = outline_key(net)
            if key in seen:
                continue
            seen.add(key)
            nets.append(net)
            bar.update()
            if progress is not None:
                progress(len(nets), n)
    if not nets:
        raise last_error or UnfoldError(f"no net found within the budget of {budget:g} s")
    return nets


def _check_count(count: object) -> int:
    if not isinstance(count, (int, np.integer)) or isinstance(count, bool) or count < 1:
        raise InvalidShapeError(f"count: expected an integer >= 1, got {count!r}")
    return int(count)
