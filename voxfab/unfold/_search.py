"""unfold / unfold_many: search for single-piece nets of a voxel surface."""

from __future__ import annotations

import dataclasses
import enum
import time

import numpy as np
import numpy.typing as npt

from voxfab._shared.progress import Meter, meter
from voxfab._shared.rng import as_rng
from voxfab._shared.validate import as_grid, check_choice
from voxfab.errors import InvalidShapeError, UnfoldError
from voxfab.shape import SurfaceGraph, cavity_count, component_count, fill_cavities, surface_graph

from ._constraints import EdgeConstraints, Resolved, resolve
from ._layout import build_net, count_without_tab_room
from ._net import Net

__all__ = ["Strategy", "Pieces", "unfold", "unfold_many"]

#: Largest board side for a free (unfitted) net; past it growth meets a wall.
MAX_BOARD = 1021
#: Growth steps per compiled call between two clock checks.
_CHUNK = 4000
#: Annealing rounds (each from a fresh net) and moves per face in each round.
_ROUNDS = 8
_MOVES_PER_ROUND = 20
#: Past this many faces a round costs seconds (mostly regrowing a fresh net), so
#: the budget shrinks to keep the whole search well inside the default timeout:
#: a search that the clock cuts short would depend on the machine, not the seed.
_LARGE = 3000
_LARGE_ROUNDS = 2
_LARGE_MOVES_PER_ROUND = 5
#: Largest subtree one annealing move may remove.
_RUIN_CAP = 60
#: Growth steps an annealing move may spend regrowing before it is undone.
_REGROW_STEPS = 2000
#: Annealing temperatures (in seams without tab room) at the start and the end.
_T0, _T1 = 1.0, 0.05
#: Compactness: box-shrinking trials, and growth steps per face each trial may use.
_COMPACT_TRIES = 24
_COMPACT_STEPS_PER_FACE = 100


class Strategy(enum.StrEnum):
    """Search strategies."""

    DEFAULT = "default"
    PAPER = "paper"


class Pieces(enum.StrEnum):
    """How many pieces a result may have."""

    ONE = "one"
    AUTO = "auto"


