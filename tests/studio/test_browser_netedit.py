"""The net editor in headless Chromium: the linked 2D and 3D views, cut and join by clicking, and the fold-up.

Driven with mouse and keyboard events only; the page's state is read back from
data attributes and the ``window.voxfabFold`` / ``window.voxfabNetView`` hooks,
and checked independently (the net rebuilt from the page's layout is validated,
the fold-up compared with ``voxfab.render.fold_frames``).
"""

from __future__ import annotations

import numpy as np
import pytest

from ._helpers import SHOTS
from .test_browser import _gallery, attr, open_page, slim_column, tab, wait
from .test_edit_api import as_net

pytestmark = pytest.mark.slow


def _move_to_net_point(browser, canvas, x, y, click=False):
    """Move the mouse to net point (x, y) of the net-2d canvas (and click), through the page's own transform."""
    from selenium.webdriver.common.actions.action_builder import ActionBuilder

    cx, cy = browser.execute_script("""
        const c = arguments[0], r = c.getBoundingClientRect();
        const p = window.voxfabNetView.toScreen(arguments[1], arguments[2]);
        return [r.left + p[0] * r.width / c.width, r.top + p[1] * r.height / c.height];""", canvas, x, y)
    actions = ActionBuilder(browser, duration=20)
    actions.pointer_action.move_to_location(int(round(cx)), int(round(cy)))
    if click:
        actions.pointer_action.click()
    actions.perform()


def _view_corners(browser):
    """The faces' corners in the page's 2D view, (F, 4, 2): each piece where netview.js lays it out."""
    return np.array(browser.execute_script("return Array.from(window.voxfabNetView.pts);"), dtype=float).reshape(-1, 4, 2)


def _edge_mid(corners, i, k):
    """The middle of edge k of face i, of the 2D view's ``corners`` (:func:`_view_corners`)."""
    c = np.asarray(corners, dtype=float)
    a, b = c[i, k], c[i, (k + 1) % 4]
    centre = c[i].mean(axis=0)
    mid = (a + b) / 2
    return mid + (centre - mid) * 0.08  # a hair inside the face, so the hit is this face's edge


def _layout(browser):
    return browser.execute_script("return window.voxfabNetView.layout;")


def _edit_by_click(browser, canvas, layout, pairs, kind, timeout=30):
    """Click the edges in turn until one edit is made; the edge, and the new layout."""
    for i, j in pairs:
        k = layout["neighbor"][4 * i: 4 * i + 4].index(j)
        version = int(attr(browser, "net-canvas", "data-version"))
        browser.execute_script("delete document.getElementById('net-canvas').dataset.error;")
        _move_to_net_point(browser, canvas, *_edit_point(browser, layout, i, k), click=True)
        wait(browser, lambda d, v=version: int(attr(d, "net-canvas", "data-version")) > v
             or attr(d, "net-canvas", "data-error"), timeout=timeout, what=f"the {kind}")
        if int(attr(browser, "net-canvas", "data-version")) > version:
            assert attr(browser, "net-canvas", "data-edit") == kind
            return (i, j), _layout(browser)
        assert "no room" in attr(browser, "net-canvas", "data-error")
    raise AssertionError(f"no {kind} could be made")


def _edit_point(browser, layout, i, k):
    """Where to click edge k of face i of the page's net ``layout`` (the one it shows), in its 2D view."""
    assert _layout(browser)["corners"] == layout["corners"], "the page shows another net"
    return [float(v) for v in _edge_mid(_view_corners(browser), i, k)]


