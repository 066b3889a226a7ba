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
    wait(driver, lambda d: d.find_element("id", "make-buttons").get_attribute("data-ready"), what="the Make buttons")


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


def slim_column(driver):
    """Type the slim column's generatrix and wait for its shape (not the empty one seen while typing)."""
    set_expression(driver, "src-generatrix", "x = 0.12")
    wait(driver, lambda d: 0 < int(attr(d, "volume", "data-volume")) < 400
         and attr(d, "wf", "data-well-formed") == "true", what="the slim column")


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
    assert "separate pieces" in reasons and "6-connected" not in reasons
    browser.save_screenshot(str(SHOTS / "edit-two-pieces.png"))
    browser.find_element("id", "undo").click()
    wait(browser, lambda d: attr(d, "wf", "data-well-formed") == "true", what="well formed after undo")
    browser.find_element("id", "redo").click()
    wait(browser, lambda d: attr(d, "wf", "data-well-formed") == "false", what="not well formed after redo")
    click_cell(0, 0)  # remove it again
    wait(browser, lambda d: attr(d, "wf", "data-well-formed") == "true", what="well formed after removing")
    assert browser.find_element("id", "reasons").text == ""
    # the 3D view orbits on a drag and zooms on the wheel
    from selenium.webdriver import ActionChains

    viewer = browser.find_element("id", "viewer")
    picture = "return arguments[0].toDataURL();"
    first = browser.execute_script(picture, viewer)
    ActionChains(browser).move_to_element(viewer).click_and_hold().move_by_offset(60, 20).release().perform()
    turned = browser.execute_script(picture, viewer)
    assert turned != first
    browser.execute_script("arguments[0].dispatchEvent(new WheelEvent('wheel', {deltaY: -400}));", viewer)
    assert browser.execute_script(picture, viewer) != turned


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

    from voxfab.fabricate.netdraw import DrawingOptions, write_net_drawing
    from voxfab.unfold import Net, validate

    open_page(browser, server)
    # a slim column, so the nets are quick to find
    slim_column(browser)
    tab(browser, "keep")
    browser.find_element("id", "save-repo").click()
    name = wait(browser, lambda d: attr(d, "save-result", "data-name"), what="the saved name")
    tab(browser, "net")
    count = browser.find_element("id", "net-count")
    count.clear()
    count.send_keys("3")
    timeout = browser.find_element("id", "net-timeout")
    timeout.clear()
    timeout.send_keys("10")  # a slim column's nets take far less once the kernels are compiled
    browser.find_element("id", "net-go").click()
    wait(browser, lambda d: len(d.find_elements("css selector", "#net-gallery figure")) == 3, timeout=90,
         what="three nets")
    assert attr(browser, "net-summary", "data-found") == "3"
    browser.find_elements("css selector", "#net-gallery figure")[1].click()
    assert attr(browser, "net-chosen-label", "data-index") == "1"
    browser.save_screenshot(str(SHOTS / "net-gallery.png"))
    # the download links point at the chosen net's files on the server once they are made
    svg_link = wait(browser, lambda d: d.find_element("css selector", '[data-testid="download-net-svg"][href]'),
                    timeout=60, what="the SVG link")
    assert svg_link.get_attribute("href").startswith(server["url"] + "/api/files/")
    svg_link.click()
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
    assert style["CUT"] == "#ff0000" and style["MOUNTAIN"] == "#ff00ff"
    cut = svgpathtools.parse_path(groups[-1].find("s:path", ns).get("d"))
    xmin, xmax, ymin, ymax = cut.bbox()
    assert 10 <= xmin < xmax <= 200 and 10 <= ymin < ymax <= 287 and cut.isclosed()
    # it is the chosen net: the JSON of the same pick refolds onto the shape and draws the same SVG
    browser.find_element("css selector", '[data-testid="download-net-json"][href]').click()
    js = wait(browser, lambda d: next(iter(sorted(d.downloads.glob("*-net.json"))), None), timeout=60,
              what="the downloaded net JSON")
    time.sleep(0.3)
    net = Net.from_json(js.read_text())
    with Repository(server["repo"], create=False) as repo:
        grid = centred(repo.get(name))
    assert validate(grid, net).ok
    again = svg.with_name("again.svg")
    face = float(re.search(r"faces ([0-9.]+) mm", browser.find_element("id", "net-summary").text).group(1))
    write_net_drawing(grid, net, again, DrawingOptions(pitch=face, sheet="A4"), title=name)
    assert again.read_bytes() == svg.read_bytes()
    assert np.count_nonzero(grid) == int(name[:5])


