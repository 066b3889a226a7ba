"""unfold / unfold_many: search for single-piece nets of a voxel surface."""

from __future__ import annotations

import dataclasses
import enum
import math
import time

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
#: pieces="auto": the smallest piece as a share of the largest (by faces), and
#: branches of a neighbour a too-small piece may try to take.
_MIN_SHARE = 0.1
_BRANCH_TRIES = 24
#: pieces="auto": pairs of neighbouring pieces tried for a join (once the
#: size rule holds).
_JOIN_TRIES = 24
#: pieces="auto" in a box: faces of a piece as a share of the box's cells.  The
#: cells left free take the glue tabs (up to four each, one from every side),
#: so a denser piece leaves seams without room.
_PIECE_SHARE = 0.5
#: Tries (each a fixed budget of growth steps) to lay one piece in its box
#: before it is cut in two.
_PIECE_TRIES = 3


class Strategy(enum.StrEnum):
    """Search strategies."""

    DEFAULT = "default"
    PAPER = "paper"
    EXACT = "exact"


class Pieces(enum.StrEnum):
    """How many pieces a result may have."""

    ONE = "one"
    AUTO = "auto"


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


def _check_fit(fit: tuple[int, int] | None) -> tuple[int, int] | None:
    if fit is None:
        return None
    try:
        w, h = (int(v) for v in fit)
    except (TypeError, ValueError):
        raise InvalidShapeError(f"fit: expected (width, height) in voxels, got {fit!r}") from None
    if w < 1 or h < 1 or w > 4096 or h > 4096:
        raise InvalidShapeError(f"fit: expected sides in 1..4096 voxels, got {w}x{h}")
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
    pieces : {"one", "auto"}
        ``"one"``: return one Net or raise UnfoldError.  ``"auto"``: always return a
        list of Nets, as few pieces as the budget allows: one per separate
        surface part (cavity walls, separate components), and when no one-piece
        net fits ``fit`` few large pieces that each fit it, none of a surface
        part's pieces under a tenth of its largest (UnfoldError when no such
        split is found).  Face ``i`` of a piece is then
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
        Exact strategy only: the cut edges must form one path (an unzipping).
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
    job = _Job(g, sg, seed, strat, fit, tab_aware, compact, deadline, float(timeout), constraints)
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
    nets: list[Net] = []
    for t, part in enumerate(parts):
        remaining = max(deadline - time.monotonic(), 0.0)
        part_job = dataclasses.replace(job, seed=seed + t,
                                       deadline=time.monotonic() + remaining / (len(parts) - t))
        nets.extend(_pieces(part_job, part))
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
    min_box = min_box or (compact and fit is None)
    if fit is None and not min_box:
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


def _pieces(job: _Job, faces: npt.NDArray[np.int64]) -> list[Net]:
    """One surface part as few pieces as the budget allows."""
    if job.fit is None or job.fit[0] * job.fit[1] >= faces.size:  # else one piece cannot fit
        try:
            return [_one_piece(job, faces)]
        except UnfoldError:
            pass
    boards = _partition(job, faces)
    nets = []
    for b, placed in boards:
        b.exclude_unplaced()
        if job.tab_aware and job.strategy is Strategy.DEFAULT:
            b.anneal(job.growth(placed.size), job.deadline)
        nets.append(job.net(b, placed))
    return nets


def _partition(job: _Job, faces: npt.NDArray[np.int64]) -> list[tuple[_Board, npt.NDArray[np.int64]]]:
    """Cut the faces into pieces that each fit the box, then join pieces while they fit.

    Without constraints the pieces are branches of one free net, each cut off
    where its layout stops fitting the box: every piece is a connected net
    from the start, with no stray faces left over.  With constraints (a kept
    group must not be cut) each piece is instead the largest net that
    ruin-and-recreate packs into the box from the faces left over.
    """
    if job.constraints is None and job.fit is not None:
        # Two ways to cut, the fewer pieces kept: slabs give straight cuts and
        # room for tabs; branches of a free net suit boxes too small for a slab.
        slabs = _sheet_pieces(job, faces)
        branches = _tree_pieces(job, faces)
        if branches is not None:
            branches = _merge_small(job, branches)
            if len(branches) < len(slabs):
                return _balance(job, branches)
        return _balance(job, slabs)
    return _balance(job, _merge_small(job, _greedy_pieces(job, faces)))


