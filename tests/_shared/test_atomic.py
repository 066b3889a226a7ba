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


def _dead_pid() -> int:
    import subprocess
    import sys

    return int(subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                              text=True).stdout)


def test_file_set_is_published_together_and_replaces_the_earlier_set(tmp_path):
    from voxfab._shared.atomic import atomic_files

    for name in ("t-1.svg", "t-2.svg", "t-3.svg", "t-2-piece1.svg", "t.sheet-4.svg", "t-2.sheet-1.svg",
                 "t-notes.svg", "other.svg"):
        (tmp_path / name).write_text("old")
    with atomic_files(tmp_path / "t.svg") as fileset:
        write_bytes(tmp_path / "t-1.svg", b"new1")
        write_bytes(tmp_path / "t-2.svg", b"new2")
        # Nothing is renamed before the block ends.
        assert (tmp_path / "t-1.svg").read_text() == "old"
    assert fileset.written == [tmp_path / "t-1.svg", tmp_path / "t-2.svg"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["other.svg", "t-1.svg", "t-2.svg", "t-notes.svg"]
    assert (tmp_path / "t-2.svg").read_bytes() == b"new2"


def test_failed_file_set_keeps_every_earlier_file(tmp_path):
    from voxfab._shared.atomic import atomic_files

    (tmp_path / "t-1.json").write_text("old")
    with pytest.raises(KeyboardInterrupt):
        with atomic_files(tmp_path / "t.json"):
            write_bytes(tmp_path / "t-1.json", b"new")
            write_bytes(tmp_path / "t-2.json", b"new")
            raise KeyboardInterrupt
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t-1.json"]
    assert (tmp_path / "t-1.json").read_text() == "old"


def test_output_into_a_missing_folder_is_refused(tmp_path):
    from voxfab._shared.atomic import check_output
    from voxfab.errors import OutputError

    with pytest.raises(OutputError, match="the folder .*missing does not exist"):
        check_output(tmp_path / "missing" / "x.bin")
    with pytest.raises(OutputError, match="the folder .*a/b does not exist"):
        check_output(tmp_path / "a" / "b" / "c", folder=True, parents=True)
    with pytest.raises(OutputError, match="is a folder"):
        check_output(tmp_path)
    assert not (tmp_path / "missing").exists() and not (tmp_path / "a").exists()
    # A library caller may name new folders.
    write_bytes(tmp_path / "new" / "deeper" / "x.bin", b"x")
    assert (tmp_path / "new" / "deeper" / "x.bin").read_bytes() == b"x"
    # A command may make its own output folder, one level down; inside it, anything.
    check_output(tmp_path / "out" / "build", folder=True, parents=True)
    with atomic_dir(tmp_path / "out" / "build") as d:
        write_bytes(d / "sub" / "deeper" / "f.txt", b"inside the folder being assembled")
    assert (tmp_path / "out" / "build" / "sub" / "deeper" / "f.txt").exists()


def test_atomic_dir_refuses_a_file_or_someone_elses_folder(tmp_path):
    from voxfab.errors import OutputError

    (tmp_path / "file").write_text("x")
    with pytest.raises(OutputError, match="exists and is not a folder"):
        with atomic_dir(tmp_path / "file"):
            pass
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "thesis.tex").write_text("precious")
    with pytest.raises(OutputError, match="not an earlier output"):
        with atomic_dir(tmp_path / "mine", marker="plates.json"):
            pass
    assert (tmp_path / "mine" / "thesis.tex").read_text() == "precious"


def test_sweep_removes_only_dead_runs_temporaries(tmp_path):
    from voxfab._shared.atomic import sweep

    dead = _dead_pid()
    (tmp_path / f".x.{dead}-abc12345.tmp").mkdir()
    (tmp_path / f".y.svg.{dead}-zz9.tmp").write_text("half")
    (tmp_path / f".z.{os.getpid()}-live1234.tmp").mkdir()
    (tmp_path / ".hidden.tmp").write_text("not ours")
    removed = sweep(tmp_path)
    assert sorted(p.name for p in removed) == sorted([f".x.{dead}-abc12345.tmp", f".y.svg.{dead}-zz9.tmp"])
    assert sorted(p.name for p in tmp_path.iterdir()) == [".hidden.tmp", f".z.{os.getpid()}-live1234.tmp"]


@pytest.mark.parametrize("signal_name", ["SIGINT", "SIGTERM", "SIGKILL"])
def test_signals_remove_temporaries_or_the_next_run_sweeps_them(tmp_path, signal_name):
    import signal
    import subprocess
    import sys

    code = (
        "import sys, time\n"
        "from voxfab._shared.atomic import atomic_dir\n"
        "from voxfab.cli._main import _terminate_as_exception\n"
        "with _terminate_as_exception(), atomic_dir(sys.argv[1]) as d:\n"
        "    (d / 'part').write_text('half')\n"
        "    print('ready', flush=True)\n"
        "    time.sleep(60)\n"
    )
    # Ctrl-C reaches a foreground command, whose SIGINT is at its default; a run started in the
    # background (as CI may be) inherits SIGINT ignored, so the child is given the terminal's default.
    proc = subprocess.Popen([sys.executable, "-c", code, str(tmp_path / "out")], stdout=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        assert proc.stdout.readline().strip() == "ready"
        assert len(list(tmp_path.glob(".out.*.tmp"))) == 1
        proc.send_signal(getattr(signal, signal_name))
        proc.wait(timeout=30)
    finally:
        proc.kill()
        proc.wait()
    left = list(tmp_path.glob(".out.*.tmp"))
    if signal_name == "SIGKILL":
        assert len(left) == 1  # nothing runs on SIGKILL...
        with atomic_dir(tmp_path / "other"):
            pass
        left = list(tmp_path.glob(".out.*.tmp"))  # ...the next run into the folder sweeps it
    assert left == [] and not (tmp_path / "out").exists()
