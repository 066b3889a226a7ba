"""End to end in headless Chromium: the queen from the repository to net files for A4, pieces moved on the page.

The page is driven by clicks, a real mouse drag and a key press only; the files
are fetched from the download links' server URLs and checked with the CLI's own
validators (every face present, the pieces refold onto the shape, the DXF
sheets pass ezdxf's audit and keep every outline inside the margin).  A
screenshot of each step goes to ``output/studio/``.
"""

from __future__ import annotations

import io
import json
import re
import time
import urllib.request
import zipfile
from pathlib import Path

import numpy as np
import pytest
from _dxf_read import entity_points

from voxfab.repo import Repository
from voxfab.studio._grid import centred

from ._helpers import SHOTS, queen
from .test_browser import attr, open_page, wait

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]



def by_id(driver, testid, many=False):
    find = driver.find_elements if many else driver.find_element
    return find("css selector", f'[data-testid="{testid}"]')


def type_into(driver, name: str, text: str) -> None:
    """Replace what the field of id or test id ``name`` holds with ``text``."""
    field = driver.find_element("css selector", f'[id="{name}"], [data-testid="{name}"]')
    field.clear()
    field.send_keys(text)


def _fetch(url: str) -> bytes:
    with urllib.request.urlopen(url, timeout=60) as resp:
        assert resp.status == 200
        return resp.read()


