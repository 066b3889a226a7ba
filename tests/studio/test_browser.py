"""End to end in headless Chromium against a real ``voxfab studio`` server.

Each test drives the page with mouse and keyboard events only, waits with
bounded waits, and leaves a screenshot under ``output/studio/``.
"""

from __future__ import annotations

import re
import time

import numpy as np
import pytest

from voxfab.repo import Repository
from voxfab.studio._grid import centred

from ._helpers import SHOTS

pytestmark = pytest.mark.slow


def wait(driver, predicate, timeout=30.0, what="condition"):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        try:
            value = predicate(driver)
        except Exception:  # noqa: BLE001 - the page may be between states
            value = None
        if value:
            return value
        time.sleep(0.05)
    message = driver.find_element("id", "message").text
    raise AssertionError(f"timed out waiting for {what}; page says: {message!r}")


def open_page(driver, server):
    driver.get(server["url"] + "/")
    wait(driver, lambda d: d.find_element("id", "volume").get_attribute("data-volume"), what="first preview")


def tab(driver, name):
    driver.find_element("css selector", f'#tabs button[data-tab="{name}"]').click()


def attr(driver, element_id, name):
    return driver.find_element("id", element_id).get_attribute(name)


def draw_stroke(driver, canvas, points):
    """Press at the first point, move through the others, release (canvas pixels from the top left)."""
    from selenium.webdriver import ActionChains

    size = canvas.size
    chain = ActionChains(driver, duration=10)
    x0, y0 = points[0]
    chain.move_to_element_with_offset(canvas, x0 - size["width"] / 2, y0 - size["height"] / 2).click_and_hold()
    for (xa, ya), (xb, yb) in zip(points, points[1:]):
        chain.move_by_offset(xb - xa, yb - ya)
    chain.release().perform()


def set_expression(driver, box_id, text):
    from selenium.webdriver.common.keys import Keys

    field = driver.find_element("css selector", f"#{box_id} input.expr")
    field.clear()
    field.send_keys(text, Keys.TAB)


def test_draw_a_generatrix_and_see_the_preview_change(server, browser):
    open_page(browser, server)
    before = int(attr(browser, "volume", "data-volume"))
    version = int(attr(browser, "viewer", "data-version"))
    previews = int(attr(browser, "latency", "data-count"))
    browser.find_element("css selector", '#src-generatrix input[value="drawn"]').click()
    canvas = browser.find_element("css selector", "#src-generatrix canvas")
    # an open vase profile from the axis (x = 20) up, bulging out and back
    draw_stroke(browser, canvas, [(22, 265), (90, 262), (120, 220), (70, 150), (60, 110), (110, 40), (22, 15)])
    wait(browser, lambda d: int(attr(d, "latency", "data-count")) > previews
         and attr(d, "volume", "data-volume") != str(before), what="the preview after the stroke")
    after = int(attr(browser, "volume", "data-volume"))
    assert after != before
    assert int(attr(browser, "viewer", "data-version")) > version
    assert browser.find_element("id", "wf").text == "well formed"
    latency = int(attr(browser, "latency", "data-ms"))
    assert latency < 5000  # the figure itself is measured in bench/bench_studio.py
    browser.save_screenshot(str(SHOTS / "draw.png"))


def test_toggle_voxels_and_see_well_formedness_change(server, browser):
    open_page(browser, server)
    assert attr(browser, "wf", "data-well-formed") == "true"
    tab(browser, "edit")
    canvas = browser.find_element("id", "layer-canvas")
    size = canvas.size
    cell = size["width"] / 25

    def click_cell(x, y):
        from selenium.webdriver import ActionChains

        ActionChains(browser).move_to_element_with_offset(
            canvas, (x + 0.5) * cell - size["width"] / 2, (24 - y + 0.5) * cell - size["height"] / 2).click().perform()

    click_cell(0, 0)  # a voxel in a far corner of the middle layer: a second piece
    wait(browser, lambda d: attr(d, "wf", "data-well-formed") == "false", what="not well formed")
    reasons = browser.find_element("id", "reasons").text
    assert "6-connected pieces" in reasons
    browser.save_screenshot(str(SHOTS / "edit-two-pieces.png"))
    browser.find_element("id", "undo").click()
    wait(browser, lambda d: attr(d, "wf", "data-well-formed") == "true", what="well formed after undo")
    browser.find_element("id", "redo").click()
    wait(browser, lambda d: attr(d, "wf", "data-well-formed") == "false", what="not well formed after redo")
    click_cell(0, 0)  # remove it again
    wait(browser, lambda d: attr(d, "wf", "data-well-formed") == "true", what="well formed after removing")
    assert browser.find_element("id", "reasons").text == ""


