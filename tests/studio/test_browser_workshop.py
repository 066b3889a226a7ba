"""The artist's workshop on the queen in headless Chromium (issue 44): where things sit, how big, what is said.

``voxfab studio queen.npy`` as a real server, the page at 1400 x 1000 px. Each
test measures the page (element boxes by getBoundingClientRect, pixels per face
from the page's own transform checked against the pixels drawn, the 3D view's
inked box) rather than only finding an element; a screenshot of each goes under
``output/studio/``.
"""

from __future__ import annotations

import json
import urllib.request

import numpy as np
import pytest

from voxfab.repo import Repository

from ._helpers import SHOTS, small_shape
from .test_browser import attr, open_page, tab, wait
from .test_browser_fixes import _click_cell, _select, _settled, _volume
from .test_browser_net import by_id
from .test_browser_page import NET_WAIT, _open_queen

pytestmark = pytest.mark.slow


def _rect(driver, element) -> dict:
    return driver.execute_script("return arguments[0].getBoundingClientRect().toJSON();", element)


def _queen_gallery(browser, count: int) -> None:
    from selenium.webdriver.support.ui import Select

    tab(browser, "net")
    Select(by_id(browser, "net-sheet")).select_by_value("A4")
    Select(by_id(browser, "net-pieces")).select_by_value("auto")
    field = browser.find_element("id", "net-count")
    field.clear()
    field.send_keys(str(count))
    by_id(browser, "net-generate").click()


def _job_result(url: str, job: str) -> dict:
    with urllib.request.urlopen(f"{url}/api/jobs/{job}", timeout=30) as resp:
        return json.loads(resp.read())["result"]


def _sheet_one_extent(net: dict) -> np.ndarray:
    """Width and height in faces of what lies on a net's first sheet, its pieces turned and placed as placed."""
    lay, place = net["layout"], net["placement"]
    corners = np.array(lay["corners"], dtype=float).reshape(-1, 4, 2)
    f = place["face_size"]
    points = []
    for i, q in enumerate(lay["piece"]):
        p = place["pieces"][q]
        if p["sheet"] != 0:
            continue
        c = corners[i]
        for _ in range(p["turns"]):
            c = np.stack([-c[:, 1], c[:, 0]], axis=1)
        points.append(c + np.array([p["x"], p["y"]]) / f)
    points = np.concatenate(points)
    return points.max(axis=0) - points.min(axis=0)


def _fill_box(browser, canvas, height: int) -> list[int]:
    """[x0, y0, x1, y1] canvas pixels of the net's paper colour in the top ``height`` rows of a gallery canvas."""
    return browser.execute_script("""
        const c = arguments[0], d = c.getContext('2d').getImageData(0, 0, c.width, arguments[1]).data;
        let x0 = 1e9, y0 = 1e9, x1 = -1, y1 = -1;
        for (let y = 0; y < arguments[1]; y++) for (let x = 0; x < c.width; x++) {
          const i = 4 * (y * c.width + x);
          if (d[i] === 0xfb && d[i + 1] === 0xf1 && d[i + 2] === 0xe2) {
            x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
          }
        }
        return [x0, y0, x1 + 1, y1 + 1];""", canvas, height)


def _inked_box(browser, canvas) -> list[int]:
    """[x0, y0, x1, y1] canvas pixels of a canvas that are not white."""
    return browser.execute_script("""
        const c = arguments[0], d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let x0 = 1e9, y0 = 1e9, x1 = -1, y1 = -1;
        for (let y = 0; y < c.height; y++) for (let x = 0; x < c.width; x++) {
          const i = 4 * (y * c.width + x);
          if (d[i] < 245 || d[i + 1] < 245 || d[i + 2] < 245) {
            x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
          }
        }
        return [x0, y0, x1 + 1, y1 + 1];""", canvas)


def _queen_nets(browser, studio, count: int = 1) -> list[dict]:
    """The queen opened, a gallery of ``count`` nets in pieces for A4 on screen; the gallery's nets (its job's)."""
    _open_queen(browser, studio)
    assert browser.execute_script("return window.innerWidth;") >= 1380
    _queen_gallery(browser, count)
    wait(browser, lambda d: attr(d, "net-summary", "data-found"), timeout=NET_WAIT, what="the queen's gallery")
    nets = _job_result(studio["url"], attr(browser, "net-gallery", "data-job"))["nets"]
    assert nets[0]["pieces"] > 1 and nets[0]["placement"]["sheets"] > 1
    return nets