def _files(raw: bytes, ext: str) -> list[bytes]:
    """The file itself, or the sheets / pieces of a zip, in name order."""
    if raw[:2] != b"PK":
        return [raw]
    with zipfile.ZipFile(io.BytesIO(raw)) as zf:
        # in number order: net.piece-2 before net.piece-10
        names = sorted((n for n in zf.namelist() if n.endswith(ext)),
                       key=lambda n: [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", n)])
        return [zf.read(n) for n in names]


def _downloads(driver, server) -> dict[str, bytes]:
    out = {}
    for kind in ("svg", "dxf", "pdf", "json"):
        href = by_id(driver, f"download-net-{kind}").get_attribute("href")
        assert href.startswith(server["url"] + "/api/files/"), href
        out[kind] = _fetch(href)
    return out


def _dxf_cut_bounds(raw: bytes) -> tuple[np.ndarray, np.ndarray]:
    import ezdxf

    doc = ezdxf.read(io.StringIO(raw.decode()))
    assert not doc.audit().has_errors
    pts = []
    for e in doc.modelspace():
        if e.dxf.layer != "CUT":
            continue
        got = entity_points(e)
        if got is not None:
            pts += [tuple(p) for p in got[0]]
    p = np.array(pts)
    return p.min(axis=0), p.max(axis=0)


def _check_files(files: dict[str, bytes], grid: np.ndarray, placement: dict) -> list:
    """The CLI's checks of the four downloads; the pieces of net.json."""
    from lxml import etree

    from voxfab.shape import surface_graph
    from voxfab.unfold import Net, validate

    pieces = [Net.from_json(raw.decode()) for raw in _files(files["json"], ".json")]
    assert len(pieces) == len(placement["pieces"])
    sg = surface_graph(grid)
    keys = [(tuple(v), tuple(n)) for p in pieces for v, n in zip(p.voxel.tolist(), p.normal.tolist())]
    assert len(keys) == len(set(keys)) == sg.face_count, "every face once"
    assert validate(grid, pieces if len(pieces) > 1 else pieces[0]).ok, "the net refolds onto the queen"
    w, h = placement["sheet"]
    m = placement["margin"]
    dxfs = _files(files["dxf"], ".dxf")
    assert len(dxfs) == placement["sheets"]
    for raw in dxfs:
        lo, hi = _dxf_cut_bounds(raw)
        assert (lo >= m - 1e-3).all() and hi[0] <= w - m + 1e-3 and hi[1] <= h - m + 1e-3  # DXF keeps 4 decimals
    svgs = _files(files["svg"], ".svg")
    assert len(svgs) == placement["sheets"]
    for raw in svgs:
        root = etree.fromstring(raw)
        assert root.get("width") == f"{w:g}mm" and root.get("height") == f"{h:g}mm"
        assert root.find("{http://www.w3.org/2000/svg}g[@id='CUT']") is not None
    assert files["pdf"].startswith(b"%PDF")
    # The sheets, and an assembly page first when the net is in pieces.
    assert files["pdf"].count(b"/Type /Page ") == placement["sheets"] + (len(pieces) > 1)
    return pieces


def _files_ready(driver, before: set[str] | None = None) -> bool:
    links = by_id(driver, "download-net-svg"), by_id(driver, "download-net-dxf"), \
        by_id(driver, "download-net-pdf"), by_id(driver, "download-net-json")
    hrefs = {a.get_attribute("href") for a in links}
    ready = all(a.get_attribute("data-state") == "ready" for a in links)
    return ready and (before is None or not hrefs & before)


def _hrefs(driver) -> set[str]:
    return {by_id(driver, f"download-net-{k}").get_attribute("href") for k in ("svg", "dxf", "pdf", "json")}


def _placement(driver) -> dict:
    return json.loads(by_id(driver, "net-sheets").get_attribute("data-placement"))


def test_queen_to_a4_in_pieces_moved_on_the_page(server, browser):
    from selenium.webdriver import ActionChains
    from selenium.webdriver.support.ui import Select

    from voxfab.fabricate.netdraw import SHEETS

    with Repository(server["repo"]) as repo:
        name = repo.add(queen()).name
        grid = centred(repo.get(name))
    open_page(browser, server)
    # The queen, opened from the repository as the artist would.
    by_id(browser, "tab-keep").click()
    fig = wait(browser, lambda d: d.find_element("css selector", f'#repo-grid figure[data-name="{name}"]'),
               what="the queen in the repository")
    fig.click()
    wait(browser, lambda d: f"Opened {name}" in by_id(d, "status").text, what="the opened queen")
    by_id(browser, "tab-net").click()
    sheet = Select(by_id(browser, "net-sheet"))
    assert [o.get_attribute("value") for o in sheet.options] == [*SHEETS, "custom"]
    sheet.select_by_value("A4")
    Select(by_id(browser, "net-pieces")).select_by_value("auto")
    assert by_id(browser, "net-face-size").get_attribute("value") == ""
    # One net is all the drags below need: the page's default gallery of 8 would search the queen 8 times.
    count = browser.find_element("id", "net-count")
    count.clear()
    count.send_keys("1")
    browser.save_screenshot(str(SHOTS / "net-1-options.png"))

    clock = {}
    t0 = time.monotonic()
    by_id(browser, "net-generate").click()
    items = wait(browser, lambda d: by_id(d, "net-gallery-item", many=True), timeout=420, what="the gallery")
    browser.save_screenshot(str(SHOTS / "net-2-gallery.png"))
    clock["gallery"] = time.monotonic() - t0
    t0 = time.monotonic()
    items[0].click()
    wait(browser, _files_ready, timeout=240, what="the net files")
    clock["files"] = time.monotonic() - t0
    assert "Net files ready" in by_id(browser, "status").text
    browser.save_screenshot(str(SHOTS / "net-3-chosen.png"))

    placement = _placement(browser)
    assert placement["sheet"] == list(SHEETS["A4"]) and len(placement["pieces"]) > 1
    old_files = _downloads(browser, server)
    pieces = _check_files(old_files, grid, placement)

    # Drag the smallest piece with the mouse by whole faces, right or up, where its sheet has room for it.
    from voxfab.fabricate.netdraw import DrawingOptions
    from voxfab.fabricate.netdraw._legible import tab_depth

    q = min(range(len(pieces)), key=lambda i: pieces[i].face_count)
    f = placement["face_size"]

    def expected_box(p: dict) -> tuple[np.ndarray, np.ndarray]:
        c = pieces[q].corners2d.reshape(-1, 2).astype(float)
        for _ in range(p["turns"]):
            c = np.stack([-c[:, 1], c[:, 0]], axis=1)
        mm = np.array([p["x"], p["y"]]) + c * f
        return mm.min(axis=0), mm.max(axis=0)

    # Drop it on the empty sheet: it goes to the middle of a sheet of its own, the files follow.
    browser.execute_script("arguments[0].scrollIntoView({block: 'start'})", by_id(browser, "net-sheets"))
    views = by_id(browser, "net-sheet-view", many=True)
    source = views[placement["pieces"][q]["sheet"]]
    scale = (source.size["width"] - 2) / placement["sheet"][0]  # less the 1 px border
    # A point of the piece: the middle of its first face.
    face = pieces[q].corners2d[0].astype(float)
    for _ in range(placement["pieces"][q]["turns"]):
        face = np.stack([-face[:, 1], face[:, 0]], axis=1)
    cx, cy = np.array([placement["pieces"][q]["x"], placement["pieces"][q]["y"]]) + face.mean(axis=0) * f
    before = _hrefs(browser)
    ActionChains(browser, duration=20).move_to_element_with_offset(
        source, cx * scale - source.size["width"] / 2 + 1, source.size["height"] / 2 - 1 - cy * scale
    ).click_and_hold().move_by_offset(4, 4).move_to_element(views[-1]).move_by_offset(2, 2).release().perform()
    wait(browser, lambda d: _placement(d)["pieces"][q]["sheet"] == _placement(d)["sheets"] - 1
         and _placement(d) != placement, what="the piece on a sheet of its own")
    wait(browser, lambda d: _files_ready(d, before), timeout=240, what="the files with the new sheet")
    browser.save_screenshot(str(SHOTS / "net-6-new-sheet.png"))
    alone = _placement(browser)
    assert sum(p["sheet"] == alone["pieces"][q]["sheet"] for p in alone["pieces"]) == 1
    lo, hi = expected_box(alone["pieces"][q])
    assert np.abs((lo + hi) / 2 - np.array(alone["sheet"]) / 2).max() <= f, "in the middle of its sheet"
    files = _downloads(browser, server)
    _check_files(files, grid, alone)
    got_lo, got_hi = _dxf_cut_bounds(_files(files["dxf"], ".dxf")[-1])
    assert (got_lo <= lo + 1e-3).all() and (got_hi >= hi - 1e-3).all()
    placement, old_files = alone, files

    place = placement["pieces"][q]
    lo, hi = expected_box(place)
    pad = tab_depth(DrawingOptions(), f)
    room = np.floor((np.array(placement["sheet"]) - placement["margin"] - pad - hi) / f + 1e-9).astype(int)
    axis = int(np.argmax(room))
    steps = int(min(room[axis], 3))
    assert steps >= 1, "the smallest piece has room to move on its sheet"
    # Grab it by the middle of one of its faces.
    face = pieces[q].corners2d[0].astype(float)
    for _ in range(place["turns"]):
        face = np.stack([-face[:, 1], face[:, 0]], axis=1)
    cx, cy = np.array([place["x"], place["y"]]) + face.mean(axis=0) * f
    browser.execute_script("arguments[0].scrollIntoView({block: 'start'})", by_id(browser, "net-sheets"))
    views = by_id(browser, "net-sheet-view", many=True)
    assert len(views) == placement["sheets"] + 1  # and an empty one for a new sheet
    source = views[place["sheet"]]
    scale = (source.size["width"] - 2) / placement["sheet"][0]  # less the 1 px border
    shift = steps * f * scale
    before = _hrefs(browser)
    chain = ActionChains(browser, duration=20).move_to_element_with_offset(
        source, cx * scale - source.size["width"] / 2 + 1, source.size["height"] / 2 - 1 - cy * scale).click_and_hold()
    for _ in range(4):
        chain.move_by_offset(shift / 4 if axis == 0 else 0, -shift / 4 if axis == 1 else 0)
    chain.release().perform()
    t0 = time.monotonic()
    want = np.array([place["x"], place["y"]]) + np.eye(2)[axis] * steps * f
    wait(browser, lambda d: np.allclose([_placement(d)["pieces"][q]["x"], _placement(d)["pieces"][q]["y"]], want,
                                        atol=1e-6), what="the dragged piece")
    wait(browser, lambda d: _files_ready(d, before), timeout=240, what="the files of the new layout")
    clock["files after the drag"] = time.monotonic() - t0
    browser.save_screenshot(str(SHOTS / "net-4-dragged.png"))
    moved = _placement(browser)
    files = _downloads(browser, server)
    _check_files(files, grid, moved)
    sheet_lo, sheet_hi = _dxf_cut_bounds(_files(old_files["dxf"], ".dxf")[place["sheet"]])
    lo, hi = _dxf_cut_bounds(_files(files["dxf"], ".dxf")[place["sheet"]])
    # That sheet's outline moved by the drag, whole faces (when the piece is alone there), no other sheet changed.
    if sum(p["sheet"] == place["sheet"] for p in placement["pieces"]) == 1:
        assert np.allclose(lo - sheet_lo, np.eye(2)[axis] * steps * f) and np.allclose(hi - sheet_hi, lo - sheet_lo)
    for k, (a, b) in enumerate(zip(_files(old_files["dxf"], ".dxf"), _files(files["dxf"], ".dxf"))):
        if k != place["sheet"]:
            assert np.allclose(np.concatenate(_dxf_cut_bounds(a)), np.concatenate(_dxf_cut_bounds(b)))
    last = _files(files["dxf"], ".dxf")[place["sheet"]]

    # The sheet holds that piece where the page shows it: its outline is the faces plus their tabs.
    lo, hi = _dxf_cut_bounds(last)
    want_lo, want_hi = expected_box(moved["pieces"][q])
    assert (lo <= want_lo + 1e-3).all() and (hi >= want_hi - 1e-3).all()
    assert (lo >= want_lo - 5.0 - 1e-3).all() and (hi <= want_hi + 5.0 + 1e-3).all()

    # Turn it half a turn with the R key (two quarter turns): the download follows again.
    before = _hrefs(browser)
    ActionChains(browser).send_keys("r").pause(0.2).send_keys("r").perform()
    wait(browser, lambda d: _placement(d)["pieces"][q]["turns"] == (moved["pieces"][q]["turns"] + 2) % 4,
         what="the turned piece")
    wait(browser, lambda d: _files_ready(d, before), timeout=240, what="the files of the turned piece")
    print("seconds:", {k: round(v, 1) for k, v in clock.items()})
    browser.save_screenshot(str(SHOTS / "net-5-turned.png"))
    turned_place = _placement(browser)
    files = _downloads(browser, server)
    _check_files(files, grid, turned_place)
    lo, hi = _dxf_cut_bounds(_files(files["dxf"], ".dxf")[place["sheet"]])
    want_lo, want_hi = expected_box(turned_place["pieces"][q])
    assert (lo <= want_lo + 1e-3).all() and (hi >= want_hi - 1e-3).all()
    assert attr(browser, "download-net-dxf", "href") not in before

    # Cut a fold of the largest piece in the net view: it splits in two, and every other piece, the one
    # moved and turned by hand too, stays where the sheets showed it; the files follow the new layout.
    from .test_browser_netedit import _edit_by_click, _layout
    from .test_relayout_api import pieces_of, spots

    shown = {"layout": _layout(browser), "placement": turned_place}
    biggest = max(pieces_of(shown).items(), key=lambda kv: len(kv[1]))[0]
    lay = shown["layout"]
    folds = [(i, j) for i, j in np.array(lay["folds"]).reshape(-1, 2).tolist() if lay["piece"][i] == biggest]
    browser.execute_script("arguments[0].scrollIntoView({block: 'center'})", by_id(browser, "net-2d"))
    before = _hrefs(browser)
    _edit_by_click(browser, by_id(browser, "net-2d"), lay, folds[len(folds) // 2:][:6], "cut")
    wait(browser, lambda d: len(_placement(d)["pieces"]) == len(pieces) + 1, what="the pieces laid out again")
    cut = {"layout": _layout(browser), "placement": _placement(browser)}
    alone = set(pieces_of(shown).values()) & set(pieces_of(cut).values())
    assert len(alone) == len(pieces) - 1
    was, now = spots(shown), spots(cut)
    for face in frozenset().union(*alone):
        assert was[face][0] == now[face][0] and np.allclose(was[face][1], now[face][1], atol=1e-6)
    wait(browser, lambda d: _files_ready(d, before), timeout=240, what="the files of the cut net")
    browser.save_screenshot(str(SHOTS / "net-7-cut.png"))
    _check_files(_downloads(browser, server), grid, cut["placement"])


def test_a_net_that_does_not_fit_says_so_plainly_and_one_click_splits_it(server, browser):
    from selenium.webdriver.support.ui import Select

    from .test_browser import slim_column

    open_page(browser, server)
    slim_column(browser)
    by_id(browser, "tab-net").click()
    # A laser bed of any size: the custom field shows for it only.
    assert not by_id(browser, "net-sheet-custom").is_displayed()
    Select(by_id(browser, "net-sheet")).select_by_value("custom")
    assert by_id(browser, "net-sheet-custom").is_displayed()
    Select(by_id(browser, "net-sheet")).select_by_value("A5")
    assert not by_id(browser, "net-sheet-custom").is_displayed()
    Select(by_id(browser, "net-pieces")).select_by_value("one")
    type_into(browser, "net-face-size", "20")
    type_into(browser, "net-timeout", "5")
    # One net shows the refusal and its ways out, and the split that follows: not the page's default 8.
    type_into(browser, "net-count", "1")
    by_id(browser, "net-generate").click()
    buttons = wait(browser, lambda d: d.find_elements("css selector", '[data-testid="net-ways-out"] button'),
                   timeout=120, what="the ways out")
    status = by_id(browser, "status").text
    # The net pipeline's words, without the CLI's flags.
    assert "does not fit sheet A5 at 20 mm faces" in status and "--" not in status, status
    labels = [b.text for b in buttons]
    assert labels[0] == "split it into pieces" and all("--" not in t for t in labels)
    browser.save_screenshot(str(SHOTS / "net-ways-out.png"))
    buttons[0].click()
    items = wait(browser, lambda d: by_id(d, "net-gallery-item", many=True), timeout=240, what="the split net")
    assert Select(by_id(browser, "net-pieces")).first_selected_option.get_attribute("value") == "auto"
    assert not browser.find_elements("css selector", '[data-testid="net-ways-out"] button')
    assert "pieces on" in items[0].text
    browser.save_screenshot(str(SHOTS / "net-split.png"))


def test_does_one_piece_fit_this_sheet_is_answered_exactly(server, browser):
    from selenium.webdriver.support.ui import Select

    from .test_browser import slim_column

    open_page(browser, server)
    slim_column(browser)
    by_id(browser, "tab-net").click()
    Select(by_id(browser, "net-sheet")).select_by_value("A3")
    face = by_id(browser, "net-face-size")
    face.clear()
    face.send_keys("10")
    by_id(browser, "net-fits").click()
    answer = wait(browser, lambda d: by_id(d, "net-fits-answer").get_attribute("data-answer"), timeout=120,
                  what="the exact answer")
    text = by_id(browser, "net-fits-answer").text
    assert answer == "yes" and "fits" in text and "--" not in text, text
    browser.save_screenshot(str(SHOTS / "net-fits.png"))
