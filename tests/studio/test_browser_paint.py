"""Painting in the studio, in headless Chromium: the coloured character opened from its .vox, painted by voxel,
face region and fill, its colour picked, a stroke undone, and the .vox downloaded and read independently;
the net editor, the gallery and the 3D views in the shape's colours.

Clicks land where the page's own 3D view draws the face asked for (checked by its picker), and
what the page did is checked against colours worked out here from the character's own grid.
"""

from __future__ import annotations

import sys
import time
from collections import deque
from pathlib import Path

import numpy as np
import pytest

from voxfab import io as vio
from voxfab.shape import VoxelShape

from ._helpers import SHOTS, small_shape
from .test_browser import open_page, tab, wait

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _voxart import CHARACTER_COLOURS, character, read_vox_independently  # noqa: E402

pytestmark = pytest.mark.slow

GREEN, BLUE, YELLOW = (0, 255, 0, 255), (0, 0, 255, 255), (255, 255, 0, 255)
MINUS_Y = "-y"


def hexa(rgba) -> str:
    return "#{:02x}{:02x}{:02x}".format(*rgba[:3])


def open_file(browser, path: Path) -> None:
    """Open a shape file through the Keep tab's file field, as the artist does."""
    tab(browser, "keep")
    browser.find_element("css selector", '[data-testid="open-file"]').send_keys(str(path))
    wait(browser, lambda d: d.find_element("id", "shape-name").text == path.name, what=f"{path.name} opened")


def page_origin(browser) -> np.ndarray:
    """The smallest x, y, z of the page's filled voxels (the page centres a shape in its 25³ grid)."""
    return np.array(browser.execute_script("""
        const g = window.voxfabPaint.grid, lo = [1e9, 1e9, 1e9];
        for (let x = 0; x < g.nx; x++) for (let y = 0; y < g.ny; y++) for (let z = 0; z < g.nz; z++)
          if (g.get(x, y, z)) { lo[0] = Math.min(lo[0], x); lo[1] = Math.min(lo[1], y); lo[2] = Math.min(lo[2], z); }
        return lo;"""))


def click_face(browser, voxel, side: str) -> None:
    """Click the 3D view where it draws the ``side`` face of page voxel ``voxel`` (its picker agrees)."""
    from selenium.webdriver.common.action_chains import ActionChains

    name = ",".join(map(str, voxel)) + "," + side
    at = browser.execute_script("""
        const v = window.voxfabPaint.viewer, name = arguments[0];
        const poly = v._polys.find((p) => p.name === name);
        if (!poly) return null;
        const r = v.canvas.getBoundingClientRect(), [a, b, c, d] = poly.pts;
        for (const [s, t] of [[.5, .5], [.35, .35], [.65, .65], [.35, .65], [.65, .35]]) {
          const x = (1 - s) * (1 - t) * a[0] + s * (1 - t) * b[0] + s * t * c[0] + (1 - s) * t * d[0];
          const y = (1 - s) * (1 - t) * a[1] + s * (1 - t) * b[1] + s * t * c[1] + (1 - s) * t * d[1];
          const hit = v.pick(x, y);
          if (hit && hit.face === name) return [r.left + x * r.width / v.canvas.width, r.top + y * r.height / v.canvas.height];
        }
        return null;""", name)
    assert at is not None, f"the 3D view shows no face {name}"
    actions = ActionChains(browser)
    actions.w3c_actions.pointer_action.move_to_location(int(round(at[0])), int(round(at[1])))
    actions.w3c_actions.pointer_action.click()
    actions.perform()


def choose_tool(browser, tool: str) -> None:
    browser.find_element("css selector", f'[data-testid="tool-{tool}"]').click()
    wait(browser, lambda d: d.find_element("tag name", "body").get_attribute("data-paint-tool") == tool, what=tool)


def choose_colour(browser, rgba) -> None:
    """Click MagicaVoxel's swatch of that colour."""
    browser.find_element("css selector", f'#paint-defaults [data-colour="{hexa(rgba)}"]').click()
    wait(browser, lambda d: d.find_element("id", "paint-current").get_attribute("data-colour") == hexa(rgba),
         what=f"current colour {hexa(rgba)}")


def undo_steps(browser) -> int:
    return browser.execute_script("return window.voxfabPaint.editor.undoStack.length;")


