"""The page defects an artist hit on the queen, in headless Chromium (issue 37, items 1 to 7 and 9).

``voxfab studio queen.npy`` as a real server; the Net tab is driven with clicks and
typed values, the page's state read back from its controls, data attributes and the
``window.voxfabNetView`` / ``window.voxfabFold`` hooks; a screenshot of each test
goes under ``output/studio/``.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from _dxf_read import entity_points

from ._helpers import SHOTS, queen
from .test_browser import attr, tab, wait
from .test_browser_net import _check_files, _downloads, _files_ready, _placement, by_id
from .test_browser_netedit import _edit_point, _layout, _move_to_net_point

pytestmark = pytest.mark.slow

#: A queen's gallery or way out may wait behind other work on a loaded machine.
NET_WAIT = 420


def _open_queen(browser, studio):
    from voxfab.studio._grid import centred

    browser.get(studio["url"] + "/")
    volume = str(int(centred(queen()).sum()))
    wait(browser, lambda d: attr(d, "volume", "data-volume") == volume, timeout=60, what="the queen")
    wait(browser, lambda d: attr(d, "make-buttons", "data-ready"), what="the Make buttons")


def _type(browser, element_id, text):
    from selenium.webdriver.common.keys import Keys

    field = browser.find_element("id", element_id)
    field.send_keys(Keys.CONTROL, "a")
    field.send_keys(Keys.DELETE)
    if text:
        field.send_keys(text)


def _net_options(browser, sheet, *, pieces="one", face="", count=1, marks=True, seconds=20):
    """Set the Net tab's controls as an artist would: menus, typed numbers, ticked boxes."""
    from selenium.webdriver.support.ui import Select

    if re.fullmatch(r"\d+x\d+", sheet):
        Select(by_id(browser, "net-sheet")).select_by_value("custom")
        _type(browser, "net-sheet-custom", sheet)
    else:
        Select(by_id(browser, "net-sheet")).select_by_value(sheet)
    Select(by_id(browser, "net-pieces")).select_by_value(pieces)
    _type(browser, "net-face", face)
    _type(browser, "net-count", str(count))
    _type(browser, "net-timeout", str(seconds))
    for box in ("net-numbers", "net-tabs"):
        if browser.find_element("id", box).is_selected() != marks:
            browser.find_element("id", box).click()


def _controls(browser):
    """The Net tab's options as its controls show them, by the option names of a way out."""
    face = browser.find_element("id", "net-face").get_attribute("value")
    sheet = browser.find_element("id", "net-sheet").get_attribute("value")
    return {"sheet": browser.find_element("id", "net-sheet-custom").get_attribute("value") if sheet == "custom" else sheet,
            "pieces": browser.find_element("id", "net-pieces").get_attribute("value"),
            "face_size": float(face) if face else None,
            "numbers": browser.find_element("id", "net-numbers").is_selected(),
            "tabs": browser.find_element("id", "net-tabs").is_selected()}


def _ways_out(browser):
    return browser.find_elements("css selector", '[data-testid="net-ways-out"] button')


def _gallery_items(browser):
    return by_id(browser, "net-gallery-item", many=True)


def _generate(browser, *, refused=False):
    """Generate; the ways out of a refusal, or the gallery's items."""
    by_id(browser, "net-generate").click()
    if refused:
        return wait(browser, _ways_out, timeout=NET_WAIT, what="the refusal's ways out")
    # the nets come one by one; the summary once the last is there
    wait(browser, lambda d: d.find_element("id", "net-summary").get_attribute("data-found"), timeout=NET_WAIT,
         what="the whole gallery")
    return _gallery_items(browser)


def _fits(caption):
    """Whether a gallery caption says its net fits ("3 pieces on 2 sheets A4, ...")."""
    return re.search(r" on \d+ sheets? ", caption) is not None


# --- 1. every way out applies all of its options, and succeeds -----------------------------------