def _growth(strategy: Strategy, faces: int):
    from ._growth import MODE_PAPER, MODE_RUIN, Growth

    if strategy is Strategy.PAPER:
        return Growth(MODE_PAPER, 1, 0, 0.0, max(50, faces // 4))
    return Growth(MODE_RUIN, 3, 3, 0.05, 0)


def _surface(sg: SurfaceGraph, resolved: Resolved | None):
    from ._board import Surface

    nb = np.ascontiguousarray(sg.neighbor, dtype=np.int64)
    ne = np.ascontiguousarray(sg.neighbor_edge, dtype=np.int64)
    if resolved is None:
        f = sg.face_count
        none = np.zeros(0, dtype=np.int64)
        resolved = Resolved(np.zeros((f, 4), dtype=np.int8), np.full(f, -1, dtype=np.int64),
                            none, none, none, none, np.zeros(1, dtype=np.int64))
        return Surface(nb, ne, *resolved)
    return Surface(nb, ne, *resolved)


class _Board:
    """Search state for the faces of one piece on one board."""

    def __init__(self, sg: SurfaceGraph, faces: npt.NDArray[np.int64], seed: int | list[int],
                 fit: tuple[int, int] | None, resolved: Resolved | None = None) -> None:
        from . import _board, _growth, _tabroom

        self.k = _board
        self.growth = _growth
        self.tabroom = _tabroom
        f = sg.face_count
        if fit is None:
            side = min(2 * faces.size + 1, MAX_BOARD)
            w, h = side, side
        else:
            w, h = fit
        self.width = w + 2
        board = np.full((h + 2, w + 2), -2, dtype=np.int32)
        board[1:-1, 1:-1] = -1
        if fit is None:
            cells = np.array([(h // 2 + 1) * self.width + w // 2 + 1], dtype=np.int64)
        else:
            ys, xs = np.nonzero(board == -1)
            cells = (ys * self.width + xs).astype(np.int64)
        pos = np.full(f, -3, dtype=np.int64)
        pos[faces] = -1
        cnt = np.zeros(_board.N_COUNTERS, dtype=np.int64)
        cnt[_board.C_WIDTH] = self.width
        cnt[_board.C_CONSTRAINED] = int(resolved is not None)
        state = np.random.SeedSequence(seed).generate_state(1, dtype=np.uint64)
        self.sf = _surface(sg, resolved)
        self.b = _board.Board(
            pos=pos, rot=np.zeros(f, dtype=np.int64), par=np.full(f, -2, dtype=np.int64),
            board=board.ravel(), off=np.array([-self.width, 1, self.width, -1], dtype=np.int64),
            cl=np.zeros(5 * f, dtype=np.int64), cp=np.full(5 * f, -1, dtype=np.int64), cnt=cnt,
            st=np.array([state[0] | np.uint64(1)], dtype=np.uint64),
            stack=np.zeros(f + 1, dtype=np.int64), opt=np.zeros(4 * f, dtype=np.int64),
            bad=np.zeros(8 * f, dtype=np.int64), blk=np.zeros(5 * f + 4, dtype=np.int64),
            root_cells=cells)
        self.pos, self.rot, self.par, self.cnt = self.b.pos, self.b.rot, self.b.par, cnt
        self.faces = faces
        self.started = self.growth.start(self.sf, self.b) >= 0

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
            if time.monotonic() > deadline or (max_steps is not None and spent >= max_steps):
                return False
            chunk = _CHUNK if max_steps is None else min(_CHUNK, max_steps - spent)
            if not self.growth.grow(self.sf, self.b, gw, chunk, False) and self.unplaced == self.faces.size:
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

    def anneal_budget(self) -> tuple[int, int]:
        """Rounds of annealing and moves per round, for this many faces."""
        n = int(self.faces.size)
        if n > _LARGE:
            return _LARGE_ROUNDS, _LARGE_MOVES_PER_ROUND * n
        return _ROUNDS, _MOVES_PER_ROUND * n

    def anneal(self, gw, deadline: float, bar: Meter | None = None) -> int:
        """Drive seams without tab room to zero; return the count reached.

        Rounds of annealing, each from a freshly grown net (a stuck net is rarely
        worth more moves than a new one), within a budget of moves proportional to
        the face count, so the outcome depends on the seed alone unless the clock
        runs out first.  The state ends at the best net seen.  ``bar`` counts the
        moves tried.
        """
        k = self.k
        n = int(self.faces.size)
        rounds, per_round = self.anneal_budget()
        sched = self.tabroom.Annealing(per_round, _T0, _T1, _REGROW_STEPS, _RUIN_CAP)
        chunk = max(200, 20000 // max(1, n // 100))
        best = None
        for _ in range(rounds):
            done = 0
            score = -1
            while done < per_round and time.monotonic() < deadline:
                score, _used = self.tabroom.anneal(self.sf, self.b, gw, sched,
                                                   min(chunk, per_round - done), done)
                if score == 0:
                    break
                if bar is not None:
                    bar.update(min(chunk, per_round - done))
                done += chunk
            if score >= 0 and (best is None or score < best[0]):
                best = (score, self.pos.copy(), self.rot.copy(), self.par.copy(),
                        int(self.cnt[k.C_ROOT]))
            if score == 0 or time.monotonic() >= deadline:
                break
            self.growth.start(self.sf, self.b)
            if not self.grow(gw, deadline):
                break
        if best is None:
            return -1
        k.restore(self.sf, self.b, best[1], best[2], best[3])
        self.cnt[k.C_ROOT] = best[4]
        return int(best[0])

    def net(self, sg: SurfaceGraph, *, faces: npt.NDArray[np.int64] | None = None,
            seed: int, strategy: str) -> Net:
        cell = np.stack([self.pos % self.width, self.pos // self.width], axis=1)
        chosen = np.flatnonzero(self.pos >= 0) if faces is None else faces
        return build_net(sg, chosen, cell, self.rot, self.par, seed=seed, strategy=strategy)


def _surface_parts(sg: SurfaceGraph) -> list[npt.NDArray[np.int64]]:
    """Face indices of each connected part of the surface, in order of first face."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    f = sg.face_count
    rows = np.repeat(np.arange(f), 4)
    m = coo_matrix((np.ones(4 * f, dtype=np.int8), (rows, sg.neighbor.ravel())), shape=(f, f))
    _, labels = connected_components(m, directed=False)
    return [np.flatnonzero(labels == lab) for lab in dict.fromkeys(labels.tolist())]


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
) -> Net | list[Net]:
    """Find a net of a voxel shape: its surface cut along voxel edges and laid flat.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        A 6-connected shape, indexed ``[x, y, z]``.
    rng : int or numpy Generator
        Seed.  The same int seed gives the identical net (unless the search runs
        into ``timeout``); different seeds give different nets.
    strategy : {"default", "paper"}
        ``"default"``: ruin-and-recreate growth (a dead end removes the subtree on
        the blocking cell and lays the blocked face there), then tab-room
        annealing.  ``"paper"``: the published random growth with leaf swaps,
        subtree drops and restarts, for comparison.
    timeout : float
        Budget in seconds for the whole call.
    fit : (int, int) or None
        Keep the net inside ``width × height`` cells (voxel units).
    tab_aware : bool
        Drive the seams without tab room towards zero (default strategy only);
        the final count is in ``Net.seams_without_tab_room``.
    fill : bool
        Fill enclosed cavities first (their surfaces cannot join the outer one).
    compact : bool
        Shrink the net's bounding box: new nets are grown inside ever smaller
        boxes (the longer side first) while one is found within a fixed growth
        budget; tab-room annealing then stays inside the final box.  One-piece
        results only.
    pieces : {"one", "auto"}
        ``"one"``: return one Net or raise UnfoldError.  ``"auto"``: always return a
        list of Nets, one per piece, as few as were found: one per separate
        surface part (cavity walls, separate components), and when the budget
        runs out the largest partial net plus pieces grown from the rest.  Face
        ``i`` of a piece is then *not* face ``i`` of the surface graph: faces are
        identified by ``(voxel, normal)``.
    constraints : EdgeConstraints, optional
        Edges to cut (never folds) and edges to keep (always folds: the faces
        they join move as one rigid group during the search).

    Returns
    -------
    Net or list of Net
        Face ``i`` of a one-piece net is face ``i`` of ``surface_graph(grid)``.

    Raises
    ------
    UnfoldError
        The shape has cavities or several components (with ``pieces="one"``), the
        faces cannot fit ``fit``, kept edges cannot all be folds, or the budget
        ran out; the message says what was tried.
    InvalidShapeError
        A bad option, or a constrained edge that is not an edge of the surface.
    """
    strat = check_choice(strategy, Strategy, name="strategy")
    mode = check_choice(pieces, Pieces, name="pieces")
    fit = _check_fit(fit)
    if not float(timeout) > 0:
        raise InvalidShapeError(f"timeout: expected a positive number of seconds, got {timeout!r}")
    seed = _seed_of(rng)
    if constraints is not None and not isinstance(constraints, EdgeConstraints):
        raise InvalidShapeError(
            f"constraints: expected EdgeConstraints, got {type(constraints).__name__}")
    g = _prepare(grid, fill, mode)
    deadline = time.monotonic() + float(timeout)
    sg = surface_graph(g)
    if fit is not None and fit[0] * fit[1] < sg.face_count and mode is Pieces.ONE:
        raise UnfoldError(
            f"the surface has {sg.face_count} faces, more than the {fit[0]}x{fit[1]} = "
            f"{fit[0] * fit[1]} cells of fit, so no net fits"
        )
    _check_groups_fit(resolve(constraints, sg), fit)  # every named edge must be on this surface
    parts = _surface_parts(sg)
    if mode is Pieces.ONE:
        if len(parts) > 1:
            _refuse_parts(g, len(parts))
        net = _one_piece(g, sg, parts[0], seed, strat, fit, tab_aware, deadline, timeout, compact,
                         resolve(constraints, sg, parts[0]))
        return dataclasses.replace(net, filled=fill)
    nets: list[Net] = []
    for t, part in enumerate(parts):
        remaining = max(deadline - time.monotonic(), 0.0)
        part_deadline = time.monotonic() + remaining / (len(parts) - t)
        nets.extend(_pieces(g, sg, part, seed + t, strat, fit, tab_aware, part_deadline,
                            constraints))
    return [dataclasses.replace(n, filled=fill) for n in nets]


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


def _one_piece(g: npt.NDArray[np.bool_], sg: SurfaceGraph, faces: npt.NDArray[np.int64],
               seed: int, strat: Strategy, fit: tuple[int, int] | None, tab_aware: bool,
               deadline: float, timeout: float, compact: bool, resolved: Resolved | None) -> Net:
    p = _growth(strat, faces.size)
    b = _Board(sg, faces, seed, fit, resolved)
    with meter(int(faces.size), desc="net: faces placed") as bar:
        grown = b.grow(p, deadline, bar=bar)
    if not grown and not b.started:
        raise UnfoldError(
            f"the faces kept together by the constraints do not fit inside {fit[0]}x{fit[1]}")
    if not grown:
        raise UnfoldError(
            f"no one-piece net of the {faces.size}-face surface in {timeout:g} s with strategy "
            f"{strat.value!r}{'' if fit is None else f' inside {fit[0]}x{fit[1]}'}: "
            f"{int(b.cnt[b.k.C_DEADENDS])} dead ends repaired, "
            f"{int(b.cnt[b.k.C_RESTARTS])} restarts, best partial net {b.best} of "
            f"{faces.size} faces; raise the timeout, try another seed, or allow several "
            "pieces (pieces='auto', CLI --pieces auto)"
        )
    if compact:
        b = _compact(sg, faces, seed, p, b, deadline, resolved)
    if tab_aware and strat is Strategy.DEFAULT:
        rounds, per_round = b.anneal_budget()
        with meter(rounds * per_round, desc="net: tab room, moves (at most)") as bar:
            b.anneal(p, deadline, bar=bar)
    net = b.net(sg, faces=faces, seed=seed, strategy=strat.value)
    return _with_tab_count(g, net)


def _compact(sg: SurfaceGraph, faces: npt.NDArray[np.int64], seed: int, p,
             board: _Board, deadline: float, resolved: Resolved | None) -> _Board:
    """Shrink the net's bounding box while a fixed growth budget still fits it.

    Each trial grows a new net inside the current box with its longer side cut
    by about a tenth; two failures in a row end the search.  Budgets are counted
    in growth steps, so the result depends on the seed alone (unless the clock
    runs out first).
    """
    best = board
    failures = 0
    for t in range(_COMPACT_TRIES):
        w, h = best.extent()
        if (w >= h) != (failures % 2 == 1):
            w = min(w - 1, int(w * 0.9))
        else:
            h = min(h - 1, int(h * 0.9))
        if w < 1 or h < 1 or w * h < faces.size or time.monotonic() > deadline:
            break
        trial = _Board(sg, faces, [seed, t + 1], (w, h), resolved)
        if trial.grow(p, deadline, _COMPACT_STEPS_PER_FACE * int(faces.size)):
            best, failures = trial, 0
        else:
            failures += 1
            if failures == 2:
                break
    return best


def _with_tab_count(grid: npt.NDArray[np.bool_], net: Net) -> Net:
    return dataclasses.replace(net, seams_without_tab_room=count_without_tab_room(grid, net))


def _pieces(g: npt.NDArray[np.bool_], sg: SurfaceGraph, faces: npt.NDArray[np.int64],
            seed: int, strat: Strategy, fit: tuple[int, int] | None, tab_aware: bool,
            deadline: float, constraints: EdgeConstraints | None) -> list[Net]:
    """One surface part as few pieces as the budget allows."""
    p = _growth(strat, faces.size)
    b = _Board(sg, faces, seed, fit, resolve(constraints, sg, faces))
    if b.grow(p, deadline):
        if tab_aware and strat is Strategy.DEFAULT:
            b.anneal(p, deadline)
        return [_with_tab_count(g, b.net(sg, faces=faces, seed=seed, strategy=strat.value))]
    nets = []
    rest = faces
    while rest.size:
        placed = rest[b.pos[rest] >= 0]
        nets.append(_with_tab_count(g, b.net(sg, faces=placed, seed=seed, strategy=strat.value)))
        rest = rest[b.pos[rest] < 0]
        if not rest.size:
            break
        # Grow the rest greedily on a fresh board, one piece per dead end.
        b = _Board(sg, rest, seed + len(nets), fit, resolve(constraints, sg, rest))
        if b.started:
            b.growth.grow(b.sf, b.b, b.growth.Growth(b.growth.MODE_PAPER, 1, 0, 0.0, 0),
                          4 * rest.size, False)
        if b.unplaced == rest.size:
            raise UnfoldError("no piece could be placed: fit is too small for a single face")
    return nets


def unfold_many(
    grid: npt.ArrayLike,
    *,
    count: int,
    rng: np.random.Generator | int,
    **options: object,
) -> list[Net]:
    """Find ``count`` distinct nets.

    Net ``t`` is ``unfold(grid, rng=seed_t, **options)`` for seeds drawn from
    ``rng``; a seed whose net repeats an earlier one is skipped.  ``timeout`` (in
    ``options``) is the budget per net.  ``pieces="auto"`` is not accepted here.

    Returns
    -------
    list of Net
        ``count`` nets, pairwise different in layout or folds.
    """
    n = int(count)
    if n < 1:
        raise InvalidShapeError(f"count: expected an integer >= 1, got {count!r}")
    if options.get("pieces", "one") != "one":
        raise InvalidShapeError("unfold_many: pieces must be 'one'")
    gen = np.random.default_rng(_seed_of(rng))
    nets: list[Net] = []
    seen: set[bytes] = set()
    tries = 0
    with meter(n, desc="nets") as bar:
        while len(nets) < n:
            tries += 1
            if tries > 4 * n + 8:
                raise UnfoldError(
                    f"only {len(nets)} distinct nets of {n} after {tries - 1} seeds: the surface "
                    "has few nets"
                )
            seed = int(gen.integers(0, 2**31 - 1))
            net = unfold(grid, rng=seed, **options)  # type: ignore[arg-type]
            key = net.corners2d.tobytes() + net.folds.tobytes()
            if key in seen:
                continue
            seen.add(key)
            nets.append(net)
            bar.update()
    return nets