def _gallery(browser, count):
    field = browser.find_element("id", "net-count")
    field.clear()
    field.send_keys(str(count))
    field = browser.find_element("id", "net-timeout")
    field.clear()
    field.send_keys("10")
    # 8.6 mm faces (legible marks), not the largest that fits: a net searched with room on the sheet,
    # whose edges can be cut and their faces hung elsewhere
    field = browser.find_element("id", "net-face")
    field.clear()
    field.send_keys("8.6")


def test_mark_an_edge_then_regenerate_honours_it(server, browser):
    import json

    from selenium.webdriver import ActionChains
    from selenium.webdriver.support.ui import Select

    from voxfab.unfold import Net

    open_page(browser, server)
    slim_column(browser)
    tab(browser, "net")
    _gallery(browser, 2)
    # A3: the column's nets at 8.6 mm keep room on the sheet once a cut edge re-hangs their faces
    Select(browser.find_element("id", "net-sheet")).select_by_value("A3")
    browser.find_element("id", "net-go").click()
    wait(browser, lambda d: len(d.find_elements("css selector", "#net-gallery figure")) == 2, timeout=90,
         what="two nets")
    browser.find_elements("css selector", "#net-gallery figure")[0].click()
    canvas = browser.find_element("id", "net-canvas")
    for dx, dy in ((0, 0), (7, 3), (-5, 9), (3, -11), (12, 12)):
        ActionChains(browser).move_to_element_with_offset(canvas, dx, dy).click().perform()
        # a click on an edge cuts it at once: the page asks the server (which a loaded machine may keep
        # waiting: the canvas says busy meanwhile) and ignores clicks until the answer; off an edge nothing
        # happens. A redraw of the view is no answer: wait for the marks themselves.
        end, quiet = time.monotonic() + 120, time.monotonic() + 2
        while time.monotonic() < end and not attr(browser, "marks-count", "data-constraints") \
                and not attr(browser, "net-canvas", "data-error") \
                and (attr(browser, "net-canvas", "data-busy") or time.monotonic() < quiet):
            time.sleep(0.05)
        if attr(browser, "marks-count", "data-constraints"):
            break
    marks = json.loads(attr(browser, "marks-count", "data-constraints"))
    # a page that took more than the quiet wait to see a click may have taken the next one too: every cut marked
    # must be honoured
    assert marks["cut"] and not marks["keep"]
    assert browser.find_element("id", "marks-count").text == f"{len(marks['cut'])} cut, 0 kept"
    browser.save_screenshot(str(SHOTS / "net-marked.png"))
    browser.find_element("id", "net-regen").click()
    wait(browser, lambda d: len(d.find_elements("css selector", "#net-gallery figure")) == 2
         and not d.find_element("id", "net-regen").get_attribute("disabled")
         and d.find_element("id", "net-chosen-label").text == "", timeout=90, what="the new gallery")
    browser.find_elements("css selector", "#net-gallery figure")[1].click()
    before = set(browser.downloads.glob("*.json"))
    tab(browser, "make")
    browser.find_element("css selector", '[data-make="net.json"]').click()
    js = wait(browser, lambda d: next(iter(set(d.downloads.glob("*.json")) - before), None), timeout=60,
              what="the net JSON")
    time.sleep(0.3)
    net = Net.from_json(js.read_text())
    names = {"+x": (1, 0, 0), "-x": (-1, 0, 0), "+y": (0, 1, 0), "-y": (0, -1, 0), "+z": (0, 0, 1), "-z": (0, 0, -1)}
    index = {(tuple(v), tuple(n)): i for i, (v, n) in enumerate(zip(net.voxel.tolist(), net.normal.tolist()))}
    folds = {tuple(sorted(p)) for p in net.folds.tolist()}
    for a, b in marks["cut"]:
        ia, ib = index[(tuple(a[:3]), names[a[3]])], index[(tuple(b[:3]), names[b[3]])]
        assert tuple(sorted((ia, ib))) not in folds  # the marked edge is cut in the new net