def test_every_way_out_applies_all_its_options_and_succeeds(queen_studio, browser):
    _open_queen(browser, queen_studio)
    tab(browser, "net")
    _net_options(browser, "Letter", seconds=5)
    offered = [(b.text, json.loads(b.get_attribute("data-options"))) for b in _generate(browser, refused=True)]
    # the artist's loop: a way out that turns the seam labels and glue tabs off
    assert any(options.get("numbers") is False and options.get("tabs") is False for _, options in offered), offered
    for n, (label, options) in enumerate(offered):
        if n:
            _net_options(browser, "Letter", seconds=5)
            _generate(browser, refused=True)
        button = _ways_out(browser)[n]
        assert button.text == label
        button.click()
        shown = _controls(browser)
        assert {k: shown[k] for k in options} == options, (label, shown)
        wait(browser, lambda d: d.find_element("id", "net-summary").get_attribute("data-found") or _ways_out(d),
             timeout=NET_WAIT, what=f"the gallery after {label!r}")
        items = _gallery_items(browser)
        assert not _ways_out(browser), f"{label!r} was refused again"
        assert _fits(items[0].text), (label, items[0].text)
        browser.save_screenshot(str(SHOTS / f"page-way-out-{n + 1}.png"))


# --- 2. a refused search leaves no net behind ----------------------------------------------------

def test_a_refused_search_clears_the_last_net(queen_studio, browser):
    _open_queen(browser, queen_studio)
    tab(browser, "net")
    _net_options(browser, "900x600")
    _generate(browser)[0].click()
    wait(browser, _files_ready, timeout=NET_WAIT, what="the net files")
    assert by_id(browser, "net-2d").get_attribute("data-faces") != "0"
    assert browser.find_element("id", "net-summary").text
    _net_options(browser, "Letter")
    _generate(browser, refused=True)
    # no summary, no net to edit or cut, no sheets, no files
    assert browser.find_element("id", "net-summary").text == ""
    assert browser.find_element("id", "net-chosen-label").text == ""
    assert by_id(browser, "net-2d").get_attribute("data-faces") == "0"
    assert browser.execute_script("return window.voxfabNetView.layout === null && !window.voxfabNetView.job;")
    assert not _gallery_items(browser)
    assert all(by_id(browser, f"download-net-{k}").get_attribute("href") is None for k in ("svg", "dxf", "pdf", "json"))
    browser.save_screenshot(str(SHOTS / "page-refused-clears.png"))


# --- 3. a lit seam does not stay -----------------------------------------------------------------

def _zoom_onto(browser, x, y, scale=40):
    browser.execute_script("""
        const v = window.voxfabNetView, c = v.canvas, s = arguments[2];
        v.view = Object.assign({}, v.view, {s, ox: c.width / 2 - arguments[0] * s, oy: c.height / 2 + arguments[1] * s});
        v.draw();""", x, y, scale)