def test_save_to_the_repository_and_browse_it(server, browser):
    open_page(browser, server)
    tab(browser, "keep")
    browser.find_element("id", "save-repo").click()
    name = wait(browser, lambda d: attr(d, "save-result", "data-name"), what="the saved name")
    assert re.fullmatch(r"\d{5}\.\d{3}", name)
    assert browser.find_element("id", "shape-name").text == name
    assert name in browser.find_element("id", "save-result").text
    # the browser lists it with a thumbnail, and opening it shows it
    fig = wait(browser, lambda d: d.find_element("css selector", f'#repo-grid figure[data-name="{name}"]'),
               what="the repository entry")
    wait(browser, lambda d: d.execute_script(
        "const i = arguments[0].querySelector('img'); return i.complete && i.naturalWidth > 0;", fig),
        what="the thumbnail")
    with Repository(server["repo"], create=False) as repo:
        assert int(name[:5]) == int(repo.get(name).sum())
    fig.click()
    wait(browser, lambda d: "Opened" in d.find_element("id", "message").text, what="the opened shape")
    browser.save_screenshot(str(SHOTS / "keep.png"))


def test_net_gallery_pick_and_download_svg(server, browser):
    from lxml import etree

    from voxfab.fabricate.netdraw import write_drawing
    from voxfab.shape import VoxelShape
    from voxfab.unfold import Net, validate

    open_page(browser, server)
    # a slim column, so the nets are quick to find
    set_expression(browser, "src-generatrix", "x = 0.12")
    wait(browser, lambda d: int(attr(d, "volume", "data-volume")) < 400, what="the slim column")
    tab(browser, "keep")
    browser.find_element("id", "save-repo").click()
    name = wait(browser, lambda d: attr(d, "save-result", "data-name"), what="the saved name")
    tab(browser, "net")
    count = browser.find_element("id", "net-count")
    count.clear()
    count.send_keys("3")
    timeout = browser.find_element("id", "net-timeout")
    timeout.clear()
    timeout.send_keys("5")
    browser.find_element("id", "net-go").click()
    wait(browser, lambda d: len(d.find_elements("css selector", "#net-gallery figure")) == 3, timeout=90,
         what="three nets")
    assert attr(browser, "net-summary", "data-found") == "3"
    browser.find_elements("css selector", "#net-gallery figure")[1].click()
    assert attr(browser, "net-chosen-label", "data-index") == "1"
    browser.save_screenshot(str(SHOTS / "net-gallery.png"))
    browser.find_element("id", "net-svg").click()
    svg = wait(browser, lambda d: next(iter(sorted(d.downloads.glob("*-net.svg"))), None), timeout=60,
               what="the downloaded SVG")
    time.sleep(0.3)  # let the download finish writing
    # the same validators as the CLI's net drawings
    import svgpathtools

    root = etree.parse(str(svg)).getroot()
    ns = {"s": "http://www.w3.org/2000/svg"}
    assert root.get("width") == "210mm" and root.get("height") == "297mm"
    groups = root.findall("s:g", ns)
    ids = [g.get("id") for g in groups]
    # layers in drawing order; a convex column has no valley folds and no grid lines
    assert ids == [i for i in ("LABEL", "GRID", "VALLEY", "MOUNTAIN", "CUT") if i in ids] and ids[-2:] == [
        "MOUNTAIN", "CUT"]
    style = {g.get("id"): g.get("stroke") for g in groups}
    assert style["CUT"] == "#ff0000" and style["MOUNTAIN"] == "#0000ff"
    cut = svgpathtools.parse_path(groups[-1].find("s:path", ns).get("d"))
    xmin, xmax, ymin, ymax = cut.bbox()
    assert 10 <= xmin < xmax <= 200 and 10 <= ymin < ymax <= 287 and cut.isclosed()
    # it is the chosen net: the JSON of the same pick refolds onto the shape and draws the same SVG
    tab(browser, "make")
    browser.find_element("css selector", '[data-make="net.json"]').click()
    js = wait(browser, lambda d: next(iter(sorted(d.downloads.glob("*-net.json"))), None), timeout=60,
              what="the downloaded net JSON")
    time.sleep(0.3)
    net = Net.from_json(js.read_text())
    with Repository(server["repo"], create=False) as repo:
        grid = centred(repo.get(name))
    assert validate(grid, net).ok
    again = svg.with_name("again.svg")
    import argparse

    write_drawing(VoxelShape(grid, 2.0), net, again, argparse.Namespace(pitch=None, sheet="A4"), title=name)
    assert again.read_bytes() == svg.read_bytes()
    assert np.count_nonzero(grid) == int(name[:5])