def test_tube_animation_eggs_by_clicking_and_a_bitmap_upload(server, browser, tmp_path):
    from PIL import Image, ImageDraw
    from selenium.webdriver import ActionChains
    from selenium.webdriver.support.ui import Select

    open_page(browser, server)
    # a bitmap curve of revolution, uploaded through the file input
    im = Image.new("L", (80, 80), 255)
    ImageDraw.Draw(im).rectangle((10, 10, 70, 70), fill=0)
    im.save(tmp_path / "square.png")
    before = attr(browser, "volume", "data-volume")
    browser.find_element("css selector", '#src-curve input[value="bitmap"]').click()
    browser.find_element("css selector", "#src-curve input.bitmap").send_keys(str(tmp_path / "square.png"))
    # (no shape while the bitmap is on its way: the empty choice is refused first)
    wait(browser, lambda d: attr(d, "volume", "data-volume") not in (before, "0"), what="the square section")
    assert attr(browser, "wf", "data-well-formed") == "true"
    # a tube: Frenet frames, then the rotating profile plays
    Select(browser.find_element("id", "maker")).select_by_value("tube")
    wait(browser, lambda d: attr(d, "volume", "data-volume") != before, what="the tube")
    Select(browser.find_element("id", "frame")).select_by_value("frenet")
    version = int(attr(browser, "viewer", "data-version"))
    browser.find_element("id", "play").click()
    wait(browser, lambda d: attr(d, "anim-status", "data-frames") == "24", timeout=60, what="24 frames")
    wait(browser, lambda d: int(attr(d, "viewer", "data-version")) > version + 5, what="the animation playing")
    browser.save_screenshot(str(SHOTS / "tube.png"))
    browser.find_element("id", "stop").click()
    # an egg: a third focus placed by clicking, and a weight changed
    Select(browser.find_element("id", "maker")).select_by_value("focal")
    wait(browser, lambda d: len(d.find_elements("css selector", "#foci-list .row")) == 2, what="the two foci")
    egg = int(wait(browser, lambda d: attr(d, "volume", "data-volume"), what="the egg"))
    canvas = browser.find_element("id", "foci-canvas")
    ActionChains(browser).move_to_element_with_offset(canvas, 40, 0).click().perform()
    wait(browser, lambda d: len(d.find_elements("css selector", "#foci-list .row")) == 3, what="a third focus")
    wait(browser, lambda d: int(attr(d, "volume", "data-volume")) != egg, what="the new egg")
    from selenium.webdriver.common.keys import Keys

    three = int(attr(browser, "volume", "data-volume"))
    weight = browser.find_elements("css selector", "#foci-list input.weight")[2]
    weight.send_keys(Keys.CONTROL, "a")
    weight.send_keys("3", Keys.TAB)  # the change event on leaving the field
    wait(browser, lambda d: int(attr(d, "volume", "data-volume")) != three, what="the heavier focus")
    assert browser.find_elements("css selector", "#foci-list input.weight")[2].get_attribute("value") == "3"
    browser.save_screenshot(str(SHOTS / "egg.png"))


def test_polyline_closed_curve_of_revolution(server, browser):
    from selenium.webdriver import ActionChains
    from selenium.webdriver.support.ui import Select

    open_page(browser, server)
    before = attr(browser, "volume", "data-volume")
    previews = int(attr(browser, "latency", "data-count"))
    browser.find_element("css selector", '#src-curve input[value="drawn"]').click()
    Select(browser.find_element("css selector", "#src-curve select.tool")).select_by_value("polyline")
    browser.find_element("css selector", "#src-curve input.closed").click()
    canvas = browser.find_element("css selector", "#src-curve canvas")
    for x, y in ((-80, -80), (80, -80), (80, 80), (-80, 80)):  # a square, one click per corner
        ActionChains(browser).move_to_element_with_offset(canvas, x, y).click().perform()
    browser.find_element("css selector", "#src-curve button.finish").click()
    wait(browser, lambda d: int(attr(d, "latency", "data-count")) > previews
         and attr(d, "volume", "data-volume") != before, what="the square curve of revolution")
    # a square section: the top layer is a filled square of the widest slice's side
    assert attr(browser, "wf", "data-well-formed") == "true"
    browser.save_screenshot(str(SHOTS / "polyline.png"))


def test_interlocked_plates_from_the_make_tab_show_their_assembly(server, browser):
    import zipfile

    from selenium.webdriver.support.ui import Select

    open_page(browser, server)
    tab(browser, "make")
    Select(browser.find_element("id", "plate-style")).select_by_value("interlocked")
    version = int(attr(browser, "viewer", "data-version"))
    browser.find_element("css selector", '[data-make="plates.zip"]').click()
    plates = wait(browser, lambda d: int(attr(d, "viewer", "data-version")) > version
                  and int(attr(d, "viewer", "data-plates") or 0), timeout=90, what="the assembled plates")
    browser.save_screenshot(str(SHOTS / "plates-interlocked.png"))
    archive = wait(browser, lambda d: next(iter(sorted(d.downloads.glob("*-plates.zip"))), None), timeout=60,
                   what="the downloaded plates")
    time.sleep(0.3)
    import json

    # named after the shape inside the zip too: NAME-plates.zip holds NAME-plates-plates.json
    report = json.loads(zipfile.ZipFile(archive).read(f"{archive.stem}-plates.json"))
    assert report["style"] == "interlocked" and report["plates"] == plates >= 2
    # Back to the shape: the viewer draws voxels again.
    browser.find_element("id", "show-shape").click()
    wait(browser, lambda d: int(attr(d, "viewer", "data-faces")) > 0 and int(attr(d, "viewer", "data-version"))
         > version + 1, what="the shape again")
