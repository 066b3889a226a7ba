"""The artist's bugs that live in the page, in headless Chromium: lost edits, stale state, jargon, jobs.

Mouse and keyboard only, bounded waits, a screenshot of each under ``output/studio/``.
"""

from __future__ import annotations

import json
import time
import urllib.request

import pytest

from voxfab.recipe import load_recipe, make_shape
from voxfab.studio._grid import pack

from ._helpers import SHOTS
from .conftest import ROOT
from .test_browser import attr, open_page, tab, wait

pytestmark = pytest.mark.slow


def _select(driver, element_id, value):
    from selenium.webdriver.support.ui import Select

    Select(driver.find_element("id", element_id)).select_by_value(value)


def _volume(driver):
    return int(attr(driver, "volume", "data-volume"))


def _settled(driver, what):
    """The preview count once it stops moving (each change of the drawing makes one)."""
    last, end = None, time.monotonic() + 30
    while time.monotonic() < end:
        now = (attr(driver, "latency", "data-count"), attr(driver, "volume", "data-volume"))
        if now == last:
            return _volume(driver)
        last = now
        time.sleep(0.4)
    raise AssertionError(f"{what}: the page never settled")


def _click_cell(driver, x, y):
    from selenium.webdriver import ActionChains

    canvas = driver.find_element("id", "layer-canvas")
    size = canvas.size
    cell = size["width"] / 25
    ActionChains(driver).move_to_element_with_offset(
        canvas, (x + 0.5) * cell - size["width"] / 2, (24 - y + 0.5) * cell - size["height"] / 2).click().perform()


def _cell_filled(driver, x, y):
    """Whether the layer editor paints cell (x, y) as a voxel (its own colour, read from the canvas)."""
    return driver.execute_script("""
        const c = document.getElementById('layer-canvas'), cell = c.width / 25;
        const p = c.getContext('2d').getImageData(Math.floor((arguments[0] + 0.5) * cell),
                                                  Math.floor((24 - arguments[1] + 0.5) * cell), 1, 1).data;
        return p[0] === 0xc2 && p[1] === 0x63 && p[2] === 0x2b;""", x, y)


def test_hand_edits_survive_a_change_of_the_drawing_and_undo_restores(server, browser):
    open_page(browser, server)
    v0 = _settled(browser, "first preview")
    _select(browser, "k", "2")
    wait(browser, lambda d: _volume(d) != v0, what="the thin walls")
    v2 = _settled(browser, "k = 2")
    _select(browser, "k", "0")
    wait(browser, lambda d: _volume(d) == v0, what="back to thick walls")
    # Two hand edits in an empty corner of the middle layer.
    tab(browser, "edit")
    _click_cell(browser, 0, 0)
    _click_cell(browser, 1, 0)
    wait(browser, lambda d: _volume(d) == v0 + 2, what="two voxels painted")
    tab(browser, "draw")
    _select(browser, "k", "2")
    # The new drawing's shape, plus the two edits: kept, and said so.
    wait(browser, lambda d: _volume(d) == v2 + 2, what="the edits kept on the new drawing")
    assert "kept" in browser.find_element("id", "message").text
    tab(browser, "edit")
    assert _cell_filled(browser, 0, 0) and _cell_filled(browser, 1, 0)
    browser.save_screenshot(str(SHOTS / "fix-edits-kept.png"))
    browser.find_element("id", "undo").click()  # back to the shape before the drawing changed
    wait(browser, lambda d: _volume(d) == v0 + 2, what="undo restores the edited shape")
    browser.find_element("id", "undo").click()
    wait(browser, lambda d: _volume(d) == v0 + 1, what="undo steps through the edits too")
    assert _cell_filled(browser, 0, 0) and not _cell_filled(browser, 1, 0)


