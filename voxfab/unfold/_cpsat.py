"""CP-SAT as voxfab runs it: loaded on demand, one worker with a fixed seed, stopped by a cancel, and lazy no-goods.

Every CP-SAT search of the project (the exact strategy, zipper nets, the
census's unzipping) goes through here, so each runs the same way every time
and a cancelled studio job stops it within a fraction of a second.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

from voxfab.errors import MissingDependencyError

__all__ = ["NogoodSearch", "cp_model", "one_worker_solver", "solve", "solve_with_nogoods"]

#: The solver's seed: fixed, so that a run never depends on anything but the input.
_SOLVER_SEED = 0


def cp_model():  # noqa: ANN201 - the ortools module
    """The ``ortools.sat.python.cp_model`` module; MissingDependencyError when ortools is not installed."""
    try:
        from ortools.sat.python import cp_model as module
    except ImportError:
        raise MissingDependencyError("ortools", "the exact unfolding strategy") from None
    return module


def one_worker_solver():  # noqa: ANN201 - an ortools CpSolver
    """A CP-SAT solver with one worker and a fixed seed: the same search, and so the same answer, every run.

    CP-SAT's own SIGINT handler is off: installed from any thread on each search and
    never put back, it left Python's Ctrl-C handler replaced, so that a later Ctrl-C
    killed the process outright (a studio after a search: no clean-up), and during a
    search it turned Ctrl-C into "ran out of time".  :func:`solve` stops the search on
    Ctrl-C itself.
    """
    solver = cp_model().CpSolver()
    solver.parameters.num_search_workers = 1
    solver.parameters.random_seed = _SOLVER_SEED
    solver.parameters.catch_sigint_signal = False
    return solver


def solve(solver: Any, model: Any) -> int:
    """``solver.solve(model)``, stopped within a fraction of a second by a cancel or a Ctrl-C.

    CP-SAT runs in native code, which neither calls :func:`check_cancelled` nor lets
    Python's signal handlers run: the search runs on a helper thread while this one
    waits in short steps, stops it when this thread's work is cancelled, and on a
    Ctrl-C (KeyboardInterrupt, main thread) stops it and lets the interrupt go on.
    """
    from voxfab._shared.progress import cancel_event, check_cancelled

    solver.parameters.catch_sigint_signal = False
    event = cancel_event()
    main = threading.current_thread() is threading.main_thread()
    if event is None and not main:
        return solver.solve(model)
    check_cancelled()
    outcome: list[Any] = []
    done = threading.Event()

    def run() -> None:
        try:
            outcome.append(solver.solve(model))
        except BaseException as exc:  # noqa: BLE001 - raised again on the caller's thread
            outcome.append(exc)
        finally:
            done.set()

    threading.Thread(target=run, name="cpsat-search", daemon=True).start()
    # Waited for on an event, not Thread.join: a join cut short by KeyboardInterrupt may return at
    # once the next time, and a search still running in native code when the interpreter exits
    # aborts the process ("terminate called without an active exception").
    try:
        while not done.wait(0.05):
            if event is not None and event.is_set():
                solver.stop_search()
    except BaseException:
        solver.stop_search()
        while True:
            try:
                done.wait()
                break
            except KeyboardInterrupt:  # a second Ctrl-C: the search is stopping already (milliseconds)
                solver.stop_search()
        raise
    check_cancelled()
    if isinstance(outcome[0], BaseException):
        raise outcome[0]
    return outcome[0]


class NogoodSearch(NamedTuple):
    """How :func:`solve_with_nogoods` ended.

    Attributes
    ----------
    status : str
        ``"found"`` (a solution was accepted), ``"infeasible"`` (the model with
        every no-good added has no solution: a proof when each no-good is
        valid) or ``"timeout"``.
    values : list of bool or None
        The accepted solution's value of each watched literal (``"found"``).
    rounds : int
        Solutions refused, each followed by its no-goods.
    """

    status: str
    values: list[bool] | None
    rounds: int


def solve_with_nogoods(model: Any, literals: Sequence[Any],
                       refuse: Callable[[list[bool]], Sequence[Sequence[Any]]], *,
                       deadline: float) -> NogoodSearch:
    """Solve, let ``refuse`` rule the solution out with no-goods, and solve again, until it is accepted.

    Parameters
    ----------
    model : ortools CpModel
        The model; the no-goods are added to it.
    literals : sequence of ortools literals
        The literals ``refuse`` reads: their values in each solution, in this
        order, and the hints (the last solution) the next solve starts from.
    refuse : callable
        ``refuse(values)`` returns the no-goods that rule the solution out, each
        a clause (a list of literals, at least one of them true); none to
        accept it.
    deadline : float
        ``time.monotonic()`` at which the search gives up.

    Returns
    -------
    NogoodSearch

    Notes
    -----
    One worker and a fixed seed (:func:`one_worker_solver`) make every round,
    and so the outcome, the same on every run; a cancelled job stops it
    (:func:`solve`).  The model is not presolved: it is solved again after
    each round of no-goods, presolving it each time costs more than it saves,
    and it drops the previous solution given as a hint (measured on the zipper
    search: 10 of 12 explored shapes decided in 8 s without presolve, 3 with it).
    """
    status_of = cp_model()
    solver = one_worker_solver()
    prm = solver.parameters
    prm.cp_model_presolve = False
    rounds = 0
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            return NogoodSearch("timeout", None, rounds)
        prm.max_time_in_seconds = left
        status = solve(solver, model)
        if status == status_of.INFEASIBLE:
            return NogoodSearch("infeasible", None, rounds)
        if status not in (status_of.OPTIMAL, status_of.FEASIBLE):
            return NogoodSearch("timeout", None, rounds)
        # Each literal read once: the solver's per-literal reads dominate small models otherwise.
        values = [solver.boolean_value(lit) for lit in literals]
        nogoods = refuse(values)
        if not nogoods:
            return NogoodSearch("found", values, rounds)
        for clause in nogoods:
            model.add_bool_or(clause)
        rounds += 1
        # Start the next search from this solution: most of it is far from what the no-goods refuse.
        model.clear_hints()
        for lit, value in zip(literals, values):
            model.add_hint(lit, value)