def test_edit_the_net_in_linked_views_and_fold_it_up(server, browser):
    from selenium.webdriver import ActionChains
    from selenium.webdriver.common.keys import Keys

    from voxfab.render import fold_frames
    from voxfab.unfold import EdgeConstraints, validate
    from voxfab.unfold._layout import count_without_tab_room

    open_page(browser, server)
    slim_column(browser)
    view = browser.find_element("css selector", '[data-testid="view-3d"]')
    # Dark sides: every face the camera sees is lit, none near black.
    dark = browser.execute_script("""
        const c = arguments[0], d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let shown = 0, dark = 0;
        for (let i = 0; i < d.length; i += 4) {
          if (d[i] > 250 && d[i + 1] > 250 && d[i + 2] > 250) continue;
          shown += 1; if (0.3 * d[i] + 0.59 * d[i + 1] + 0.11 * d[i + 2] < 90) dark += 1;
        }
        return [shown, dark];""", view)
    assert dark[0] > 2000 and dark[1] < 0.02 * dark[0], dark
    tab(browser, "net")
    _gallery(browser, 1)
    browser.find_element("id", "net-go").click()
    wait(browser, lambda d: len(d.find_elements("css selector", "#net-gallery figure")) == 1, timeout=90,
         what="the gallery")
    browser.find_elements("css selector", "#net-gallery figure")[0].click()
    canvas = browser.find_element("css selector", '[data-testid="net-2d"]')
    browser.execute_script("arguments[0].scrollIntoView({block: 'center'});", canvas)
    wait(browser, lambda d: _layout(d) is not None, what="the chosen net")
    layout = _layout(browser)
    from voxfab.studio._grid import unpack

    shape = unpack(browser.execute_script("return window.voxfabNetView.shape().pack();"))

    # Zoom in with the wheel, then pan with a drag: the net's transform changes.
    before = browser.execute_script("return Object.assign({}, window.voxfabNetView.view);")
    browser.execute_script("""arguments[0].dispatchEvent(new WheelEvent('wheel', {deltaY: -400, clientX:
        arguments[0].getBoundingClientRect().left + 200, clientY: arguments[0].getBoundingClientRect().top + 150,
        bubbles: true, cancelable: true}));""", canvas)
    zoomed = browser.execute_script("return Object.assign({}, window.voxfabNetView.view);")
    assert zoomed["s"] > 1.5 * before["s"]
    ActionChains(browser, duration=20).move_to_element(canvas).click_and_hold().move_by_offset(60, 25).release().perform()
    panned = browser.execute_script("return Object.assign({}, window.voxfabNetView.view);")
    assert abs(panned["ox"] - zoomed["ox"] - 60 * int(canvas.get_attribute("width")) / canvas.size["width"]) < 8
    browser.execute_script("const v = window.voxfabNetView; v.view = Object.assign({}, arguments[0]); v.draw();", before)

    # Hover a seam in 2D: both its faces light up in 3D, with the seam's label.
    folds = {tuple(p) for p in np.array(layout["folds"]).reshape(-1, 2).tolist()}
    nb = np.array(layout["neighbor"]).reshape(-1, 4)
    seams = [(i, int(j)) for i in range(nb.shape[0]) for j in nb[i] if i < j and (i, j) not in folds]
    i, j = seams[len(seams) // 2]
    k = list(nb[i]).index(j)
    _move_to_net_point(browser, canvas, *_edit_point(browser, layout, i, k))
    wait(browser, lambda d: attr(d, "net-canvas", "data-hover-edge") == str(k), what="the hovered edge")
    name = lambda f: ",".join(str(v) for v in layout["faces"][f])  # noqa: E731
    lit = set(attr(browser, "viewer", "data-highlight").split())
    assert lit == {name(i), name(j)}
    assert attr(browser, "viewer", "data-highlight-label") == layout["labels"][f"{i}-{j}"] != ""
    browser.save_screenshot(str(SHOTS / "net-linked-2d-hover.png"))
    # ... and a face hovered in 3D lights up in 2D.
    ActionChains(browser, duration=20).move_to_element(view).perform()
    wait(browser, lambda d: attr(d, "net-canvas", "data-hover-face"), what="the face hovered in 3D")
    face = attr(browser, "net-canvas", "data-hover-face")
    assert face in set(attr(browser, "viewer", "data-highlight").split())
    browser.save_screenshot(str(SHOTS / "net-linked-3d-hover.png"))

    def check(new, marks):
        """The page's net, rebuilt from its layout alone, is a valid unfolding that keeps the marks."""
        import dataclasses

        net = as_net(new)
        net = dataclasses.replace(net, seams_without_tab_room=count_without_tab_room(shape, net))
        report = validate(shape, net, strict=False, constraints=EdgeConstraints.from_dict(marks))
        assert report.ok, report.problems[:3]
        return net

    # Click a fold: it is cut and the net laid out again around it.
    fold_pairs = sorted(folds, reverse=True)
    (a, b), cut = _edit_by_click(browser, canvas, layout, fold_pairs, "cut")
    assert (a, b) not in {tuple(p) for p in np.array(cut["folds"]).reshape(-1, 2).tolist()}
    marks = browser.execute_script("return window.voxfabNetView.marks;")
    assert marks["cut"] == [sorted([layout["faces"][a], layout["faces"][b]])]
    check(cut, marks)
    assert cut["corners"] != layout["corners"]
    assert float(attr(browser, "net-canvas", "data-seconds")) < 5
    browser.save_screenshot(str(SHOTS / "net-cut.png"))
    # Click a seam: it is joined.
    folds2 = {tuple(p) for p in np.array(cut["folds"]).reshape(-1, 2).tolist()}
    seams2 = [(i, int(j)) for i in range(nb.shape[0]) for j in nb[i] if i < j and (i, j) not in folds2
              and (i, j) != (a, b)]
    (c, d), joined = _edit_by_click(browser, canvas, cut, seams2, "join")
    assert (c, d) in {tuple(p) for p in np.array(joined["folds"]).reshape(-1, 2).tolist()}
    marks = browser.execute_script("return window.voxfabNetView.marks;")
    assert len(marks["cut"]) == 1 and len(marks["keep"]) == 1
    net = check(joined, marks)
    browser.save_screenshot(str(SHOTS / "net-joined.png"))

    # The fold slider to 100 (keyboard End): the folded faces are the shape's faces, corner for corner.
    slider = browser.find_element("css selector", '[data-testid="net-fold"]')
    slider.click()
    slider.send_keys(Keys.END)
    wait(browser, lambda d: d.find_element("css selector", '[data-testid="net-fold"]').get_attribute("value") == "100",
         what="the slider at 100")
    assert attr(browser, "viewer", "data-version") is not None
    folded = browser.execute_script("return window.voxfabFold(1);")
    corners = np.array(folded["corners"]).reshape(-1, 4, 3)
    assert np.abs(corners - np.array(joined["corners3d"]).reshape(-1, 4, 3)).max() < 1e-6
    assert np.abs(corners - net.corners3d).max() < 1e-6  # the shape's own corners, not just the page's copy
    browser.save_screenshot(str(SHOTS / "net-folded.png"))
    # Half way, every hinge turned by half its angle the right way: the Python fold-up agrees.
    half = np.array(browser.execute_script("return window.voxfabFold(0.5);")["corners"]).reshape(-1, 4, 3)
    assert np.abs(half - fold_frames(net, steps=3)[1]).max() < 1e-6
    flat = np.array(browser.execute_script("return window.voxfabFold(0);")["corners"]).reshape(-1, 3)
    assert np.linalg.svd(flat - flat.mean(axis=0), compute_uv=False)[-1] < 1e-6
    # Play: the animation runs to the end and says how long a frame takes.
    browser.find_element("id", "net-fold-play").click()
    ms = wait(browser, lambda d: attr(d, "net-canvas", "data-fold-frame-ms"), timeout=20, what="the fold played")
    print(f"fold frame {ms} ms for {net.face_count} faces")
    assert float(ms) < 100
    # Undo: back to the cut net.
    version = int(attr(browser, "net-canvas", "data-version"))
    browser.find_element("id", "net-undo").click()
    wait(browser, lambda d: int(attr(d, "net-canvas", "data-version")) > version, what="the undo")
    assert _layout(browser)["corners"] == cut["corners"]

