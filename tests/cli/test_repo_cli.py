"""``voxfab repo`` through the real entry point."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from _voxart import character, write_animated_character

from voxfab import io
from voxfab.cli import main
from voxfab.repo import Repository
from voxfab.shape import crop, examples, mirror, rotate, volume


def voxfab(*args: object, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "voxfab", *map(str, args)], capture_output=True, text=True, cwd=cwd
    )


@pytest.fixture
def files(tmp_path: Path) -> dict[str, Path]:
    """Shape files: two random shapes, a rotated and a mirrored copy, a bad shape."""
    a = examples.random_shape(4, fill=0.08)
    b = examples.random_shape(5, fill=0.08)
    out = {
        "a": tmp_path / "a.npy",
        "b": tmp_path / "b.txt",
        "a_rot": tmp_path / "a_rot.npy",
        "a_mir": tmp_path / "a_mir.npy",
        "ball": tmp_path / "ball.npy",
    }
    io.write(a, out["a"])
    io.write(b, out["b"])
    io.write(rotate(a, "x", 1), out["a_rot"])
    io.write(mirror(a, "z"), out["a_mir"])
    io.write(examples.ball(3), out["ball"])
    return out


def test_add_list_show_export_remove_in_subprocesses(tmp_path: Path, files: dict[str, Path]) -> None:
    repo = tmp_path / "r.sqlite"
    a = io.read(files["a"]).grid
    b = io.read(files["b"]).grid
    na, nb = f"{volume(a):05d}.001", f"{volume(b):05d}.001"

    r = voxfab("repo", "add", files["a"], files["b"], files["a"], "--repo", repo)
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == [f"{na} created", f"{nb} created", f"{na} exists"]

    r = voxfab("repo", "list", "--json", "--repo", repo)
    assert r.returncode == 0, r.stderr
    listing = json.loads(r.stdout)
    assert [s["name"] for s in listing["shapes"]] == sorted([na, nb])
    by_name = {s["name"]: s for s in listing["shapes"]}
    assert by_name[na] == {"name": na, "volume": volume(a), "extents": list(crop(a).shape), "draft": False}

    r = voxfab("repo", "export", na, tmp_path / "out.txt", "--repo", repo)
    assert r.returncode == 0, r.stderr
    assert np.array_equal(io.read(tmp_path / "out.txt").grid, crop(a))

    r = voxfab("repo", "remove", na, "--repo", repo)
    assert r.returncode == 0 and r.stdout.strip() == f"{na} removed"
    r = voxfab("repo", "show", na, "--repo", repo)
    assert r.returncode == 8
    assert r.stderr == f"voxfab: error: {na}: no such shape in {repo}\n"
    assert r.stdout == ""


def test_add_symmetric_finds_rotated_and_mirrored(tmp_path: Path, files: dict[str, Path], capsys) -> None:
    repo = str(tmp_path / "r.sqlite")
    assert main(["repo", "add", str(files["a"]), "--repo", repo]) == 0
    name = capsys.readouterr().out.split()[0]
    assert main(["repo", "add", str(files["a_rot"]), str(files["a_mir"]), "--symmetric", "--repo", repo]) == 0
    assert capsys.readouterr().out.splitlines() == [f"{name} exists", f"{name} exists"]
    # Without --symmetric the mirrored copy is a new shape of the same volume.
    assert main(["repo", "add", str(files["a_mir"]), "--repo", repo]) == 0
    assert capsys.readouterr().out.strip() == f"{name[:5]}.002 created"


def test_not_well_formed_is_refused_then_stored_as_draft(tmp_path: Path, files: dict[str, Path], capsys) -> None:
    repo = str(tmp_path / "r.sqlite")
    assert main(["repo", "add", str(files["ball"]), "--repo", repo]) == 8
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.splitlines()
    assert len(lines) == 1
    assert lines[0].startswith(f"voxfab: error: {files['ball']}: not well formed: extents (7, 7, 7)")
    assert "--draft" in lines[0]

    assert main(["repo", "add", str(files["ball"]), "--draft", "--repo", repo]) == 0
    captured = capsys.readouterr()
    draft = captured.out.split()[0]
    assert captured.out == f"{draft} created\n" and draft.startswith("draft-")
    assert "stored as a draft" in captured.err

    assert main(["repo", "show", draft, "--json", "--repo", repo]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["draft"] is True and info["rank"] is None and info["reasons"]
    assert info["meta"] == {"source": str(files["ball"])}

    assert main(["repo", "list", "--repo", repo]) == 0
    out = capsys.readouterr().out.splitlines()
    assert len(out) == 1 and out[0].split() == [draft, str(volume(examples.ball(3))), "7x7x7", "draft"]


def test_show_text_and_list_text(tmp_path: Path, files: dict[str, Path], capsys) -> None:
    repo = str(tmp_path / "r.sqlite")
    assert main(["repo", "add", str(files["b"]), str(files["a"]), "--repo", repo]) == 0
    names = [line.split()[0] for line in capsys.readouterr().out.splitlines()]
    assert main(["repo", "list", "--repo", repo]) == 0
    rows = [line.split() for line in capsys.readouterr().out.splitlines()]
    assert [row[0] for row in rows] == sorted(names)
    assert main(["repo", "show", names[0], "--repo", repo]) == 0
    text = capsys.readouterr().out
    assert f"name: {names[0]}\n" in text
    assert "rank: 1\n" in text and "draft: no\n" in text
    assert f"meta.source: {files['b']}\n" in text
    assert "colours: 0\n" in text  # stored without colours


def test_show_text_counts_the_stored_colours(tmp_path: Path, capsys) -> None:
    io.write(character(), tmp_path / "char.vox")
    repo = str(tmp_path / "r.sqlite")
    assert main(["repo", "add", "--draft", str(tmp_path / "char.vox"), "--repo", repo]) == 0
    name = capsys.readouterr().out.split()[0]
    assert main(["repo", "show", name, "--repo", repo]) == 0
    assert "colours: 12\n" in capsys.readouterr().out


def test_default_repository_in_the_working_folder(tmp_path: Path, files: dict[str, Path]) -> None:
    r = voxfab("repo", "add", files["a"], cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "output" / "repository.sqlite").is_file()
    r = voxfab("repo", "list", cwd=tmp_path)
    assert r.returncode == 0 and len(r.stdout.splitlines()) == 1


@pytest.mark.parametrize(
    ("argv", "code", "message"),
    [
        (["list"], 8, "no repository at {missing}"),
        (["show", "00025.001"], 8, "no repository at {missing}"),
        (["remove", "00025.001"], 8, "no repository at {missing}"),
        (["export", "00025.001", "{tmp}/x.npy"], 8, "no repository at {missing}"),
    ],
)
def test_missing_repository_is_not_created(tmp_path: Path, capsys, argv, code, message) -> None:
    missing = tmp_path / "missing.sqlite"
    argv = [a.format(tmp=tmp_path) for a in argv]
    assert main(["repo", *argv, "--repo", str(missing)]) == code
    err = capsys.readouterr().err
    assert err == f"voxfab: error: {message.format(missing=missing)}\n"
    assert not missing.exists()


def test_errors_are_one_line_with_exit_codes(tmp_path: Path, files: dict[str, Path], capsys) -> None:
    repo = str(tmp_path / "r.sqlite")
    assert main(["repo", "add", str(files["a"]), "--repo", repo]) == 0
    capsys.readouterr()
    (tmp_path / "bad.npy").write_bytes(b"\x93NUMPY garbage")
    (tmp_path / "x.xyz").write_text("?")
    cases = [
        (["add", str(tmp_path / "bad.npy")], 5, "bad.npy"),
        (["add", str(tmp_path / "x.xyz")], 4, "x.xyz"),
        (["add", str(tmp_path / "nothere.npy")], 5, "nothere.npy: no such file"),
        (["show", "nonsense"], 8, "'nonsense': not a shape name"),
        (["remove", "99999.999"], 8, "99999.999: no such shape"),
        (["export", "99999.999", str(tmp_path / "o.npy")], 8, "99999.999: no such shape"),
    ]
    for argv, code, fragment in cases:
        assert main(["repo", *argv, "--repo", repo]) == code, argv
        captured = capsys.readouterr()
        lines = captured.err.splitlines()
        assert len(lines) == 1 and lines[0].startswith("voxfab: error: "), captured.err
        assert fragment in lines[0]
        assert "Traceback" not in captured.err
    with Repository(repo, create=False) as r:
        assert len(r) == 1


def test_corrupt_repository_file_in_subprocess(tmp_path: Path) -> None:
    bad = tmp_path / "bad.sqlite"
    bad.write_bytes(b"garbage" * 1000)
    r = voxfab("repo", "list", "--repo", bad)
    assert r.returncode == 8
    assert r.stderr.startswith(f"voxfab: error: {bad}: not a voxfab repository")
    assert len(r.stderr.splitlines()) == 1 and "Traceback" not in r.stderr
    r = voxfab("repo", "list", "--repo", bad, "--debug")
    assert r.returncode == 8 and "Traceback" in r.stderr


def test_missing_action_is_a_usage_error() -> None:
    r = voxfab("repo")
    assert r.returncode == 2
    assert "ACTION" in r.stderr or "required" in r.stderr


def test_module_imports_stay_light() -> None:
    code = (
        "import sys, voxfab.cli.repo; "
        "print(sorted(m for m in ('scipy', 'trimesh', 'sqlite3', 'voxfab.repo') if m in sys.modules))"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "[]"


def test_explore_then_stats_and_pages(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    repo = tmp_path / "r.sqlite"
    r = voxfab("explore", "--count", "40", "--seed", "3", "--volume", "25:300", "--repo", repo)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0].startswith("40 new shapes in ")
    ranges = [line.split() for line in lines[2:]]
    assert all(row[0] == "volume" for row in ranges) and sum(int(row[2]) for row in ranges) == 40

    assert main(["repo", "stats", "--json", "--repo", str(repo)]) == 0
    stats = json.loads(capsys.readouterr().out)
    assert stats["shapes"] == 40 and stats["drafts"] == 0
    with Repository(repo, create=False) as opened:
        entries = opened.list()
        for row in stats["volumes"]:
            assert row["count"] == sum(e.volume == row["volume"] for e in entries)
        for line in ranges:  # the ranges printed by explore count the stored volumes
            lo, hi = map(int, line[1].split("-"))
            assert int(line[2]) == sum(lo <= e.volume <= hi for e in entries)

    # Without paging options --json lists every shape; with them, pages chain through next_after.
    assert main(["repo", "list", "--json", "--repo", str(repo)]) == 0
    every = [s["name"] for s in json.loads(capsys.readouterr().out)["shapes"]]
    assert every == [e.name for e in entries] and len(every) == 40
    paged, after = [], None
    while True:
        argv = ["repo", "list", "--json", "--limit", "15", "--repo", str(repo)]
        assert main(argv + (["--after", after] if after else [])) == 0
        page = json.loads(capsys.readouterr().out)
        paged += [s["name"] for s in page["shapes"]]
        after = page["next_after"]
        if after is None:
            break
    assert paged == every

    assert main(["repo", "list", "--volume", "100:200", "--repo", str(repo)]) == 0
    shown = [line.split()[0] for line in capsys.readouterr().out.splitlines()]
    assert shown == [e.name for e in entries if 100 <= e.volume <= 200]
    assert main(["repo", "stats", "--bins", "3", "--repo", str(repo)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("shapes: 40\ndrafts: 0\n") and len(out.splitlines()) <= 3 + 3


def test_explore_is_reproducible_from_the_command_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    outs = []
    for d in ("a", "b"):
        (tmp_path / d).mkdir()
        assert main(["explore", "--count", "12", "--seed", "8", "--generator", "mix", "--repo",
                     str(tmp_path / d / "r.sqlite")]) == 0
        outs.append(capsys.readouterr().out.replace(str(tmp_path / d), "R"))
        with Repository(tmp_path / d / "r.sqlite", create=False) as opened:
            outs.append([opened.get(e.name).tobytes() for e in opened.list()])
    assert outs[0] == outs[2] and outs[1] == outs[3]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["explore", "--count", "0"], "count"),
        (["explore", "--count", "2", "--volume", "9:x"], "volume: expected MIN:MAX"),
        (["explore", "--count", "2", "--volume", "25:25", "--max-attempts", "100"], "only 1 of 2"),
        (["repo", "list", "--limit", "0"], "--limit"),
        (["repo", "list", "--after", "00999.001"], "no such shape"),
        (["repo", "stats", "--bins", "0"], "--bins"),
    ],
)
def test_explore_and_listing_errors(tmp_path: Path, argv: list[str], message: str) -> None:
    repo = tmp_path / "r.sqlite"
    Repository(repo).close()
    r = voxfab(*argv, "--repo", repo)
    assert r.returncode != 0
    assert r.stderr.startswith("voxfab: error: ") and message in r.stderr and "Traceback" not in r.stderr


def test_add_stores_the_frame_asked_of_an_animation(tmp_path: Path, capsys) -> None:
    write_animated_character(tmp_path / "anim.vox")
    db = str(tmp_path / "r.sqlite")
    for k in (1, 2):
        assert main(["repo", "add", "--repo", db, "--draft", "--frame", str(k), str(tmp_path / "anim.vox")]) == 0
    assert capsys.readouterr().out.split() == ["draft-1", "created", "draft-2", "created"]
    with Repository(db) as repo:
        for k in (1, 2):
            want = io.read(tmp_path / "anim.vox", frame=k).shape()
            got = repo.shape(f"draft-{k}")
            box = tuple(slice(a.min(), a.max() + 1) for a in np.nonzero(want.grid))  # stored cropped
            assert np.array_equal(got.grid, want.grid[box])
            assert np.array_equal(got.colours.rgba, want.colours.rgba[box])
    assert main(["repo", "add", "--repo", db, "--frame", "3", str(tmp_path / "anim.vox")]) != 0
    assert capsys.readouterr().err.strip().endswith("frame 3: the file holds 2 frames")
