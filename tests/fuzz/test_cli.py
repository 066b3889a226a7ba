"""Fuzz the command lines: random argument vectors over each command's real options."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from _fuzz import CLI_COMMANDS, CLI_FIXED, argv_for, check_outcome, cli_corpus, cli_positionals, run_cli
from hypothesis import given, settings


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    root = tmp_path_factory.mktemp("cli")
    cli_corpus(root)
    return root


@pytest.mark.parametrize("command", CLI_COMMANDS)
def test_random_command_lines(folder, command):
    positionals = cli_positionals(folder, command)
    counts = {"ok": 0, "refused": 0}

    @settings(max_examples=25 if command in ("net", "slices", "mesh") else 30, database=None, derandomize=True)
    @given(argv=argv_for(command, positionals, fixed=CLI_FIXED.get(command, ())))
    def fuzz(argv):
        o = check_outcome(run_cli(argv))
        counts["ok" if o.code == 0 else "refused"] += 1
        if o.code == 0 and command in ("net", "slices") and o.out.strip():
            # Reports name only files that exist.
            report = json.loads(o.out)
            assert all(Path(p).exists() for p in report.get("written", report.get("files", [])))
        # No temporary is left behind by a finished run.
        assert not list((folder / "out").glob(".*.tmp")), argv

    fuzz()
    assert counts["refused"] > 0
