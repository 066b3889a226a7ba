"""Progress bars: silent in library use, drawn on a terminal only after a second of work."""

import io

import pytest

from voxfab._shared import progress as prog


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


@pytest.fixture
def terminal(monkeypatch):
    """The CLI's setting, stderr a terminal, and a clock the test moves by hand.

    Called from the test body: pytest's output capture resets ``sys.stderr``
    after fixtures run.
    """

    def use() -> tuple[_Terminal, list[float]]:
        now = [100.0]
        err = _Terminal()
        monkeypatch.setattr(prog, "ENABLED", True)
        monkeypatch.setattr(prog.sys, "stderr", err)
        monkeypatch.setattr(prog.time, "monotonic", lambda: now[0])
        return err, now

    return use


def test_quick_work_draws_nothing(terminal):
    err, now = terminal()
    with prog.meter(10, desc="quick") as m:
        for _ in range(10):
            now[0] += 0.05
            m.update()
    assert m.done == 10
    assert err.getvalue() == ""


def test_slow_work_draws_a_bar_after_the_delay(terminal):
    err, now = terminal()
    with prog.meter(10, desc="slow work") as m:
        m.update(3)
        assert err.getvalue() == ""  # not yet: under a second
        now[0] += prog.DELAY + 0.5
        m.update(2)
        m.update(5)
    out = err.getvalue()
    assert "slow work" in out and "5/10" in out  # drawn with the work done when it appeared
    assert m.done == 10


def test_library_use_and_pipes_stay_silent(monkeypatch):
    now = [0.0]
    monkeypatch.setattr(prog.time, "monotonic", lambda: now[0])
    for enabled, err in ((False, _Terminal()), (True, io.StringIO())):
        monkeypatch.setattr(prog, "ENABLED", enabled)
        monkeypatch.setattr(prog.sys, "stderr", err)
        items = []
        for i in prog.progress(range(5), desc="items"):
            now[0] += 1.0
            items.append(i)
        assert items == [0, 1, 2, 3, 4]
        assert err.getvalue() == ""


def test_progress_counts_every_item_and_closes_its_bar(terminal):
    err, now = terminal()

    def slow():
        for i in range(4):
            now[0] += 0.6
            yield i

    assert list(prog.progress(slow(), total=4, desc="items")) == [0, 1, 2, 3]
    assert "items" in err.getvalue()