def test_a_refused_drawing_shows_no_shape_not_the_old_one(server, browser, tmp_path):
    open_page(browser, server)
    _settled(browser, "first preview")
    assert browser.find_element("id", "wf").text == "well formed"
    # A bitmap that is not an image.
    bad = tmp_path / "not-a-picture.png"
    bad.write_bytes(b"this is not a PNG")
    browser.find_element("css selector", '#src-curve input[value="bitmap"]').click()
    browser.find_element("css selector", "#src-curve input.bitmap").send_keys(str(bad))
    wait(browser, lambda d: "PNG" in d.find_element("id", "message").text, what="the refusal")
    assert browser.find_element("id", "wf").text == "no shape"
    assert attr(browser, "wf", "class").strip() == "badge" and _volume(browser) == 0
    browser.save_screenshot(str(SHOTS / "fix-refused-bitmap.png"))
    # Back to an expression: a shape again.
    browser.find_element("css selector", '#src-curve input[value="expr"]').click()
    wait(browser, lambda d: d.find_element("id", "wf").text == "well formed", what="a shape again")


def test_a_bad_focus_weight_shows_no_shape(server, browser):
    from selenium.webdriver.common.keys import Keys

    open_page(browser, server)
    _select(browser, "maker", "focal")
    wait(browser, lambda d: d.find_element("id", "wf").text == "well formed" and _volume(d) > 0, what="the egg")
    weight = browser.find_element("css selector", "#foci-list input.weight")
    weight.send_keys(Keys.CONTROL, "a")  # typed over, so the one change comes with the Tab
    weight.send_keys("0", Keys.TAB)
    wait(browser, lambda d: "weight" in d.find_element("id", "message").text, what="the refusal")
    assert browser.find_element("id", "wf").text == "no shape" and _volume(browser) == 0


def test_saved_as_goes_once_the_shape_is_edited(server, browser):
    open_page(browser, server)
    _settled(browser, "first preview")
    tab(browser, "keep")
    browser.find_element("id", "save-repo").click()
    wait(browser, lambda d: attr(d, "save-result", "data-name"), what="the saved name")
    assert browser.find_element("id", "save-result").text
    tab(browser, "edit")
    _click_cell(browser, 0, 0)
    tab(browser, "keep")
    wait(browser, lambda d: d.find_element("id", "save-result").text == "", what="the note gone")
    assert browser.find_element("id", "shape-name").text == "unsaved"


def test_plain_words_on_the_page_with_the_terms_in_tooltips(server, browser):
    open_page(browser, server)
    panel = browser.find_element("id", "pane-draw")
    labels = panel.text
    for jargon in ("Mode", "k 0", "6-connected", "draft=True", "--pieces"):
        assert jargon not in labels
    k = browser.find_element("id", "k")
    assert "k" in k.find_element("xpath", "..").get_attribute("title")
    assert [o.text for o in k.find_elements("tag name", "option")] == ["thick (no gaps)", "medium", "thin"]
    # a reason for not being well formed: plain words, the library's line on hover
    tab(browser, "edit")
    _click_cell(browser, 0, 0)
    wait(browser, lambda d: attr(d, "wf", "data-well-formed") == "false", what="two pieces")
    # read in one go: each answer of the check draws the list again, which leaves a found item stale
    text, title = wait(browser, lambda d: d.execute_script(
        "const li = document.querySelector('#reasons li'); return li && [li.innerText, li.title];"),
        what="the reason")
    assert "separate pieces" in text and "6-connected" in title
    # a refused keep: the page's words, the technical line as the message's tooltip
    tab(browser, "keep")
    browser.find_element("id", "save-repo").click()
    wait(browser, lambda d: "as a draft if not well formed" in d.find_element("id", "message").text, what="refusal")
    assert "draft=True" not in browser.find_element("id", "message").text
    assert "draft=True" in attr(browser, "message", "title")


