"""The board: the search state of one piece, on which growth and tab-room annealing run."""

from __future__ import annotations

import dataclasses
import time

import numpy as np
import numpy.typing as npt

from voxfab._shared.progress import Meter, check_cancelled
from voxfab._shared.rng import seed_state
from voxfab.shape import SurfaceGraph

from ._constraints import Resolved
from ._job import FIT_STEPS_PER_FACE, Job, Strategy, growth_settings, tab_growth
from ._layout import build_net, count_without_tab_room
from ._net import Net
from ._params import Annealing

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


def count_seams(board: SearchBoard) -> int:
    """Seams without tab room of a board's complete net (used after a fallback)."""
    k = board.k
    face, half, b, cnt, _ = board.b
    n = int(k.track_seams(board.sf.link, face, half, b, cnt))
    cnt[k.C_TRACK] = 0
    return n


class SearchBoard:
    """Search state for the faces of one piece on one board."""

    def __init__(self, sg: SurfaceGraph, faces: npt.NDArray[np.int64], seed: int | list[int],
                 fit: tuple[int, int] | None, resolved: Resolved | None = None,
                 kernel_faces: int | None = None, tab_restarts: bool = False) -> None:
        # ``kernel_faces`` picks the kernels by a larger search than this board
        # (the pieces of one surface): many small boards add up.  With
        # ``tab_restarts``, annealing rounds after the first start from a net
        # grown for tab room (see :func:`anneal`).
        self.tab_restarts = tab_restarts
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
        state = seed_state(seed)
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
            self.growth.grow(*self.sf, *self.b, growth_settings(Strategy.DEFAULT, 1), 0, False)
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

    def grow(self, gw, deadline: float, max_steps: int | None = None, bar: Meter | None = None,
             sparse: bool = False) -> bool:
        """Grow until every face is placed; False when the clock or ``max_steps`` runs out.

        ``bar`` counts the faces of the largest partial net so far.  ``sparse``
        grows as annealing regrows: each tournament's winner touches the
        fewest placed faces.
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
                done = self.growth.grow(*self.sf, *self.b, gw, chunk, sparse)
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

        On a board with ``tab_restarts`` the fresh nets are grown, and their
        rounds regrow, for tab room (:func:`voxfab.unfold._job.tab_growth`):
        such a net starts with fewer seams without room and is fixed in a
        fraction of the moves, though with a few more seams.  The first round
        keeps the net it is given, so a net fixed at once is as before.
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
                if self.tab_restarts:
                    gw = tab_growth(gw)
                self.restart()
                if not self.grow(gw, deadline, FIT_STEPS_PER_FACE * int(self.faces.size), sparse=self.tab_restarts):
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

    def net(self, job: Job, faces: npt.NDArray[np.int64]) -> Net:
        """The net of ``faces`` as laid on this board, its seams without tab room counted."""
        cell = np.stack([self.pos % self.width, self.pos // self.width], axis=1)
        net = build_net(job.sg, faces, cell, self.rot, self.par, seed=job.seed, strategy=job.strategy.value)
        return dataclasses.replace(net, seams_without_tab_room=count_without_tab_room(job.grid, net))


def board_of(job: Job, piece: npt.NDArray[np.int64], cells: npt.NDArray[np.int64],
              rot: npt.NDArray[np.int64], par: npt.NDArray[np.int64], seed: list[int]
              ) -> tuple[SearchBoard, npt.NDArray[np.int64]]:
    """A board in the box (turned to fit) holding ``piece`` laid out on ``cells``."""
    x, y = cells[piece, 0], cells[piece, 1]
    w, h = int(np.ptp(x)) + 1, int(np.ptp(y)) + 1
    if job.fit is None:
        box = None
    else:
        box = job.fit if w <= job.fit[0] and h <= job.fit[1] else (job.fit[1], job.fit[0])
    b = SearchBoard(job.sg, piece, seed, box, None, job.sg.face_count)
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