def plane_region(rgba: np.ndarray, grid: np.ndarray, start: tuple[int, int, int]) -> set[tuple[int, int, int]]:
    """The voxels whose -y face is on ``start``'s plane, exposed, of its colour and joined to it edge to edge."""
    y = start[1]
    want = tuple(rgba[start])

    def face(x: int, z: int) -> bool:
        inside = 0 <= x < grid.shape[0] and 0 <= z < grid.shape[2]
        return inside and grid[x, y, z] and (y == 0 or not grid[x, y - 1, z]) and tuple(rgba[x, y, z]) == want

    seen, todo = {(start[0], start[2])}, deque([(start[0], start[2])])
    while todo:
        x, z = todo.popleft()
        for nx, nz in ((x + 1, z), (x - 1, z), (x, z + 1), (x, z - 1)):
            if (nx, nz) not in seen and face(nx, nz):
                seen.add((nx, nz))
                todo.append((nx, nz))
    return {(x, y, z) for x, z in seen}


def test_paint_a_voxel_a_face_region_and_a_fill_pick_a_colour_undo_and_download_the_vox(server, browser, tmp_path):
    hero = character()
    vio.write(hero, tmp_path / "character.vox")
    open_page(browser, server)
    open_file(browser, tmp_path / "character.vox")
    assert browser.execute_script("return window.voxfabPaint.grid.colours !== null;")
    shift = page_origin(browser) - np.argwhere(hero.grid).min(axis=0)  # character -> page coordinates
    tab(browser, "edit")
    wait(browser, lambda d: d.find_element("id", "paint-own").get_attribute("data-count") == "12", what="12 colours")

    def page(v) -> list[int]:
        return [int(c) for c in np.add(v, shift)]

    expected = hero.colours.rgba.copy()
    steps = undo_steps(browser)

    # one voxel: a shirt voxel on the front, seen through its -y face
    one = (14, 7, 10)
    choose_colour(browser, GREEN)
    choose_tool(browser, "voxel")
    click_face(browser, page(one), MINUS_Y)
    wait(browser, lambda d: undo_steps(d) == steps + 1, what="the voxel stroke's undo step")
    expected[one] = GREEN

    # a face region: the shirt's front around the green voxel, the buttons and the green voxel left out
    region = plane_region(expected, hero.grid, (5, 7, 10))
    assert one not in region and len(region) == 12 * 6 - 4 - 1  # the front, less the buttons and the green voxel
    choose_colour(browser, BLUE)
    choose_tool(browser, "face")
    click_face(browser, page((5, 7, 10)), MINUS_Y)
    wait(browser, lambda d: undo_steps(d) == steps + 2, what="the face region's undo step")
    for v in region:
        expected[v] = BLUE

    # a fill of the trousers, connected: both legs and the crotch (then undone)
    choose_colour(browser, YELLOW)
    choose_tool(browser, "fill")
    assert browser.find_element("id", "fill-scope").get_attribute("value") == "connected"
    click_face(browser, page((6, 8, 2)), MINUS_Y)
    wait(browser, lambda d: undo_steps(d) == steps + 3, what="the fill's undo step")
    said = browser.find_element("id", "message").text
    assert f"Painted {int(np.all(hero.colours.rgba == CHARACTER_COLOURS['trousers'], axis=-1).sum())} voxels" in said
    assert "fill of the voxels of that colour touching it" in said
    trousers = np.all(hero.colours.rgba == CHARACTER_COLOURS["trousers"], axis=-1)
    painted = browser.execute_script("""
        const g = window.voxfabPaint.grid, out = [];
        for (let i = 0; i < g.data.length; i++) if (g.data[i] && g.palette[4 * g.colours[i] + 2] === 0
            && g.palette[4 * g.colours[i]] === 255 && g.palette[4 * g.colours[i] + 1] === 255) out.push(i);
        return out.length;""")
    assert painted == int(trousers.sum())

    # the eyedropper: the hair's colour becomes the current colour, no undo step
    choose_tool(browser, "pick")
    click_face(browser, page((9, 9, 18)), "+z")
    hair = hexa(CHARACTER_COLOURS["hair"])
    wait(browser, lambda d: d.find_element("id", "paint-current").get_attribute("data-colour") == hair, what="hair")
    assert undo_steps(browser) == steps + 3
    browser.save_screenshot(str(SHOTS / "paint-character.png"))

    # Undo takes the fill back, one stroke, and nothing else
    browser.find_element("id", "undo").click()
    wait(browser, lambda d: undo_steps(d) == steps + 2, what="one undo step")

    tab(browser, "keep")
    target = browser.downloads / "character.vox"
    target.unlink(missing_ok=True)
    browser.find_element("css selector", '[data-testid="save-vox"]').click()
    wait(browser, lambda d: target.exists() and target.stat().st_size > 0, what="the .vox download")
    time.sleep(0.3)
    size, voxels = read_vox_independently(target)
    lo = np.argwhere(hero.grid).min(axis=0)
    want = {tuple(int(c) for c in p - lo): tuple(int(c) for c in expected[tuple(p)]) for p in np.argwhere(hero.grid)}
    assert size == tuple(int(s) for s in np.ptp(np.argwhere(hero.grid), axis=0) + 1)
    assert voxels == want
    assert sum(1 for c in voxels.values() if c == BLUE) == len(region)
    assert sum(1 for c in voxels.values() if c == CHARACTER_COLOURS["trousers"]) == int(trousers.sum())

    # a voxel added by hand on the layer takes the current colour (the hair's, picked above)
    tab(browser, "edit")
    added = browser.execute_script("""
        const e = window.voxfabPaint.editor, g = e.grid, c = e.canvas, r = c.getBoundingClientRect();
        for (let x = 0; x < g.nx; x++) for (let y = 0; y < g.ny; y++) if (!g.get(x, y, e.layer))
          return [x, y, e.layer, r.left + (x + 0.5) * r.width / g.nx, r.top + (g.ny - y - 0.5) * r.height / g.ny];
        return null;""")
    steps = undo_steps(browser)
    from selenium.webdriver.common.action_chains import ActionChains

    actions = ActionChains(browser)
    actions.w3c_actions.pointer_action.move_to_location(int(added[3]), int(added[4]))
    actions.w3c_actions.pointer_action.click()
    actions.perform()
    wait(browser, lambda d: undo_steps(d) == steps + 1, what="the added voxel")
    rgba = browser.execute_script("return window.voxfabPaint.grid.rgba(...arguments);", *added[:3])
    assert tuple(rgba) == CHARACTER_COLOURS["hair"]
    browser.find_element("id", "undo").click()

    # Join parts: the four parts joined by their voxels, listed, as one undo step
    steps = undo_steps(browser)
    volume = int(browser.find_element("id", "volume").get_attribute("data-volume"))
    browser.find_element("css selector", '[data-testid="join-parts"]').click()
    wait(browser, lambda d: d.find_element("id", "join-result").get_attribute("data-joins") == "4", what="4 joins")
    wait(browser, lambda d: int(d.find_element("id", "volume").get_attribute("data-volume")) == volume + 6,
         what="the 6 voxels added")
    assert undo_steps(browser) == steps + 1 and browser.find_element("id", "wf").text == "not well formed"
    assert "separate pieces" not in browser.find_element("id", "reasons").text
    assert all("joined the part of" in li.text for li in browser.find_elements("css selector", "#join-result li"))
    browser.find_element("id", "undo").click()
    wait(browser, lambda d: int(d.find_element("id", "volume").get_attribute("data-volume")) == volume,
         what="the join undone")