def _post(url, body):
    req = urllib.request.Request(url, data=json.dumps(body).encode(), headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(req, timeout=10) as r:
        return json.loads(r.read())


def test_a_waiting_job_shows_its_place_and_cancel_stops_it(server, browser):
    """Two long galleries fill both workers; the page's own job waits 1st in the queue, and Cancel stops it."""
    open_page(browser, server)
    _settled(browser, "first preview")
    queen = make_shape(load_recipe(ROOT / "recipes" / "chess" / "queen.toml")).grid
    body = {"grid": pack(queen), "count": 12, "options": {"timeout": 30.0, "sheet": "A4", "pieces": "auto"}}
    busy = [_post(f"{server['url']}/api/nets", dict(body, seed=s))["job"] for s in range(2)]
    try:
        tab(browser, "net")
        browser.find_element("css selector", '[data-testid="net-generate"], #net-go').click()
        wait(browser, lambda d: attr(d, "progress", "data-state") == "queued", what="the page's job queued")
        status = browser.find_element("css selector", '[data-testid="status"]')
        assert attr(browser, "progress", "data-place") == "1"
        assert "1st in the queue" in status.text
        browser.save_screenshot(str(SHOTS / "fix-job-queued.png"))
        browser.find_element("id", "job-cancel").click()
        wait(browser, lambda d: "Cancelled" in d.find_element("id", "message").text, what="the job cancelled")
        wait(browser, lambda d: "hidden" in attr(d, "progress", "class"), what="the progress bar gone")
    finally:
        for j in busy:
            _post(f"{server['url']}/api/jobs/{j}/cancel", {})


def test_voxfab_studio_shape_opens_the_page_on_it(browser, tmp_path):
    """``voxfab studio queen.npy``: the page opens on the queen, not on its default drawing."""
    import numpy as np

    from .conftest import start_studio

    queen = make_shape(load_recipe(ROOT / "recipes" / "chess" / "queen.toml")).grid
    np.save(tmp_path / "queen.npy", queen)
    proc, url = start_studio(tmp_path, str(tmp_path / "queen.npy"))
    try:
        browser.get(url + "/")
        wait(browser, lambda d: d.find_element("id", "shape-name").text == "queen.npy", what="the queen opened")
        assert _volume(browser) == int(queen.sum())
        assert browser.find_element("id", "wf").text == "well formed"
        assert "Opened queen.npy" in browser.find_element("id", "message").text
        time.sleep(0.5)  # no preview of the default drawing replaces it
        assert _volume(browser) == int(queen.sum()) and attr(browser, "latency", "data-count") is None
        browser.save_screenshot(str(SHOTS / "fix-studio-shape.png"))
    finally:
        import signal

        proc.send_signal(signal.SIGINT)
        proc.wait(10)


def test_the_chosen_net_and_its_marks_go_when_the_shape_changes(server, browser):
    import numpy as np

    from .test_browser import _gallery, slim_column
    from .test_browser_netedit import _edit_by_click, _layout

    open_page(browser, server)
    slim_column(browser)
    tab(browser, "net")
    _gallery(browser, 2)
    browser.find_element("css selector", '[data-testid="net-generate"], #net-go').click()
    items = '[data-testid="net-gallery-item"], #net-gallery figure'
    wait(browser, lambda d: len(d.find_elements("css selector", items)) == 2, timeout=90, what="two nets")
    browser.find_elements("css selector", items)[0].click()
    canvas = browser.find_element("id", "net-canvas")
    wait(browser, lambda d: _layout(d) is not None, what="the chosen net")
    layout = _layout(browser)
    # Click folds in turn (from the net's last faces, nearer its outline) until one can be cut: a cut that
    # leaves no room to hang the cut-off faces elsewhere is refused, and the next fold is tried.
    folds = sorted({tuple(p) for p in np.array(layout["folds"]).reshape(-1, 2).tolist()}, reverse=True)
    _edit_by_click(browser, canvas, layout, folds, "cut")
    assert browser.find_element("id", "marks-count").text == "1 cut, 0 kept"
    assert attr(browser, "net-chosen-label", "data-index") == "0"
    # The shape changes (a hand edit): its nets, the chosen one and the marks on it go.
    tab(browser, "edit")
    _click_cell(browser, 0, 0)
    tab(browser, "net")
    wait(browser, lambda d: not d.find_elements("css selector", items), what="the gallery gone")
    assert browser.find_element("id", "net-chosen-label").text == ""
    assert browser.find_element("id", "marks-count").text == "0 cut, 0 kept"
    assert "new net" in attr(browser, "make-net", "textContent")
    browser.save_screenshot(str(SHOTS / "fix-net-forgotten.png"))
