"""The index of a batch: thumbnails per shape, ``index.html`` and PNG contact sheets."""

from __future__ import annotations

import dataclasses
import html
import json
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from voxfab._shared.typing import BoolGrid

if TYPE_CHECKING:
    from voxfab.shape import VoxelShape

__all__ = ["draw_thumbnails", "hunt_summary", "write_index", "HuntSummary", "SHEET_SHAPES", "INDEX_NAME", "THUMBS"]

INDEX_NAME = "index.html"
#: Folder of the thumbnails, beside the index page.
THUMBS = "thumbs"
#: Shapes per contact sheet; a bigger batch gets ``contact_sheet_2.png`` and so on.
SHEET_SHAPES = 400


def draw_thumbnails(grid: BoolGrid | VoxelShape, gives: Mapping[str, Any], thumbs: Path, *, name: str, seed: int,
                    size: int) -> list[str]:
    """Write ``thumbs/<name>.png`` (isometric render) and ``thumbs/<name>-net.png``, in colour for a coloured shape.

    The net is what the build's outputs gave (``gives``, :attr:`voxfab.recipe.BuiltRecipe.gives`):
    the net output's net when it is in one piece, else the hunt's zipper net, else its
    one-piece net; else the pictures pipeline's net for the recipe's seed (the
    triptych's).  Returns notes (why a net is missing).
    """
    from voxfab.render import make_net, net_picture, render, save_picture

    thumbs.mkdir(parents=True, exist_ok=True)
    save_picture(render(grid, view="iso", size=size), thumbs / f"{name}.png")
    pieces = gives.get("net") or ()
    built = [pieces[0] if len(pieces) == 1 else None, gives.get("zipper_net"), gives.get("hunt_net")]
    try:
        net = next((n for n in built if n is not None), None)
        if net is None:
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


@dataclasses.dataclass(frozen=True)
class HuntSummary:
    """The hunt's outcomes over a batch: shape names by outcome (see :data:`voxfab.unfold.HUNT_NET`).

    Attributes
    ----------
    net : dict
        ``random``, ``exact``, ``none``, ``undecided`` → names: a one-piece net found by
        the random engine, found only by the exact strategy, proved not to exist, or undecided.
    zipper : dict
        ``found``, ``none``, ``undecided``, ``skipped`` → names.
    """

    net: dict[str, list[str]]
    zipper: dict[str, list[str]]

    @property
    def shapes(self) -> int:
        """Shapes hunted."""
        return sum(len(v) for v in self.net.values())

    def counts(self) -> dict[str, dict[str, int]]:
        """How many shapes each outcome has."""
        return {"net": {k: len(v) for k, v in self.net.items()}, "zipper": {k: len(v) for k, v in self.zipper.items()}}


def hunt_summary(outdir: Path, names: Sequence[str]) -> HuntSummary:
    """Read ``DIR/<name>/hunt.json`` of each of ``names`` (those without one are left out) and sort them by outcome."""
    from voxfab.fabricate.hunt import read_hunt
    from voxfab.unfold import HUNT_NET, HUNT_ZIPPER

    net: dict[str, list[str]] = {k: [] for k in HUNT_NET}
    zipper: dict[str, list[str]] = {k: [] for k in HUNT_ZIPPER}
    for name in names:
        data = read_hunt(outdir / name / "hunt.json")
        if data is None or data.get("net") not in net or data.get("zipper") not in zipper:
            continue
        net[data["net"]].append(name)
        zipper[data["zipper"]].append(name)
    return HuntSummary(net, zipper)


#: What each hunt outcome means on the index page.
_HUNT_WORDS = {
    ("net", "random"): "one-piece net found by the random engine",
    ("net", "exact"): "one-piece net found only by the exact strategy",
    ("net", "none"): "no one-piece net (proved)",
    ("net", "undecided"): "one-piece net undecided",
    ("zipper", "found"): "zipper net found",
    ("zipper", "none"): "no zipper net (proved)",
    ("zipper", "undecided"): "zipper net undecided",
    ("zipper", "skipped"): "zipper net not looked for",
}
#: Outcomes whose shapes the page lists by name (the rest are the common case).
_HUNT_LISTED = (("net", "exact"), ("net", "none"), ("net", "undecided"), ("zipper", "none"), ("zipper", "undecided"))


def _hunt_section(summary: HuntSummary) -> str:
    def link(n: str) -> str:
        q = html.escape(n, quote=True)
        return f'<a href="#{q}">{q}</a>'

    groups: dict[str, Any] = {"net": summary.net, "zipper": summary.zipper}
    rows = "".join(f'<tr><td>{_HUNT_WORDS[(g, k)]}</td><td class="n" id="hunt-{g}-{k}">{len(v)}</td></tr>'
                   for g in ("net", "zipper") for k, v in groups[g].items())
    lists = "".join(f"<h3>{_HUNT_WORDS[(g, k)]} ({len(groups[g][k])})</h3><p>"
                    + " ".join(link(n) for n in groups[g][k]) + "</p>"
                    for g, k in _HUNT_LISTED if groups[g][k])
    return (f"<h2>Hunt: {summary.shapes} shapes</h2>\n<table>{rows}</table>\n{lists}\n")


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
    summary = hunt_summary(outdir, built)
    hunted = {n: f"net: {k}" for k, v in summary.net.items() for n in v}
    for k, v in summary.zipper.items():
        for n in v:
            hunted[n] += f", zipper: {k}"
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
        said = f"<br>{hunted[name]}" if name in hunted else ""
        cards.append(f'<figure id="{q}"><a href="{q}/">{imgs}</a><figcaption><b>{q}</b>{said}<br>{links}'
                     "</figcaption></figure>")
    rows = "".join(
        f"<li><b>{html.escape(n)}</b>: {html.escape(str(shapes[n].get('error', '')))}</li>" for n in failed
    )
    sheet_links = " ".join(f'<a href="{p.name}">{p.name}</a>' for p in sheets)
    hunt = _hunt_section(summary) if summary.shapes else ""
    page = (
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>voxfab batch</title>\n"
        "<style>body{font-family:sans-serif;margin:1em}figure{display:inline-block;vertical-align:top;"
        "margin:.4em;width:" + str(2 * tile + 8) + "px}figcaption{font-size:80%;word-wrap:break-word}"
        "a{margin-right:.4em}td.n{text-align:right;padding-left:1em}</style></head><body>\n"
        f"<h1>voxfab batch: {len(built)} shapes built, {len(failed)} failed</h1>\n"
        f"<p>Contact sheets: {sheet_links or '(none)'}. Outcomes: <a href=\"batch.json\">batch.json</a>.</p>\n"
        + hunt
        + "\n".join(cards)
        + (f"\n<h2>Failed</h2><ul>{rows}</ul>" if failed else "")
        + "\n</body></html>\n"
    )
    index = outdir / INDEX_NAME
    write_text(index, page)
    return [index, *sheets]