def test_a_256th_colour_is_refused_in_plain_words(server, browser, tmp_path):
    open_page(browser, server)
    vio.write(character(), tmp_path / "character.vox")
    open_file(browser, tmp_path / "character.vox")
    tab(browser, "edit")
    # 255 voxels of the character each in a colour of its own: the palette is full
    refused = browser.execute_script("""
        const p = window.voxfabPaint, g = p.grid;
        let k = 0;
        for (let i = 0; i < g.data.length && k < 255; i++) if (g.data[i]) {
          k++; g.colours[i] = k; g.palette.set([k, 7, 7, 255], 4 * k);
        }
        for (let i = 0; i < g.data.length; i++) if (g.data[i] && !g.colours[i]) g.colours[i] = 1;
        const before = p.current.slice();
        return [p.choose([1, 2, 3, 255]), p.current, before, p.choose([9, 7, 7, 255])];""")
    assert refused[0] is False and refused[1] == refused[2] and refused[3] is True
    assert "already uses 255 colours" in browser.find_element("id", "message").text


def _two_colour_column(tmp_path: Path) -> Path:
    """The column of small_shape(): red below z = 12, blue from it, as a .vox."""
    grid = small_shape()
    z = np.arange(25)[None, None, :]
    shape = VoxelShape(grid).painted((220, 30, 30, 255), grid & (z < 12)).painted((30, 60, 220, 255), grid & (z >= 12))
    vio.write(shape, tmp_path / "column.vox")
    return tmp_path / "column.vox"


