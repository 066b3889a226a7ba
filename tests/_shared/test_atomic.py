import os

import pytest

from voxfab._shared.atomic import atomic_dir, atomic_open, write_bytes


def test_failed_write_leaves_no_file_and_keeps_the_old_one(tmp_path):
    target = tmp_path / "out.bin"
    write_bytes(target, b"old")
    with pytest.raises(RuntimeError):
        with atomic_open(target) as fh:
            fh.write(b"half")
            raise RuntimeError("disk on fire")
    assert target.read_bytes() == b"old"
    assert [p.name for p in tmp_path.iterdir()] == ["out.bin"]


def test_written_files_and_folders_get_normal_permissions(tmp_path):
    mask = os.umask(0o022)
    try:
        write_bytes(tmp_path / "a.bin", b"x")
        with atomic_dir(tmp_path / "d") as d:
            (d / "f").write_bytes(b"y")
    finally:
        os.umask(mask)
    assert (tmp_path / "a.bin").stat().st_mode & 0o777 == 0o644
    assert (tmp_path / "d").stat().st_mode & 0o777 == 0o755


def test_atomic_dir_replaces_only_on_success(tmp_path):
    target = tmp_path / "build"
    with atomic_dir(target) as d:
        (d / "one").write_text("1")
    with pytest.raises(ValueError):
        with atomic_dir(target) as d:
            (d / "two").write_text("2")
            raise ValueError
    assert sorted(p.name for p in target.iterdir()) == ["one"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["build"]
