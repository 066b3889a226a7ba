"""The index of a batch: thumbnails per shape, ``index.html`` and PNG contact sheets."""

from __future__ import annotations

import html
import json
import math
from collections.abc import Sequence
from pathlib import Path

from voxfab._shared.typing import BoolGrid

__all__ = ["draw_thumbnails", "write_index", "SHEET_SHAPES", "INDEX_NAME", "THUMBS"]

INDEX_NAME = "index.html"
#: Folder of the thumbnails, beside the index page.
THUMBS = "thumbs"
#: Shapes per contact sheet; a bigger batch gets ``contact_sheet_2.png`` and so on.
SHEET_SHAPES = 400


def draw_thumbnails(grid: BoolGrid, folder: Path, thumbs: Path, *, name: str, seed: int, size: int) -> list[str]:
    """Write ``thumbs/<name>.png`` (isometric render) and ``thumbs/<name>-net.png``.

    The net is the batch's own (``folder/net.json``) when the outputs include a net,
    else the pictures pipeline's net for the recipe's seed (the triptych's).  Returns
    notes (why a net is missing).
    """
    from voxfab.render import make_net, net_picture, render, save_picture
    from voxfab.unfold import Net

    thumbs.mkdir(parents=True, exist_ok=True)
    save_picture(render(grid, view="iso", size=size), thumbs / f"{name}.png")
    built = folder / "net.json"
    try:
        if built.is_file():
            net = Net.from_json(built.read_text())
        else:
            net = make_net(grid, rng=seed)
        picture = net_picture(net, grid, size=size, legend=False, numbers=False)
    except Exception as exc:  # noqa: BLE001 - a missing thumbnail must not fail a built shape
        return [f"no net thumbnail: {' '.join(str(exc).split())}"]
    save_picture(picture, thumbs / f"{name}-net.png")
    return []


def _sheet(names: Sequence[str], thumbs: Path, tile: int) -> object:
    """Render and net thumbnails side by side, two tiles per shape, each pair over its name."""
    from PIL import Image, ImageDraw

    from voxfab.render import sheet_layout
    from voxfab.render._image import font

    pairs = max(1, math.ceil(math.sqrt(len(names))))
    lay = sheet_layout(2 * len(names), tile=tile, columns=2 * pairs)
    sheet = Image.new("RGB", (lay.width, lay.height), "white")
    for i, name in enumerate(names):
        for j, suffix in enumerate(("", "-net")):
            path = thumbs / f"{name}{suffix}.png"
            if path.is_file():
                with Image.open(path) as im:
                    sheet.paste(im.convert("RGB").resize((tile, tile)), lay.origins[2 * i + j])
    draw = ImageDraw.Draw(sheet)
    fnt = font(int(lay.label_height * 0.7))
    for i, name in enumerate(names):
        x0, y0 = lay.origins[2 * i]
        draw.text((x0 + tile, y0 + tile + lay.label_height / 2), name, fill=(30, 30, 30), font=fnt, anchor="mm")
    return sheet


def _files(folder: Path) -> list[str]:
    try:
        manifest = json.loads((folder / "manifest.json").read_text())
    except (OSError, ValueError):
        return []
    return sorted(["manifest.json"] + [f["path"] for f in manifest.get("files", [])])


def write_index(outdir: Path, shapes: dict[str, dict[str, object]], *, tile: int = 160) -> list[Path]:
    """Write ``DIR/index.html`` and the contact sheets from the batch's outcomes.

    Parameters
    ----------
    outdir : Path
        The batch folder.
    shapes : dict
        ``batch.json``'s ``shapes``: name → outcome (``status``, ``error``, ...).

    Returns
    -------
    list of Path
        The files written (the page first).
    """
    from voxfab._shared.atomic import write_text
    from voxfab.render import save_picture

    thumbs = outdir / THUMBS
    names = sorted(shapes)
    built = [n for n in names if shapes[n].get("status") == "built"]
    sheets = []
    for k in range(0, len(built), SHEET_SHAPES):
        path = outdir / ("contact_sheet.png" if k == 0 else f"contact_sheet_{k // SHEET_SHAPES + 1}.png")
        save_picture(_sheet(built[k : k + SHEET_SHAPES], thumbs, tile), path)  # type: ignore[arg-type]
        sheets.append(path)
    failed = [n for n in names if shapes[n].get("status") == "failed"]
    cards = []
    for name in built:
        q = html.escape(name, quote=True)
        links = " ".join(
            f'<a href="{q}/{html.escape(f, quote=True)}">{html.escape(f)}</a>' for f in _files(outdir / name)
        )
        imgs = "".join(
            f'<img src="{THUMBS}/{q}{suffix}.png" alt="{q} {what}" width="{tile}" height="{tile}" loading="lazy">'
            for suffix, what in (("", "render"), ("-net", "net"))
            if (thumbs / f"{name}{suffix}.png").is_file()
        )
        cards.append(f'<figure id="{q}"><a href="{q}/">{imgs}</a><figcaption><b>{q}</b><br>{links}'
                     "</figcaption></figure>")
    rows = "".join(
        f"<li><b>{html.escape(n)}</b>: {html.escape(str(shapes[n].get('error', '')))}</li>" for n in failed
    )
    sheet_links = " ".join(f'<a href="{p.name}">{p.name}</a>' for p in sheets)
    page = (
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>voxfab batch</title>\n"
        "<style>body{font-family:sans-serif;margin:1em}figure{display:inline-block;vertical-align:top;"
        "margin:.4em;width:" + str(2 * tile + 8) + "px}figcaption{font-size:80%;word-wrap:break-word}"
        "a{margin-right:.4em}</style></head><body>\n"
        f"<h1>voxfab batch: {len(built)} shapes built, {len(failed)} failed</h1>\n"
        f"<p>Contact sheets: {sheet_links or '(none)'}. Outcomes: <a href=\"batch.json\">batch.json</a>.</p>\n"
        + "\n".join(cards)
        + (f"\n<h2>Failed</h2><ul>{rows}</ul>" if failed else "")
        + "\n</body></html>\n"
    )
    index = outdir / INDEX_NAME
    write_text(index, page)
    return [index, *sheets]

