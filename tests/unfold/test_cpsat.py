"""solve_with_nogoods: the solve, refuse, solve again loop that the zipper search and the census share."""

from __future__ import annotations

import threading
import time

import pytest

pytest.importorskip("ortools")

from voxfab._shared.progress import cancel_scope  # noqa: E402
from voxfab.errors import CancelledError  # noqa: E402
from voxfab.unfold import solve_with_nogoods  # noqa: E402
from voxfab.unfold._cpsat import cp_model  # noqa: E402


def _three_bits():
    m = cp_model().CpModel()
    bits = [m.new_bool_var(f"b{i}") for i in range(3)]
    return m, bits


def test_refusing_every_solution_walks_all_of_them_then_proves_none_is_left():
    m, bits = _three_bits()
    seen = []

    def refuse(values: list[bool]) -> list[list]:
        seen.append(tuple(values))
        return [[~b if v else b for b, v in zip(bits, values)]]  # exactly this assignment is ruled out

    search = solve_with_nogoods(m, bits, refuse, deadline=time.monotonic() + 30)
    assert search.status == "infeasible" and search.values is None
    assert search.rounds == 8 and len(set(seen)) == 8  # each of the 2**3 assignments once


def test_the_first_solution_accepted_is_returned_and_the_run_is_the_same_every_time():
    def run() -> tuple:
        m, bits = _three_bits()
        m.add(sum(bits) == 2)
        return solve_with_nogoods(m, bits, lambda v: [] if v[2] else [[bits[2]]], deadline=time.monotonic() + 30)

    first = run()
    assert first.status == "found" and first.values[2] and sum(first.values) == 2
    assert run() == first


def test_a_deadline_passed_is_a_timeout_and_a_cancelled_job_stops():
    m, bits = _three_bits()
    assert solve_with_nogoods(m, bits, lambda v: [], deadline=time.monotonic() - 1).status == "timeout"
    event = threading.Event()
    event.set()
    with cancel_scope(event), pytest.raises(CancelledError):
        solve_with_nogoods(m, bits, lambda v: [], deadline=time.monotonic() + 30)