def test_the_net_editor_gallery_and_3d_views_show_the_faces_colours(server, browser, tmp_path):
    open_page(browser, server)
    open_file(browser, _two_colour_column(tmp_path))
    # each face the 3D view shows whole at its centre, and the pixel there
    visible_face_pixels = """
        const v = window.voxfabPaint.viewer, ctx = v.canvas.getContext('2d'), out = [];
        for (const p of v._polys) {
          const x = p.pts.reduce((a, q) => a + q[0], 0) / 4, y = p.pts.reduce((a, q) => a + q[1], 0) / 4;
          const hit = v.pick(x, y);
          if (!hit || hit.face !== p.name) continue;
          out.push([p.name, Array.from(ctx.getImageData(Math.round(x), Math.round(y), 1, 1).data)]);
        }
        return out;"""
    red_or_blue = """
        const [r, g, b] = arguments[0];
        return r > 1.8 * Math.max(g, b) ? 'red' : b > 1.8 * Math.max(r, g) ? 'blue' : 'other';"""

    # the shape in the 3D view: each visible face in its voxel's colour, times its shade
    faces = browser.execute_script(visible_face_pixels)
    assert len(faces) > 50
    for name, px in faces:
        z = int(name.split(",")[2])
        kind = browser.execute_script(red_or_blue, px)
        assert kind == ("red" if z < 12 else "blue"), (name, px)

    # a gallery of one net: the thumbnail, the net editor's faces and the fold-up in the faces' colours
    tab(browser, "net")
    count = browser.find_element("id", "net-count")
    count.clear()
    count.send_keys("1")
    browser.find_element("css selector", '[data-testid="net-generate"]').click()
    figure = wait(browser, lambda d: d.find_element("css selector", '[data-testid="net-gallery-item"]'), timeout=120,
                  what="the first net")
    thumb = browser.execute_script("""
        const c = arguments[0].querySelector('canvas'), d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let red = 0, blue = 0;
        for (let i = 0; i < d.length; i += 4) {
          if (d[i] === 220 && d[i + 1] === 30 && d[i + 2] === 30) red++;
          if (d[i] === 30 && d[i + 1] === 60 && d[i + 2] === 220) blue++;
        }
        return [red, blue];""", figure)
    assert thumb[0] > 100 and thumb[1] > 100
    figure.click()
    wait(browser, lambda d: d.execute_script("return window.voxfabNetView.layout !== null;"), what="the chosen net")
    sampled = browser.execute_script("""
        const nv = window.voxfabNetView, L = nv.layout, ctx = nv.canvas.getContext('2d'), out = [];
        nv.setHover(null, false);
        for (let i = 0; i < L.faces.length; i++) {
          let x = 0, y = 0;
          for (let k = 0; k < 4; k++) { x += nv.pts[8 * i + 2 * k] / 4; y += nv.pts[8 * i + 2 * k + 1] / 4; }
          const [px, py] = nv.toScreen(x, y);
          if (px < 0 || py < 0 || px >= nv.canvas.width || py >= nv.canvas.height) continue;
          out.push([L.faces[i], Array.from(ctx.getImageData(Math.round(px), Math.round(py), 1, 1).data)]);
        }
        return out;""")
    assert len(sampled) > 100
    for face, px in sampled:
        assert tuple(px[:3]) == ((220, 30, 30) if face[2] < 12 else (30, 60, 220)), (face, px)

    # folded up in the 3D view: the outside of each face in its colour times its shade
    browser.execute_script("window.voxfabNetView.fold(1);")
    folded = browser.execute_script(visible_face_pixels)
    assert len(folded) > 50
    for name, px in folded:
        assert browser.execute_script(red_or_blue, px) == ("red" if int(name.split(",")[2]) < 12 else "blue"), (name, px)
    browser.save_screenshot(str(SHOTS / "paint-net.png"))


def test_a_painted_drawing_keeps_its_colours_when_the_drawing_grows(server, browser):
    from .test_browser import set_expression, slim_column

    open_page(browser, server)
    slim_column(browser)
    before = int(browser.find_element("id", "volume").get_attribute("data-volume"))
    tab(browser, "edit")
    choose_colour(browser, GREEN)
    choose_tool(browser, "fill")
    browser.find_element("css selector", '#fill-scope option[value="all"]').click()
    face = browser.execute_script("""
        const v = window.voxfabPaint.viewer;
        for (let t = v._polys.length - 1; t >= 0; t--) {
          const p = v._polys[t], x = p.pts.reduce((a, q) => a + q[0], 0) / 4, y = p.pts.reduce((a, q) => a + q[1], 0) / 4;
          const hit = v.pick(x, y);
          if (hit && hit.face === p.name) return p.name.split(',');
        }
        return null;""")
    click_face(browser, [int(c) for c in face[:3]], face[3])
    everywhere = """
        const g = window.voxfabPaint.grid;
        if (!g.colours) return false;
        for (let i = 0; i < g.data.length; i++)
          if (g.data[i] && (!g.colours[i] || g.palette[4 * g.colours[i] + 1] !== 255 || g.palette[4 * g.colours[i]] !== 0)) return false;
        return g.count();"""
    wait(browser, lambda d: d.execute_script(everywhere) == before, what="the whole column painted green")
    # a wider column: the painted voxels stay green, and the drawing's new ones take their nearest's green
    tab(browser, "draw")
    set_expression(browser, "src-generatrix", "x = 0.3")
    wait(browser, lambda d: (d.execute_script(everywhere) or 0) > before, what="the wider column, all green")
