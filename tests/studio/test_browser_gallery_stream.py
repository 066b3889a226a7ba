"""The net gallery streams in headless Chromium: on the bundled queen, A4, pieces split automatically,
the first net is on screen (drawn on its canvas) while the server is still making the last."""

from __future__ import annotations

import json
import urllib.request

import pytest

from ._helpers import SHOTS, queen
from .test_browser import attr, wait
from .test_browser_net import by_id

pytestmark = pytest.mark.slow

COUNT = 4


def _status(url: str, job: str) -> dict:
    with urllib.request.urlopen(f"{url}/api/jobs/{job}", timeout=30) as resp:
        return json.loads(resp.read())


def _inked(browser, index: int) -> int:
    """Pixels of gallery item ``index``'s canvas that are not white: the net is drawn, not an empty frame."""
    return browser.execute_script("""
        const cv = document.querySelector(`[data-testid="net-gallery-item"][data-index="${arguments[0]}"] canvas`);
        const px = cv.getContext('2d').getImageData(0, 0, cv.width, cv.height).data;
        let n = 0;
        for (let i = 0; i < px.length; i += 4) if (px[i] < 250 || px[i + 1] < 250 || px[i + 2] < 250) n++;
        return n;""", index)


def test_the_first_queen_net_in_pieces_is_on_screen_before_the_last_is_made(queen_studio, browser):
    from selenium.webdriver.support.ui import Select

    from voxfab.studio._grid import centred

    url = queen_studio["url"]
    browser.get(url + "/")
    wait(browser, lambda d: attr(d, "volume", "data-volume") == str(int(centred(queen()).sum())), timeout=60,
         what="the queen from the command line")
    by_id(browser, "tab-net").click()
    Select(by_id(browser, "net-sheet")).select_by_value("A4")
    Select(by_id(browser, "net-pieces")).select_by_value("auto")
    count = browser.find_element("id", "net-count")
    count.clear()
    count.send_keys(str(COUNT))
    by_id(browser, "net-generate").click()
    first = wait(browser, lambda d: by_id(d, "net-gallery-item", many=True), timeout=420, what="the first net")
    # The moment the first net is on the page, the server has not made the last one yet.
    job = attr(browser, "net-gallery", "data-job")
    s = _status(url, job)
    assert s["state"] == "running" and s["made"] < COUNT, s
    assert len(first) < COUNT
    assert _inked(browser, 0) > 1000
    assert "piece" in first[0].text and "A4" in first[0].text
    browser.save_screenshot(str(SHOTS / "stream-1-first.png"))
    # The first net can be picked while the others are cut: its sheets are laid out on the board.
    first[0].click()
    wait(browser, lambda d: attr(d, "net-chosen-label", "data-index") == "0", what="the first net chosen")
    # Then every net arrives, in order, and the summary counts them.
    wait(browser, lambda d: attr(d, "net-summary", "data-found") == str(COUNT), timeout=600, what="the whole gallery")
    items = by_id(browser, "net-gallery-item", many=True)
    assert [it.get_attribute("data-index") for it in items] == [str(i) for i in range(COUNT)]
    shown = [int(it.get_attribute("data-ms")) for it in items]
    assert shown == sorted(shown) and shown[0] < shown[-1]
    assert all(_inked(browser, i) > 1000 for i in range(COUNT))
    s = _status(url, job)
    assert s["state"] == "done" and s["made"] == COUNT
    assert [n["pieces"] for n in s["result"]["nets"]] == [int(it.text.split("#")[1].split()[1]) for it in items]
    browser.save_screenshot(str(SHOTS / "stream-2-all.png"))
