"""Hostile census runs: folders that cannot hold it, scheduler addresses and servers it refuses, tampered resumes.

Every refusal is one line and a non-zero exit, made before anything is (no empty
DIR or DIR/nets is left); a resume keeps only records whose net files parse,
are nets of their polycube, refold and hold their fold tree, and says which it
censuses again; the final folder passes :func:`verify_census`.
"""

from __future__ import annotations

import json
import shutil
import socket
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from voxfab.census import run_census, verify_census
from voxfab.errors import UnfoldError, VoxfabWarning

#: One-sided polycubes of 1..4 cubes.
SHAPES_TO_4 = 1 + 1 + 2 + 8


def _census(*args: str, timeout: float = 300) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "voxfab", "census", *args], capture_output=True, text=True,
                          timeout=timeout)


def _refused(run: subprocess.CompletedProcess, words: str) -> str:
    assert run.returncode not in (0, 1), (run.returncode, run.stderr)
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in run.stderr, run.stderr
    assert lines[0].startswith("voxfab: error: ") and words in lines[0], lines[0]
    return lines[0]


@pytest.fixture(scope="module")
def census4(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("census") / "c4"
    run_census(4, out, workers=0)
    assert verify_census(out).problems == ()
    return out


# ---- folders that cannot hold a census ---------------------------------------------------------------------


@pytest.mark.parametrize("where, why", [("/proc/voxfab-census", "No such file or directory"),
                                        ("/proc/self/voxfab-census", "No such file or directory"),
                                        ("/sys/voxfab-census", "Operation not permitted")])
def test_a_folder_on_a_virtual_file_system_is_refused_in_one_line(where: str, why: str) -> None:
    """mkdir there raised FileNotFoundError (/proc) or PermissionError (/sys, as root too): both are one line."""
    _refused(_census("2", "-o", where, "--workers", "0"), f"{where}: cannot write in {Path(where).parent}: {why}")
    assert not Path(where).exists()


def test_the_folder_is_tried_before_the_scheduler_is_reached() -> None:
    """A folder that cannot hold the census is refused first, not after a cluster started or a scheduler answered."""
    run = _census("2", "-o", "/proc/voxfab-census", "--scheduler", f"tcp://127.0.0.1:{_closed_port()}")
    _refused(run, "/proc/voxfab-census: cannot write in /proc")


def test_nets_that_is_a_file_is_refused_before_anything_is_made(tmp_path: Path) -> None:
    out = tmp_path / "c"
    out.mkdir()
    (out / "nets").write_text("a file")
    _refused(_census("2", "-o", str(out), "--workers", "0"), "is not a folder")
    assert sorted(p.name for p in out.iterdir()) == ["nets"]


@pytest.mark.parametrize("text, words", [
    ("[" * 100_000 + "]" * 100_000, "nested too deep"),
    ('{"format": "voxfab-census/2", "n": 4, "settings": {}, "shapes": [{"id": "4-1"}]}', "not a census id"),
    ('{"format": "voxfab-census/2", "n": 4, "settings": {}, "shapes": [{"id": 7}]}', "not a census id"),
    ('{"format": "voxfab-census/2", "n": 4, "settings": {}, "shapes": [{"id": "04-000001\\n"}]}',
     "not a census id"),
    ('{"format": "voxfab-census/2", "n": 4, "settings": {}, "shapes": ["04-000001"]}', "not a census id"),
    ('{"format": "something else"}', "not a census file"),
    ("not json", "not a census file"),
])
def test_a_census_json_that_is_no_census_is_refused_and_kept(tmp_path: Path, text: str, words: str) -> None:
    out = tmp_path / "c"
    out.mkdir()
    (out / "census.json").write_text(text)
    _refused(_census("2", "-o", str(out), "--workers", "0"), words)
    assert (out / "census.json").read_text() == text  # someone's file is never overwritten unread


# ---- scheduler addresses and servers -----------------------------------------------------------------------


def _closed_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def not_dask() -> tuple[int, threading.Event]:
    """A server on a free port that answers every connection with bytes that are no Dask handshake."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen()
    stop = threading.Event()

    def serve() -> None:
        server.settimeout(0.2)
        while not stop.is_set():
            try:
                conn, _ = server.accept()
            except OSError:
                continue
            with conn:
                conn.sendall(b"HTTP/1.0 200 OK\r\n\r\nhello, this is no scheduler")
    t = threading.Thread(target=serve, daemon=True)
    t.start()
    yield server.getsockname()[1], stop
    stop.set()
    t.join()
    server.close()


@pytest.mark.parametrize("address, words", [
    ("garbage", "expected tcp://HOST:PORT"),
    ("", "expected tcp://HOST:PORT"),
    ("tcp://127.0.0.1:99999", "expected tcp://HOST:PORT"),
    ("256.1.1.1:8786", "expected tcp://HOST:PORT"),
    ("tcp://256.1.1.1:8786", "expected tcp://HOST:PORT"),
    ("tcp://:8786", "expected tcp://HOST:PORT"),
    ("inproc://", "over tcp:// only"),
    ("ucx://127.0.0.1:8786", "over tcp:// only"),
    ("tls://127.0.0.1:8786", "over tcp:// only"),
    ("closed", "cannot reach"),
    ("not dask", "is not a Dask scheduler"),
])
def test_a_refused_scheduler_leaves_no_folder(tmp_path: Path, not_dask: tuple[int, threading.Event],
                                              address: str, words: str) -> None:
    address = {"closed": f"tcp://127.0.0.1:{_closed_port()}",
               "not dask": f"tcp://127.0.0.1:{not_dask[0]}"}.get(address, address)
    out = tmp_path / "c"
    _refused(_census("2", "-o", str(out), "--scheduler", address, "--connect-timeout", "3", timeout=120), words)
    assert not out.exists()


# ---- searches out of time, searches that fail --------------------------------------------------------------


def test_a_search_out_of_time_is_undecided_not_an_error(tmp_path: Path) -> None:
    out = tmp_path / "c"
    run = _census("4", "-o", str(out), "--workers", "0", "--timeout", "0.001")
    assert run.returncode == 0, run.stderr
    shapes = json.loads((out / "census.json").read_text())["shapes"]
    assert len(shapes) == SHAPES_TO_4
    assert not [r for r in shapes if "error" in r]
    assert any(r["unzip"] == "undecided" for r in shapes)
    assert verify_census(out).problems == ()


def test_a_census_whose_every_search_failed_is_no_success(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from voxfab.census import _task

    def fails(shape_id: str, *args: object) -> dict:
        raise UnfoldError(f"the search of {shape_id} failed")

    monkeypatch.setattr(_task, "census_shape", fails)
    with pytest.raises(UnfoldError, match=r"every search of the census failed \(4 polycubes; 01-000001: the search"):
        run_census(3, tmp_path / "c", workers=0)
    shapes = json.loads((tmp_path / "c" / "census.json").read_text())["shapes"]
    assert len(shapes) == 4 and all("error" in r for r in shapes)  # saved, and censused again by the next run
    monkeypatch.undo()
    with pytest.warns(VoxfabWarning, match="4 earlier record"):
        again = run_census(3, tmp_path / "c", workers=0)
    assert (again.censused, again.kept) == (4, 0)


# ---- resumes that must not trust what they find ------------------------------------------------------------


def _net(rec: dict) -> str:
    return rec["net"]


def _truncate(out: Path, data: dict) -> str:
    rec = data["shapes"][5]
    path = out / rec["net"]
    path.write_bytes(path.read_bytes()[:100])
    return rec["id"]


def _empty_unzip(out: Path, data: dict) -> str:
    rec = data["shapes"][6]
    (out / rec["unzip_net"]).write_bytes(b"")
    return rec["id"]


def _forged(out: Path, data: dict) -> str:
    fake = dict(data["shapes"][-1], id="04-000009")
    shutil.copy(out / data["shapes"][-1]["net"], out / "nets" / "04-000009.net.json")
    fake["net"], fake["unzip_net"] = "nets/04-000009.net.json", None
    data["shapes"].append(fake)
    return "04-000009"


def _maybe(out: Path, data: dict) -> str:
    data["shapes"][7]["unfold"] = "maybe"
    return data["shapes"][7]["id"]


def _outside(out: Path, data: dict) -> str:
    rec = data["shapes"][8]
    shutil.copy(out / rec["net"], out.parent / "elsewhere.json")
    rec["net"] = "../elsewhere.json"
    return rec["id"]


def _folder(out: Path, data: dict) -> str:
    rec = data["shapes"][9]
    (out / rec["net"]).unlink()
    (out / rec["net"]).mkdir()
    return rec["id"]


def _other_shape(out: Path, data: dict) -> str:
    rec, other = data["shapes"][10], data["shapes"][11]
    shutil.copy(out / other["unzip_net"], out / rec["unzip_net"])
    return rec["id"]


def _no_tree(out: Path, data: dict) -> str:
    rec = data["shapes"][4]
    path = out / rec["unzip_net"]
    net = json.loads(path.read_text())
    net["tree"] = net["folds"]  # every uncut edge: cycles round the flat vertices
    path.write_text(json.dumps(net))
    return rec["id"]


def _no_proof(out: Path, data: dict) -> str:
    rec = data["shapes"][3]
    rec["unzip"], rec["unzip_net"], rec["certificate"] = "none", None, "trust me"
    return rec["id"]


@pytest.mark.parametrize("tamper", [_truncate, _empty_unzip, _forged, _maybe, _outside, _folder, _other_shape,
                                    _no_tree, _no_proof])
def test_a_resume_recomputes_every_record_that_does_not_check_out(census4: Path, tmp_path: Path, tamper) -> None:
    out = tmp_path / "c"
    shutil.copytree(census4, out)
    data = json.loads((out / "census.json").read_text())
    sid = tamper(out, data)
    (out / "census.json").write_text(json.dumps(data))
    run = _census("4", "-o", str(out), "--workers", "0")
    assert run.returncode == 0, run.stderr
    warning = [line for line in run.stderr.splitlines() if "censused again" in line]
    assert len(warning) == 1 and sid in warning[0], run.stderr
    again = json.loads((out / "census.json").read_text())
    assert [r["id"] for r in again["shapes"]] == [r["id"] for r in json.loads(
        (census4 / "census.json").read_text())["shapes"]]
    assert all(r["unfold"] in ("found", "none", "undecided") for r in again["shapes"])
    assert all(r["net"] in (None, f"nets/{r['id']}.net.json") for r in again["shapes"])
    assert verify_census(out).problems == ()
    assert f"{SHAPES_TO_4 - 1} kept from an earlier run" in run.stdout or sid == "04-000009"


def test_a_net_file_of_the_earlier_version_gets_its_fold_tree(census4: Path, tmp_path: Path) -> None:
    """A net file written before the fold tree was given is kept, and given its tree, when it checks out."""
    out = tmp_path / "c"
    shutil.copytree(census4, out)
    for path in (out / "nets").iterdir():
        net = json.loads(path.read_text())
        del net["tree"]
        path.write_text(json.dumps(net))
    assert verify_census(out).problems  # no tree: the check says so
    report = run_census(4, out, workers=0)
    assert (report.censused, report.kept) == (0, SHAPES_TO_4)
    assert verify_census(out).problems == ()