def _hover_a_seam(browser):
    """Hover the middle of a cut edge (a seam with its label) in the 2D view; its label, lit in 3D."""
    canvas = by_id(browser, "net-2d")
    browser.execute_script("arguments[0].scrollIntoView({block: 'center'});", canvas)
    layout = _layout(browser)
    folds = {tuple(p) for p in np.array(layout["folds"]).reshape(-1, 2).tolist()}
    nb = np.array(layout["neighbor"]).reshape(-1, 4)
    seams = [(i, int(j)) for i in range(nb.shape[0]) for j in nb[i] if i < j and (i, j) not in folds]
    i, j = seams[len(seams) // 2]
    k = list(nb[i]).index(j)
    x, y = _edit_point(browser, layout, i, k)
    _zoom_onto(browser, x, y)
    _move_to_net_point(browser, canvas, x, y)
    return wait(browser, lambda d: attr(d, "viewer", "data-highlight-label"), what="the seam lit in 3D"), (x, y)


def _move_away(browser):
    from selenium.webdriver import ActionChains

    ActionChains(browser, duration=20).move_to_element(browser.find_element("id", "net-summary")).perform()


def _unlit(browser):
    return attr(browser, "viewer", "data-highlight") == "" and attr(browser, "viewer", "data-highlight-label") == ""


def test_a_clicked_seam_goes_dark_and_stays_dark_on_a_new_gallery_and_shape(queen_studio, browser):
    _open_queen(browser, queen_studio)
    tab(browser, "net")
    _net_options(browser, "900x600")
    _generate(browser)[0].click()
    wait(browser, _files_ready, timeout=NET_WAIT, what="the net files")
    # hover a seam, click it (a join), and take the mouse away: nothing stays lit
    label, (x, y) = _hover_a_seam(browser)
    version = int(attr(browser, "net-canvas", "data-version"))
    _move_to_net_point(browser, by_id(browser, "net-2d"), x, y, click=True)
    wait(browser, lambda d: int(attr(d, "net-canvas", "data-version")) > version or attr(d, "net-canvas", "data-error"),
         timeout=120, what="the click's edit")
    _move_away(browser)
    wait(browser, _unlit, what="the 3D view unlit once the mouse left")
    # lit again, then a new gallery: unlit
    _hover_a_seam(browser)
    _generate(browser)
    wait(browser, _unlit, what="the 3D view unlit by a new gallery")
    # lit again, then a new shape (a voxel painted in Edit): unlit
    _gallery_items(browser)[0].click()
    wait(browser, lambda d: _layout(d), what="the net chosen")
    _hover_a_seam(browser)
    tab(browser, "edit")
    from .test_browser_fixes import _click_cell

    _click_cell(browser, 0, 0)
    wait(browser, _unlit, what="the 3D view unlit on a new shape")
    browser.save_screenshot(str(SHOTS / "page-seam-unlit.png"))


# --- 4. one stroke is one undo step --------------------------------------------------------------

def _slow_stroke(driver, canvas, points, ms=25):
    """Press at the first point, drag through the others ``ms`` each, release (canvas pixels from the top left)."""
    from selenium.webdriver import ActionChains

    size = canvas.size
    chain = ActionChains(driver, duration=ms)
    x0, y0 = points[0]
    chain.move_to_element_with_offset(canvas, x0 - size["width"] / 2, y0 - size["height"] / 2).click_and_hold()
    for (xa, ya), (xb, yb) in zip(points, points[1:]):
        chain.move_by_offset(xb - xa, yb - ya)
    chain.release().perform()


def test_a_freehand_stroke_is_one_undo_step(queen_studio, browser):
    from selenium.webdriver.support.ui import Select

    from .test_browser_fixes import _click_cell

    _open_queen(browser, queen_studio)
    queen = int(attr(browser, "volume", "data-volume"))
    # the drawing's shape in place of the queen, with a hand edit on it
    Select(browser.find_element("id", "k")).select_by_value("2")
    wait(browser, lambda d: int(attr(d, "volume", "data-volume")) not in (queen, 0), what="the drawn shape")
    tab(browser, "edit")
    drawn = int(attr(browser, "volume", "data-volume"))
    _click_cell(browser, 0, 0)
    wait(browser, lambda d: int(attr(d, "volume", "data-volume")) == drawn + 1, what="the hand edit")
    # a freehand generatrix: no shape while it is empty, then one stroke dragged through 40 points
    tab(browser, "draw")
    browser.find_element("css selector", '#src-generatrix input[value="drawn"]').click()
    wait(browser, lambda d: attr(d, "volume", "data-volume") == "0", what="no shape while the generatrix is empty")
    count = int(attr(browser, "latency", "data-count") or 0)
    canvas = browser.find_element("css selector", "#src-generatrix canvas")
    ts = np.linspace(0, 1, 40)
    _slow_stroke(browser, canvas, [(int(22 + 90 * np.sin(np.pi * t) ** 2), int(265 - 250 * t)) for t in ts])
    wait(browser, lambda d: int(attr(d, "latency", "data-count") or 0) > count
         and attr(d, "volume", "data-volume") not in ("0", None), what="the stroke's shape")
    # one Undo takes back the whole stroke (and the empty generatrix, which has no shape to return to)
    tab(browser, "edit")
    browser.find_element("id", "undo").click()
    wait(browser, lambda d: int(attr(d, "volume", "data-volume")) == drawn + 1, timeout=10,
         what="one undo back to the hand-edited shape before the stroke")
    browser.save_screenshot(str(SHOTS / "page-stroke-undo.png"))


# --- 5. fold 0 is flat, pieces as on the page ----------------------------------------------------

def test_fold_zero_lays_every_piece_flat_as_in_the_2d_view(queen_studio, browser):
    _open_queen(browser, queen_studio)
    tab(browser, "net")
    _net_options(browser, "A4", pieces="auto", count=2)
    items = _generate(browser)
    found = len(items)
    summary = browser.find_element("id", "net-summary").text
    assert summary.startswith(f"{found} net{'s' if found > 1 else ''} in pieces in "), summary  # not "2 net in pieces"
    items[0].click()
    layout = wait(browser, lambda d: _layout(d), what="the net chosen")
    assert max(layout["piece"]) >= 1, "the queen on A4 comes in pieces"
    flat = np.array(browser.execute_script("return window.voxfabFold(0);")["corners"]).reshape(-1, 3)
    # one plane for all the pieces ...
    centred = flat - flat.mean(axis=0)
    assert np.linalg.svd(centred, compute_uv=False)[-1] < 1e-6
    # ... and in it, the pieces where the 2D view puts them (a rigid motion of its points, no overlap)
    view = np.array(browser.execute_script("return Array.from(window.voxfabNetView.pts);")).reshape(-1, 2)
    view = np.column_stack([view, np.zeros(len(view))])
    a, b = view - view.mean(axis=0), centred
    u, _, vt = np.linalg.svd(a.T @ b)
    assert np.abs(a @ (u @ vt) - b).max() < 1e-6
    # ... and at 1 the surface, as before
    folded = np.array(browser.execute_script("return window.voxfabFold(1);")["corners"])
    assert np.abs(folded - np.array(layout["corners3d"])).max() < 1e-6
    browser.save_screenshot(str(SHOTS / "page-fold-zero.png"))


# --- 6. empty face size: the largest that fits ---------------------------------------------------

def _dxf_fold_lengths(raw: bytes) -> np.ndarray:
    """Lengths in mm of the fold lines of a net's DXF (read back with ezdxf)."""
    import io

    import ezdxf

    doc = ezdxf.read(io.StringIO(raw.decode()))
    out = []
    for e in doc.modelspace():
        if e.dxf.layer not in ("MOUNTAIN", "VALLEY"):
            continue
        got = entity_points(e)  # LINE, POLYLINE (R12) or LWPOLYLINE (R2000, the default)
        if got is None:
            continue
        pts = [tuple(p) for p in got[0]] + ([tuple(got[0][0])] if got[1] else [])
        out += [float(np.hypot(b[0] - a[0], b[1] - a[1])) for a, b in zip(pts, pts[1:])]
    return np.array([d for d in out if d > 1e-6])


def test_an_empty_face_size_is_the_largest_at_which_the_net_fits(queen_studio, browser):
    _open_queen(browser, queen_studio)
    tab(browser, "net")
    _net_options(browser, "900x600", count=3)
    items = _generate(browser)
    summary = browser.find_element("id", "net-summary").text
    face = float(re.search(r"faces ([\d.]+) mm", summary).group(1))
    caps = [float(re.search(r"faces ([\d.]+) mm", item.text).group(1)) for item in items]
    assert all(c == face for c in caps)
    assert all(_fits(item.text) for item in items)
    # the gallery's own fit data: its best net fits at this face size and at no larger one (0.1 mm steps)
    items[0].click()
    wait(browser, _files_ready, timeout=NET_WAIT, what="the net files")
    nets = browser.execute_script("""
        const xhr = new XMLHttpRequest(); xhr.open('GET', '/api/jobs/' + window.voxfabNetView.job, false); xhr.send();
        return JSON.parse(xhr.responseText).result.nets;""")
    assert all(n["fit"]["fits"] and n["fit"]["face_size"] == face for n in nets)
    assert face in {n["fit"]["largest_face_size"] for n in nets}, [n["fit"] for n in nets]
    assert face > 8.6  # the smallest face with legible marks, where the page used to stay
    # ... and the files are drawn at that face size: fold lines run whole face edges of `face` mm
    # (those of the glue tabs are a little shorter)
    lengths = _dxf_fold_lengths(_downloads(browser, queen_studio)["dxf"])
    whole = np.abs(lengths / face - np.round(lengths / face)) < 1e-3
    assert whole.any() and lengths[whole].min() == pytest.approx(face, abs=1e-3)
    assert (lengths[~whole] < face).all()


# --- 7. a "yes" opens the net found ------------------------------------------------------------

def test_a_yes_opens_the_net_found_in_the_editor_with_its_files(queen_studio, browser):
    _open_queen(browser, queen_studio)
    tab(browser, "net")
    _net_options(browser, "A1", face="8.6", seconds=30)
    by_id(browser, "net-fits").click()
    answer = wait(browser, lambda d: by_id(d, "net-fits-answer").get_attribute("data-answer"), timeout=NET_WAIT,
                  what="the answer")
    assert answer == "yes", by_id(browser, "net-fits-answer").text
    layout = wait(browser, lambda d: _layout(d), what="the net found, in the editor")
    assert max(layout["piece"]) == 0 and by_id(browser, "net-2d").get_attribute("data-faces") == str(len(layout["faces"]))
    wait(browser, _files_ready, timeout=NET_WAIT, what="its files")
    # the files of the net found, checked as the CLI checks its own: every face, refolded onto the queen
    from voxfab.studio._grid import centred

    pieces = _check_files(_downloads(browser, queen_studio), centred(queen()), _placement(browser))
    assert len(pieces) == 1 and pieces[0].face_count == len(layout["faces"])
    assert browser.find_element("id", "net-summary").text
    # named after the shape the studio opened (queen.npy), not "studio"
    names = {k: by_id(browser, f"download-net-{k}").get_attribute("download") for k in ("svg", "dxf", "pdf", "json")}
    assert names == {k: f"queen-net.{k}" for k in names}, names
    browser.save_screenshot(str(SHOTS / "page-fits-opens.png"))


# --- 9. small points: the GIF for tubes only, plain words on the controls -------------------------

def test_the_tube_animation_is_offered_for_a_drawn_tube_only_and_the_controls_speak_plainly(queen_studio, browser):
    from selenium.webdriver.support.ui import Select

    _open_queen(browser, queen_studio)
    tab(browser, "make")
    gif = browser.find_element("css selector", '[data-make="animation.gif"]')
    assert not gif.is_displayed()  # the queen is no tube
    assert browser.find_element("css selector", '[data-make="mesh.stl"]').is_displayed()
    tab(browser, "draw")
    Select(browser.find_element("id", "maker")).select_by_value("tube")
    wait(browser, lambda d: "replaced" in d.find_element("id", "message").text, what="the drawn tube")
    tab(browser, "make")
    wait(browser, lambda d: d.find_element("css selector", '[data-make="animation.gif"]').is_displayed(),
         what="the GIF offered for the drawn tube")
    tab(browser, "net")
    timeout = browser.find_element("css selector", "label:has(#net-timeout)")
    assert "seconds per net" in timeout.text and "s per net" not in timeout.text.replace("seconds per net", "")
    assert "timeout" in timeout.get_attribute("title")