def _fold_tree(faces: npt.NDArray[np.int64], par: npt.NDArray[np.int64]) -> tuple[int, dict[int, list[int]], list[int]]:
    """The root, the children of each face and a breadth-first walk (every face after its parent) of a net's folds."""
    children: dict[int, list[int]] = {}
    root = -1
    for f in faces.tolist():
        p = int(par[f])
        if p >= 0:
            children.setdefault(p, []).append(f)
        else:
            root = f
    walk = [root]
    for f in walk:
        walk.extend(children.get(f, ()))
    return root, children, walk


def _tree_pieces(job: _Job, faces: npt.NDArray[np.int64]) -> list | None:
    """Branches of a free net that fit the box, bottom up; None when no free net grows."""
    n = int(faces.size)
    free = _Board(job.sg, faces, [job.seed, 1999], None, None, n)
    if not free.grow(job.growth(n), math.inf, _FIT_STEPS_PER_FACE * n):
        return None
    w_box, h_box = job.fit
    x, y = free.pos % free.width, free.pos // free.width

    def fits(b: tuple[int, int, int, int]) -> bool:
        w, h = b[1] - b[0] + 1, b[3] - b[2] + 1
        return (w <= w_box and h <= h_box) or (w <= h_box and h <= w_box)

    root, children, walk = _fold_tree(faces, free.par)
    box: dict[int, tuple[int, int, int, int]] = {}
    members: dict[int, list[int]] = {}
    cut: list[list[int]] = []
    for f in reversed(walk):
        b = (int(x[f]), int(x[f]), int(y[f]), int(y[f]))
        mem = [f]
        # The smallest branches join first, so that fewer faces are cut off.
        for c in sorted(children.get(f, ()), key=lambda c: (len(members[c]), c)):
            cb = box.pop(c)
            joined = (min(b[0], cb[0]), max(b[1], cb[1]), min(b[2], cb[2]), max(b[3], cb[3]))
            if fits(joined):
                b = joined
                mem += members.pop(c)
            else:
                cut.append(members.pop(c))
        box[f], members[f] = b, mem
    cut.append(members[root])
    return [_laid_out(job, free, np.array(sorted(m), dtype=np.int64), t) for t, m in enumerate(cut)]