def _choose_first(browser) -> None:
    by_id(browser, "net-gallery-item", many=True)[0].click()
    wait(browser, lambda d: attr(d, "net-chosen-label", "data-index") == "0", what="the chosen net")


def test_the_gallery_the_editor_and_the_3d_view_side_by_side(queen_studio, browser):
    _queen_nets(browser, queen_studio)
    _choose_first(browser)
    browser.execute_script("window.scrollTo(0, 0);")
    # All three in the first screenful, at working widths, the editor and the 3D view beside the gallery.
    g = _rect(browser, browser.find_element("id", "net-gallery"))
    e, v = _rect(browser, by_id(browser, "net-2d")), _rect(browser, by_id(browser, "view-3d"))
    assert e["left"] >= g["right"] and v["left"] >= e["right"], (g, e, v)
    assert e["top"] < 200 and e["top"] < g["bottom"] and g["top"] < e["bottom"], (g, e)
    assert e["bottom"] <= browser.execute_script("return window.innerHeight;"), e
    assert e["width"] >= 400 and v["width"] >= 300 and g["width"] >= 400, (g, e, v)
    browser.save_screenshot(str(SHOTS / "workshop-side-by-side.png"))


def test_a_thumbnail_shows_its_first_sheet_large(queen_studio, browser):
    nets = _queen_nets(browser, queen_studio)
    thumb = by_id(browser, "net-gallery-item", many=True)[0].find_element("css selector", "canvas")
    box = _rect(browser, thumb)
    # The page's pixels per face, on screen, and checked against the paper it drew for the first sheet.
    per_face = float(thumb.get_attribute("data-face-px"))
    assert per_face * box["width"] / int(thumb.get_attribute("width")) >= 4.5
    main_rows = round(0.78 * int(thumb.get_attribute("height")))  # above the strip of the other sheets
    x0, y0, x1, y1 = _fill_box(browser, thumb, main_rows)
    want = _sheet_one_extent(nets[0]) * per_face
    assert abs((x1 - x0) - want[0]) <= 3 + 0.03 * want[0] and abs((y1 - y0) - want[1]) <= 3 + 0.03 * want[1], \
        ((x1 - x0, y1 - y0), want)


def test_the_chosen_net_opens_zoomed_to_fit_and_undo_says_when_there_is_nothing(queen_studio, browser):
    _queen_nets(browser, queen_studio)
    _choose_first(browser)
    editor = by_id(browser, "net-2d")
    view = browser.execute_script("return Object.assign({}, window.voxfabNetView.view);")
    w, h = int(editor.get_attribute("width")), int(editor.get_attribute("height"))
    face_px = view["s"] * _rect(browser, editor)["width"] / w
    assert face_px >= 12, face_px  # an edge's quarter face either side is 3 px at least
    # What it is fitted to (the whole net, or a piece of it) is in view whole, and fills it one way.
    fitted = attr(browser, "net-canvas", "data-fitted") or "all"
    shown = np.array(browser.execute_script("""
        const v = window.voxfabNetView, q = arguments[0], out = [];
        v.layout.piece.forEach((p, i) => { if (q === 'all' || p === Number(q) - 1)
          for (let k = 0; k < 4; k++) out.push(v.toScreen(v.pts[8 * i + 2 * k], v.pts[8 * i + 2 * k + 1])); });
        return out;""", fitted))
    assert shown.min() >= 0 and shown[:, 0].max() <= w and shown[:, 1].max() <= h, "in view whole"
    assert shown[:, 0].max() - shown[:, 0].min() > 0.8 * w or shown[:, 1].max() - shown[:, 1].min() > 0.8 * h
    # Each piece is a click away, fitted in its turn.
    buttons = browser.find_elements("css selector", '[data-testid="net-view-pieces"] button')
    assert [b.text for b in buttons][:2] == ["whole net", "piece 1"]
    buttons[-1].click()
    assert attr(browser, "net-canvas", "data-fitted") == str(len(buttons) - 1)
    browser.save_screenshot(str(SHOTS / "workshop-zoomed-to-fit.png"))
    # Undo with no edit to take back says so.
    browser.find_element("id", "net-undo").click()
    wait(browser, lambda d: "Nothing to undo" in by_id(d, "status").text, what="nothing to undo")


