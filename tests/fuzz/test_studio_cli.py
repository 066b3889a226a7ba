"""The studio's command line: bad hosts and repositories are refused at start, in one line."""

from __future__ import annotations

import sqlite3
from pathlib import Path

import pytest
from _fuzz import check_outcome, refused, run_cli

from voxfab.repo import Repository


@pytest.fixture()
def repos(tmp_path: Path) -> Path:
    (tmp_path / "folder.sqlite").mkdir()
    (tmp_path / "text.sqlite").write_text("not a database\n")
    with sqlite3.connect(tmp_path / "other.sqlite") as db:
        db.execute("CREATE TABLE t (x)")
    with Repository(tmp_path / "future.sqlite"):
        pass
    db = sqlite3.connect(tmp_path / "future.sqlite")
    db.execute("PRAGMA user_version = 99")
    db.execute("PRAGMA journal_mode = DELETE")  # no -wal file left beside it
    db.close()
    return tmp_path


@pytest.mark.parametrize(("args", "message"), [
    (["--host", ""], "--host: expected an address"),
    (["--host", "  "], "--host: expected an address"),
    (["--host", "no-such-host.invalid"], "--host: cannot use 'no-such-host.invalid'"),
    (["--repo", "{root}/folder.sqlite"], "is a folder, not a repository file"),
    (["--repo", "{root}/text.sqlite"], "not an SQLite file"),
    (["--repo", "{root}/other.sqlite"], "not a voxfab repository"),
    (["--repo", "{root}/future.sqlite"], "repository schema 99 is newer"),
    (["--repo", "{root}/missing/r.sqlite"], "the folder"),
    (["--port", "0"], "--port: expected 1..65535"),
    (["--port", "70000"], "--port: expected 1..65535"),
])
def test_the_studio_refuses_at_start(repos: Path, args: list[str], message: str) -> None:
    before = set(repos.rglob("*"))
    argv = ["studio", "--no-browser", *(a.format(root=repos) for a in args)]
    if "--repo" not in args:
        argv += ["--repo", str(repos / "new.sqlite")]
    line = refused(argv, seconds=15)
    assert message in line, line
    assert set(repos.rglob("*")) == before


def test_a_network_address_is_warned_about(repos: Path) -> None:
    # 192.0.2.1 (TEST-NET-1) is no address of this machine: the warning comes, then the port refusal,
    # so no server ever listens beyond 127.0.0.1 in the tests.
    o = check_outcome(run_cli(["studio", "--no-browser", "--host", "192.0.2.1", "--repo", repos / "new.sqlite"],
                              seconds=15))
    assert o.code != 0
    assert o.err.splitlines()[0].startswith("voxfab: warning: --host 192.0.2.1: the studio is reachable from "
                                            "the network")
    assert "cannot listen on 192.0.2.1" in o.error_lines[0]