def _laid_out(job: _Job, free: _Board, piece: npt.NDArray[np.int64], t: int) -> tuple[_Board, npt.NDArray[np.int64]]:
    """A board in the box holding ``piece`` as laid out on the free board ``free``."""
    cells = np.stack([free.pos % free.width, free.pos // free.width], axis=1)
    return _board_of(job, piece, cells, free.rot, free.par, [job.seed, 2000 + t])


def _board_of(job: _Job, piece: npt.NDArray[np.int64], cells: npt.NDArray[np.int64],
              rot: npt.NDArray[np.int64], par: npt.NDArray[np.int64], seed: list[int]
              ) -> tuple[_Board, npt.NDArray[np.int64]]:
    """A board in the box (turned to fit) holding ``piece`` laid out on ``cells``."""
    x, y = cells[piece, 0], cells[piece, 1]
    w, h = int(np.ptp(x)) + 1, int(np.ptp(y)) + 1
    if job.fit is None:
        box = None
    else:
        box = job.fit if w <= job.fit[0] and h <= job.fit[1] else (job.fit[1], job.fit[0])
    b = _Board(job.sg, piece, seed, box, None, job.sg.face_count)
    saved = np.zeros((job.sg.face_count, 3), dtype=np.int64)
    saved[:, 0] = -3  # faces of other pieces stay out
    saved[:, 2] = -2
    saved[piece, 0] = (y - y.min() + 1) * b.width + (x - x.min() + 1)  # inside the wall
    saved[piece, 1] = rot[piece]
    inside = np.zeros(job.sg.face_count, dtype=bool)
    inside[piece] = True
    up = par[piece]
    saved[piece, 2] = np.where((up >= 0) & inside[np.maximum(up, 0)], up, -1)
    b.k.restore(*b.b[:4], saved)
    b.cnt[b.k.C_ROOT] = int(piece[saved[piece, 2] < 0][0])
    b.faces = piece
    return b, piece


def _layout(b: _Board) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    return np.stack([b.pos % b.width, b.pos // b.width], axis=1), b.rot.copy(), b.par.copy()


def _join_layouts(job: _Job, q: tuple, r: tuple, seed: list[int]) -> tuple | None:
    """Pieces q and r as one, r turned and moved rigidly to fold onto q along a shared edge.

    No face is regrown: both keep their layouts, so the join works even when
    each fills most of the box.  None when no shared edge gives a layout
    without overlap inside the box.
    """
    sg = job.sg
    (bq, fq), (br, fr) = q, r
    cq, rq, pq = _layout(bq)
    cr, rr, pr = _layout(br)
    taken = {tuple(c) for c in cq[fq].tolist()}
    in_r = np.zeros(sg.face_count, dtype=bool)
    in_r[fr] = True
    step = np.array([[0, -1], [1, 0], [0, 1], [-1, 0]], dtype=np.int64)
    for a in fq.tolist():
        for k in range(4):
            c = int(sg.neighbor[a, k])
            if not in_r[c]:
                continue
            s_ = (k + int(rq[a])) % 4
            target = cq[a] + step[s_]
            if tuple(target.tolist()) in taken:
                continue
            turns = ((s_ + 2 - int(sg.neighbor_edge[a, k])) - int(rr[c])) % 4
            v = cr[fr] - cr[c]
            for _ in range(turns):  # a quarter turn counter-clockwise: (x, y) -> (-y, x)
                v = np.stack([-v[:, 1], v[:, 0]], axis=1)
            moved = v + target
            lo = np.minimum(moved.min(axis=0), cq[fq].min(axis=0))
            side = np.maximum(moved.max(axis=0), cq[fq].max(axis=0)) - lo + 1
            if job.fit is not None and not ((side[0] <= job.fit[0] and side[1] <= job.fit[1]) or (side[0] <= job.fit[1] and side[1] <= job.fit[0])):
                continue
            if any(tuple(m) in taken for m in moved.tolist()):
                continue
            cells, rot, par = cq.copy(), rq.copy(), pq.copy()
            cells[fr] = moved
            rot[fr] = (rr[fr] + turns) % 4
            par[fr] = pr[fr]
            # Re-root r's tree at c, then hang c from a.
            node, above = c, a
            while node >= 0:
                nxt = int(par[node])
                par[node] = above
                above, node = node, nxt
            both = np.sort(np.concatenate([fq, fr]))
            return _board_of(job, both, cells, rot, par, seed)
    return None


def _greedy_pieces(job: _Job, faces: npt.NDArray[np.int64]) -> list[tuple[_Board, npt.NDArray[np.int64]]]:
    """Pieces grown one by one into the box from the faces left over, the largest first."""
    n = int(faces.size)
    p = job.growth(n)
    pieces: list[tuple[_Board, npt.NDArray[np.int64]]] = []
    left = np.zeros(job.sg.face_count, dtype=bool)
    left[faces] = True
    t = 0
    while left.any():
        for part in _surface_parts(job.sg, np.flatnonzero(left)):
            t += 1
            b = _Board(job.sg, part, [job.seed, 2000 + t], job.fit, job.resolved(part), n)
            if b.started:
                b.grow(p, math.inf, _steps_left(job, part.size))
            placed = part[b.pos[part] >= 0]
            if placed.size == 0:
                raise UnfoldError(
                    f"no piece fits {job.fit[0]}x{job.fit[1]} cells: the box is too small for the "
                    "faces kept together, or for a single face")
            pieces.append((b, placed))
            left[placed] = False
    return pieces


def _steps_left(job: _Job, faces: int) -> int:
    # Growth steps for one piece: a full budget while the clock allows, and a
    # short greedy one after it, so that pieces="auto" always returns pieces.
    return (_FIT_STEPS_PER_FACE if time.monotonic() < job.deadline else 4) * int(faces)


def _merge_small(job: _Job, pieces: list) -> list:
    """Join neighbouring pieces, the smallest first, while their union grows inside the box.

    A join is tried only when no piece would end under a tenth of the
    largest, or when it swallows a piece that breaks that rule.
    """
    sg = job.sg
    area = math.inf if job.fit is None else job.fit[0] * job.fit[1]
    tried: set[tuple[int, int]] = set()
    while True:
        pieces.sort(key=lambda bp: (bp[1].size, int(bp[1][0])))
        owner = np.full(sg.face_count, -1, dtype=np.int64)
        for q, (_, placed) in enumerate(pieces):
            owner[placed] = q
        sizes = [int(bp[1].size) for bp in pieces]
        # Joins for fewer pieces stop with the clock or the tries; joins that
        # mend the size rule go on while a pair is left to try.
        if not _too_small(sizes) and (time.monotonic() > job.deadline or len(tried) >= _JOIN_TRIES):
            break
        joined = False
        for q in range(len(pieces)):
            near = owner[sg.neighbor[pieces[q][1]].ravel()]
            for r in sorted(set(near[(near >= 0) & (near != q)].tolist())):
                key = (int(pieces[q][1][0]), int(pieces[r][1][0]))
                if key in tried or sizes[q] + sizes[r] > area:
                    continue
                rest = [z for t, z in enumerate(sizes) if t not in (q, r)] + [sizes[q] + sizes[r]]
                mends = _too_small(sizes) and sizes[q] < _MIN_SHARE * max(sizes)  # q breaks the rule
                if _too_small(rest) and not mends:
                    continue
                tried.add(key)
                both = np.sort(np.concatenate([pieces[q][1], pieces[r][1]]))
                box = None if job.fit is None else _orientations(job.fit)[len(tried) % len(_orientations(job.fit))]
                seed = [job.seed, 3000 + len(tried)]
                joinable = job.constraints is None
                one = _join_layouts(job, pieces[q], pieces[r], seed) if joinable else None
                if one is None:
                    b = _Board(sg, both, seed, box, job.resolved(both), sg.face_count)
                    # Past the clock a join still gets a full budget while the split breaks the rule.
                    steps = _FIT_STEPS_PER_FACE * int(both.size) if _too_small(sizes) else _steps_left(job, both.size)
                    if b.started and b.grow(_settings(Strategy.DEFAULT, both.size), math.inf, steps):
                        one = (b, both)
                if one is not None:
                    pieces = [bp for t, bp in enumerate(pieces) if t not in (q, r)] + [one]
                    joined = True
                    break
            if joined:
                break
        if not joined:
            break
    return pieces


def _too_small(sizes: list[int]) -> bool:
    return min(sizes) < _MIN_SHARE * max(sizes)


def _balance(job: _Job, pieces: list) -> list:
    """Guarantee the size rule: no piece under a tenth of the largest.

    A piece still too small after merging (its neighbours fill their boxes)
    takes a branch of a neighbour's fold tree: the neighbour keeps its layout
    minus the branch (still a net, still inside the box), and the small piece
    is grown anew with the branch's faces.  UnfoldError when no branch works.
    """
    for _ in range(2 * len(pieces) + 8):
        pieces.sort(key=lambda bp: -bp[1].size)
        sizes = [int(bp[1].size) for bp in pieces]
        if not _too_small(sizes):
            return pieces
        if not _take_branch(job, pieces, len(pieces) - 1):
            break
    sizes = sorted((int(bp[1].size) for bp in pieces), reverse=True)
    where = "" if job.fit is None else f" that fit {job.fit[0]}x{job.fit[1]} cells"
    raise UnfoldError(
        f"could not split the {sum(sizes)}-face surface into pieces{where} "
        f"with none under a tenth of the largest (sizes "
        f"{sizes[:3]} ... {sizes[-3:]}); use a larger sheet or smaller faces")


def _take_branch(job: _Job, pieces: list, q: int) -> bool:
    """Grow piece ``q`` with a branch of a neighbouring piece; False when none fits."""
    sg = job.sg
    small = pieces[q][1]
    large = max(int(bp[1].size) for bp in pieces)
    floor = math.ceil(_MIN_SHARE * large)  # every piece must keep at least this many faces
    owner = np.full(sg.face_count, -1, dtype=np.int64)
    for r, (_, placed) in enumerate(pieces):
        owner[placed] = r
    near = owner[sg.neighbor[small].ravel()]
    tries = 0
    for r in sorted(set(near[(near >= 0) & (near != q)].tolist()), key=lambda r: (-pieces[r][1].size, r)):
        b, placed = pieces[r]
        for u, branch in _branches(b, placed, small, floor - small.size, placed.size - floor):
            both = np.sort(np.concatenate([small, branch]))
            tries += 1
            trial = _Board(sg, both, [job.seed, 4000 + tries], job.fit, job.resolved(both), sg.face_count)
            if trial.started and trial.grow(_settings(Strategy.DEFAULT, both.size), math.inf,
                                            _FIT_STEPS_PER_FACE * int(both.size)):
                b.k.remove_subtree(*b.sf, *b.b[:4], u)
                pieces[r] = (b, np.setdiff1d(placed, branch))
                pieces[q] = (trial, both)
                return True
            if tries >= _BRANCH_TRIES:
                return False
    return False


def _branches(b: _Board, placed: npt.NDArray[np.int64], small: npt.NDArray[np.int64], least: int,
              most: int):
    """Branches of board ``b``'s fold tree of ``least`` to ``most`` faces that touch ``small``.

    Yields (the branch's top face, its faces), smallest first: the neighbour
    then loses as little as it can.  A branch never starts inside a kept group.
    """
    nf = b.sf.link.shape[0]
    par = b.par
    size = np.zeros(nf, dtype=np.int64)
    touch = np.zeros(nf, dtype=bool)  # the branch holds a neighbour of the small piece
    near_small = np.zeros(nf, dtype=bool)
    near_small[b.sf.link[small, b.k.NB].ravel()] = True
    root, children, walk = _fold_tree(placed, par)
    for f in reversed(walk):
        size[f] += 1
        touch[f] |= near_small[f]
        p = int(par[f])
        if p >= 0:
            size[p] += size[f]
            touch[p] |= touch[f]
    cands = [f for f in walk if f != root and least <= size[f] <= most and touch[f]
             and int(b.k.entry(b.sf.link, b.b.face, b.cnt, f)) == f]
    cands.sort(key=lambda f: (int(size[f]), f))
    for u in cands:
        branch = []
        stack = [u]
        while stack:
            f = stack.pop()
            branch.append(f)
            stack.extend(children.get(f, ()))
        yield u, np.array(sorted(branch), dtype=np.int64)


def unfold_many(
    grid: npt.ArrayLike,
    *,
    count: int,
    rng: np.random.Generator | int,
    budget: float = DEFAULT_BUDGET,
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
    if not nets:
        raise last_error or UnfoldError(f"no net found within the budget of {budget:g} s")
    return nets


def _check_count(count: object) -> int:
    if not isinstance(count, (int, np.integer)) or isinstance(count, bool) or count < 1:
        raise InvalidShapeError(f"count: expected an integer >= 1, got {count!r}")
    return int(count)


def _sweep_regions(sg: SurfaceGraph, faces: npt.NDArray[np.int64], k: int) -> list[npt.NDArray[np.int64]]:
    """``faces`` cut into about ``k`` slabs of equal size across one axis, each slab's connected parts apart.

    Slabs end between two layers of face centres, so each cut runs along a
    straight line of voxel edges round the shape; of the three axes the one
    whose cuts are shortest (fewest seams between slabs) wins.
    """
    centre = sg.corners[faces].mean(axis=1)
    best: tuple[int, list[npt.NDArray[np.int64]]] | None = None
    for axis in range(3):
        # Face centres lie on half-integer layers: doubled, they are integers.
        level = np.rint(2 * centre[:, axis]).astype(np.int64)
        levels, counts = np.unique(level, return_counts=True)
        cum = np.cumsum(counts)
        cuts = [int(levels[np.argmin(np.abs(cum - faces.size * t / k))]) for t in range(1, k)]
        slab = np.searchsorted(np.array(sorted(set(cuts)), dtype=np.int64), level, side="left")
        if k > 1 and slab.max() == slab.min():
            continue  # the faces lie in one layer across this axis
        owner = np.full(sg.face_count, -1, dtype=np.int64)
        owner[faces] = slab
        nb = owner[sg.neighbor[faces]]
        seams = int(np.count_nonzero((nb >= 0) & (nb != slab[:, None])))
        if best is None or seams < best[0]:
            parts = [p for s in np.unique(slab).tolist() for p in _surface_parts(sg, faces[slab == s])]
            best = (seams, parts)
    if best is None:
        return _surface_parts(sg, faces)
    return best[1]


def _merge_parts(sg: SurfaceGraph, parts: list[npt.NDArray[np.int64]], least: int) -> list[npt.NDArray[np.int64]]:
    """Parts under ``least`` faces joined to the neighbouring part they share most edges with."""
    parts = [p for p in parts if p.size]
    while len(parts) > 1:
        sizes = [int(p.size) for p in parts]
        q = int(np.argmin(sizes))
        if sizes[q] >= least:
            break
        owner = np.full(sg.face_count, -1, dtype=np.int64)
        for t, p in enumerate(parts):
            owner[p] = t
        near = owner[sg.neighbor[parts[q]].ravel()]
        near = near[(near >= 0) & (near != q)]
        if near.size == 0:
            break  # a separate surface: it stays a piece of its own
        r = int(np.bincount(near).argmax())
        joined = np.sort(np.concatenate([parts[q], parts[r]]))
        parts = [p for t, p in enumerate(parts) if t not in (q, r)] + [joined]
    return parts


def _lay_in_box(job: _Job, faces: npt.NDArray[np.int64], tries: int) -> _Board | None:
    """A net of ``faces`` grown inside the fit box (either way round), or None within ``tries`` tries."""
    n = int(faces.size)
    p = job.growth(n)
    boxes = _orientations(job.fit)
    for t in range(tries):
        trial = _Board(job.sg, faces, [job.seed, 5000 + n, t], boxes[t % len(boxes)], None, job.sg.face_count)
        if trial.grow(p, math.inf, _FIT_STEPS_PER_FACE * n):
            return trial
    return None


def _sheet_pieces(job: _Job, faces: npt.NDArray[np.int64]) -> list[tuple[_Board, npt.NDArray[np.int64]]]:
    """Pieces of about :data:`_PIECE_SHARE` of the box each, cut along straight runs of seams.

    The surface is cut into slabs across its best axis (:func:`_sweep_regions`),
    each slab's parts apart and the tiny ones joined to a neighbour; a part
    that does not grow inside the box is cut in two the same way.  Every piece
    is laid in the box from the start, with room left round it for its tabs.
    """
    w, h = job.fit
    target = max(_PIECE_SHARE * w * h, 1.0)
    least = max(1, int(_MIN_SHARE * target))
    k = max(1, math.ceil(faces.size / target))
    queue = _merge_parts(job.sg, _sweep_regions(job.sg, faces, k), least)
    pieces: list[tuple[_Board, npt.NDArray[np.int64]]] = []
    while queue:
        part = queue.pop(0)
        board = _lay_in_box(job, part, _PIECE_TRIES) if part.size <= w * h else None
        if board is not None:
            pieces.append((board, part))
            continue
        if part.size == 1:
            raise UnfoldError(f"no piece fits {w}x{h} cells: the box is too small for a single face")
        halves = _merge_parts(job.sg, _sweep_regions(job.sg, part, 2), max(1, part.size // 10))
        if len(halves) < 2 or min(int(p.size) for p in halves) * 4 < part.size:
            # A ring, or a cut that would shave a sliver: halve the walk instead.
            halves = _split_in_two(job.sg, part)
        queue[:0] = halves
    return pieces


def _split_in_two(sg: SurfaceGraph, faces: npt.NDArray[np.int64]) -> list[npt.NDArray[np.int64]]:
    """``faces`` (connected, in one layer) as the first and second half of a breadth-first walk."""
    inside = np.zeros(sg.face_count, dtype=bool)
    inside[faces] = True
    seen = {int(faces[0])}
    walk = [int(faces[0])]
    for f in walk:
        for g in sg.neighbor[f].tolist():
            if inside[g] and g not in seen:
                seen.add(g)
                walk.append(g)
    half = len(walk) // 2
    first = np.sort(np.array(walk[:half], dtype=np.int64))
    return [first] + _surface_parts(sg, np.setdiff1d(faces, first))

