"""Studio fixtures: the app in-process for API tests, a real uvicorn server and headless Chromium for end to end."""

from __future__ import annotations

import os
import shutil
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
SHOTS = ROOT / "output" / "studio"


@pytest.fixture
def client(tmp_path):
    import warnings

    with warnings.catch_warnings():
        # Starlette asks for httpx2 in future; httpx is what its test client uses today
        warnings.simplefilter("ignore")
        from starlette.testclient import TestClient

    from voxfab.studio import Settings, create_app

    # No kernel warm-up thread: it would run the net engine beside tests that patch it.
    app = create_app(Settings(repo=tmp_path / "repo.sqlite", hosts=frozenset({"testserver"}), work=tmp_path / "work",
                              warm_up=False))
    with TestClient(app) as c:
        yield c


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_studio(folder: Path, *extra: str, repo: Path | None = None, tmpdir: Path | None = None,
                 apart: bool = False) -> tuple[subprocess.Popen, str]:
    """``voxfab studio [extra]`` as a real uvicorn process on 127.0.0.1 and a free port, once it answers.

    ``tmpdir`` is its TMPDIR; with ``apart`` its output and errors are read apart, as text.
    """
    port = free_port()
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    if tmpdir is not None:
        env["TMPDIR"] = str(tmpdir)
    proc = subprocess.Popen(
        [sys.executable, "-m", "voxfab", "studio", *extra, "--port", str(port), "--repo",
         str(repo or folder / "repo.sqlite"), "--no-browser"],
        env=env, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE if apart else subprocess.STDOUT,
        text=apart,
    )
    url = f"http://127.0.0.1:{port}"
    end = time.monotonic() + 60
    while True:
        try:
            with urllib.request.urlopen(f"{url}/api/info", timeout=1):
                return proc, url
        except OSError:
            if proc.poll() is not None or time.monotonic() > end:
                proc.kill()
                said = proc.communicate()[1 if apart else 0]
                said = said if isinstance(said, str) else said.decode()
                raise AssertionError(f"studio did not start: {said[-2000:]}") from None
            time.sleep(0.05)


def stop_studio(proc: subprocess.Popen) -> None:
    """Stop a studio started by :func:`start_studio`, killing it if it does not end in 10 s."""
    proc.terminate()
    try:
        proc.wait(10)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait(5)


@pytest.fixture(scope="session")
def server(tmp_path_factory):
    """``voxfab studio`` as a real uvicorn process on 127.0.0.1 and a free port; always stopped.

    One for the session: each start compiles or loads every kernel group, and the page
    keeps no state of its own between two loads (the tests each open it afresh).
    """
    folder = tmp_path_factory.mktemp("studio")
    proc, url = start_studio(folder)
    try:
        yield {"url": url, "repo": folder / "repo.sqlite", "folder": folder}
    finally:
        stop_studio(proc)


@pytest.fixture(scope="module")
def queen_studio(tmp_path_factory):
    """``voxfab studio queen.npy`` (the bundled queen) as a real server on 127.0.0.1; always stopped.

    One per module: a module's queen searches end with its server, so none waits behind another's.
    """
    from ._helpers import queen

    folder = tmp_path_factory.mktemp("queen-studio")
    np.save(folder / "queen.npy", queen())
    proc, url = start_studio(folder, "queen.npy")
    try:
        yield {"url": url, "folder": folder}
    finally:
        stop_studio(proc)


@pytest.fixture(scope="session")
def chromium(tmp_path_factory):
    """Headless Debian Chromium through chromedriver, one for the session (a start takes seconds)."""
    webdriver = pytest.importorskip("selenium.webdriver")
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_path = shutil.which("chromedriver")
    if not chromium or not driver_path:
        pytest.skip("needs Debian's chromium and chromium-driver (.ci/run installs them)")
    opts = webdriver.ChromeOptions()
    opts.binary_location = chromium
    for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--window-size=1400,1000",
                "--disable-gpu", "--no-first-run"):
        opts.add_argument(arg)
    opts.add_experimental_option("prefs", {"download.prompt_for_download": False})
    driver = webdriver.Chrome(options=opts, service=webdriver.ChromeService(executable_path=driver_path))
    driver.set_page_load_timeout(30)
    SHOTS.mkdir(parents=True, exist_ok=True)
    try:
        yield driver
    finally:
        driver.quit()


@pytest.fixture(scope="module")
def browser(chromium, tmp_path_factory):
    """The session's Chromium, downloading into a temporary folder of this module's own.

    Tests find their downloads by name in ``browser.downloads``: a folder per module
    keeps another module's files out of it.
    """
    downloads = tmp_path_factory.mktemp("downloads")
    chromium.execute_cdp_cmd("Browser.setDownloadBehavior", {"behavior": "allow", "downloadPath": str(downloads)})
    chromium.downloads = downloads
    try:
        yield chromium
    finally:
        chromium.get("about:blank")  # no page of this module goes on polling its server