def test_the_folded_queen_is_framed_in_the_3d_view(queen_studio, browser):
    from selenium.webdriver.common.keys import Keys

    _queen_nets(browser, queen_studio)
    _choose_first(browser)
    slider = by_id(browser, "net-fold")
    slider.click()
    slider.send_keys(Keys.END)
    wait(browser, lambda d: by_id(d, "net-fold").get_attribute("value") == "100", what="the slider at 100")
    # In the middle of the view and most of its height.
    view3d = by_id(browser, "view-3d")
    x0, y0, x1, y1 = _inked_box(browser, view3d)
    W, H = int(view3d.get_attribute("width")), int(view3d.get_attribute("height"))
    assert (y1 - y0) >= 0.6 * H, (y0, y1, H)
    assert abs((x0 + x1) / 2 - W / 2) <= 0.08 * W and abs((y0 + y1) / 2 - H / 2) <= 0.08 * H, (x0, y0, x1, y1)
    browser.save_screenshot(str(SHOTS / "workshop-folded.png"))


def test_a_cancelled_gallery_says_how_many_nets_it_kept(queen_studio, browser):
    _open_queen(browser, queen_studio)
    _queen_gallery(browser, 8)
    wait(browser, lambda d: by_id(d, "net-gallery-item", many=True), timeout=NET_WAIT, what="a first net")
    browser.find_element("id", "job-cancel").click()
    wait(browser, lambda d: "Cancelled" in by_id(d, "status").text, timeout=60, what="the cancel")
    kept = len(by_id(browser, "net-gallery-item", many=True))
    assert 1 <= kept < 8
    status = by_id(browser, "status").text
    assert f"Cancelled: {kept} net{'s' if kept > 1 else ''} kept" in status, status
    assert browser.find_element("id", "net-summary").text.startswith(f"Cancelled: {kept} net")
    assert attr(browser, "net-summary", "data-found") == str(kept)
    browser.save_screenshot(str(SHOTS / "workshop-cancelled.png"))


def test_undo_after_opening_a_kept_shape_gives_the_file_its_name_back(queen_studio, browser):
    with Repository(queen_studio["folder"] / "repo.sqlite") as repo:
        kept = repo.add(small_shape()).name
    _open_queen(browser, queen_studio)
    assert browser.find_element("id", "shape-name").text == "queen.npy"
    queen_volume = _volume(browser)
    tab(browser, "keep")
    wait(browser, lambda d: d.find_element("css selector", f'#repo-grid figure[data-name="{kept}"]'),
         what="the kept shape").click()
    wait(browser, lambda d: d.find_element("id", "shape-name").text == kept, what="the kept shape opened")
    tab(browser, "edit")
    browser.find_element("id", "undo").click()
    wait(browser, lambda d: _volume(d) == queen_volume, what="the queen back")
    assert browser.find_element("id", "shape-name").text == "queen.npy"
    # Its files are named after it again.
    tab(browser, "make")
    browser.find_element("css selector", '[data-make="mesh.stl"]').click()
    link = wait(browser, lambda d: d.find_element("css selector", '#downloads a[data-artefact="mesh.stl"]'),
                timeout=60, what="the STL")
    assert link.get_attribute("download") == "queen.stl"
    # Nothing left to undo: said so, the shape kept.
    tab(browser, "edit")
    browser.find_element("id", "undo").click()
    wait(browser, lambda d: "Nothing to undo" in by_id(d, "status").text, what="nothing to undo")
    assert _volume(browser) == queen_volume and browser.find_element("id", "shape-name").text == "queen.npy"


def test_hand_edits_on_one_makers_shape_do_not_land_on_anothers(server, browser):
    open_page(browser, server)
    vase = _settled(browser, "the vase")
    _select(browser, "maker", "focal")
    wait(browser, lambda d: _volume(d) != vase, what="the egg")
    egg = _settled(browser, "the egg")
    tab(browser, "edit")
    _click_cell(browser, 0, 0)
    _click_cell(browser, 1, 0)
    wait(browser, lambda d: _volume(d) == egg + 2, what="two voxels painted on the egg")
    tab(browser, "draw")
    _select(browser, "maker", "revolution")
    # The vase as its drawing makes it, not with the egg's two voxels; and the page says where they went.
    wait(browser, lambda d: "starts clean" in d.find_element("id", "message").text, what="the new maker")
    assert _settled(browser, "the vase again") == vase
    browser.save_screenshot(str(SHOTS / "workshop-maker-switch.png"))
    tab(browser, "edit")
    browser.find_element("id", "undo").click()
    wait(browser, lambda d: _volume(d) == egg + 2, what="the edited egg back")
