"""``census.html``: the census table per n, with pictures of the polycubes it names.

The page is one self-contained file: the table of ``census.json``'s rows, the
polycubes without an unzipping (each with its proof), those left undecided and
those outside the paper's model (touchings, handles), each drawn as an
isometric picture, and for each n the unzipping net of its first polycube with
the cut path in red.  Pictures are drawing pages (:mod:`voxfab.drawing`, the
model of every picture of the project) written inline by its SVG backend, so the
page needs no other file.
"""

from __future__ import annotations

import html
import json
from pathlib import Path
from typing import Any

__all__ = ["cubes_page", "cubes_svg", "net_page", "net_svg", "write_page"]

#: Pictures drawn per list on the page (the lists themselves are complete in census.json).
_PICTURES = 24
#: Millimetres per CSS pixel: a drawing's page is in mm, the census page lays pictures out in pixels.
_MM = 25.4 / 96
#: The page's pictures are for people: the layers' colours, with widths seen at a thumbnail's size.
_STYLES = {"LABEL": ("#222233", 0.2), "GRID": ("#99aaaa", 0.15), "CUT": ("#cc0000", 0.45)}


def _svg(page: Any) -> str:
    """A drawing page as inline SVG (no XML declaration inside HTML), in the census page's line styles."""
    from voxfab.drawing import LAYERS, LayerStyle, Lines, LineStyle
    from voxfab.drawing.svg import page_svg

    styles = {**LAYERS, **{k: LayerStyle(c, LineStyle.SOLID, w) for k, (c, w) in _STYLES.items()}}
    text = page_svg(page, styles=styles, lines=Lines.PREVIEW)
    return text[text.index("<svg"):].strip()


def _fit(rings: list[Any], size: float) -> tuple[Any, float, float]:
    """Scale and shift that fit points into a square of ``size`` mm with a margin; the page's width and height."""
    import numpy as np

    pts = np.concatenate(rings)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    span = hi - lo
    margin = 4 * _MM
    s = (size - 2 * margin) / max(float(span.max()), 1.0)
    return (lambda p: (np.asarray(p, dtype=float) - lo) * s + margin), float(span[0] * s + 2 * margin), \
        float(span[1] * s + 2 * margin)


def cubes_page(cells: list[list[int]], size: int = 120) -> Any:
    """An isometric picture of unit cubes as a drawing page: visible faces filled back to front, shaded by
    direction, outlined; ``size`` pixels square at most."""
    import numpy as np

    from voxfab.drawing import Fill, Page, Polylines

    filled = {tuple(c) for c in cells}

    # Page position of a lattice point, looking from (+1, +1, +1) with z up (the page's y is up).
    def at(x: float, y: float, z: float) -> tuple[float, float]:
        return ((x - y) * 0.866, z - (x + y) * 0.5)

    faces = []
    for x, y, z in filled:
        for d, shade, quad in (
            ((1, 0, 0), "#8fa8c8", ((1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1))),
            ((0, 1, 0), "#6d88ad", ((0, 1, 0), (1, 1, 0), (1, 1, 1), (0, 1, 1))),
            ((0, 0, 1), "#c9d7ea", ((0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1))),
        ):
            if (x + d[0], y + d[1], z + d[2]) in filled:
                continue
            faces.append((x + y + z + sum(d) * 0.5, shade, np.array([at(x + a, y + b, z + c) for a, b, c in quad])))
    faces.sort(key=lambda f: (f[0], f[1], f[2].tolist()))
    place, w, h = _fit([f[2] for f in faces], size * _MM)
    rings = [place(f[2]) for f in faces]
    fills = tuple(Fill(Polylines.from_list([r], [True]), shade) for r, (_, shade, _) in zip(rings, faces))
    # Each face's outline after its fill: a nearer face hides the outlines behind it only where it is filled.
    return Page(w, h, {"LABEL": Polylines.from_list(rings, [True] * len(rings))}, fills=fills)


def net_page(net: dict[str, Any], size: int = 160) -> Any:
    """A ``voxfab-net/1`` net as a drawing page: squares filled grey, folds thin (GRID), cut edges red (CUT).

    An edge is cut when no fold joins the two squares it bounds in 3D; for an unzipping these are its cut path.
    """
    import numpy as np

    from voxfab.drawing import Fill, Page, Polylines

    faces = net["faces"]
    folds = {tuple(sorted(p)) for p in net["folds"]}
    place, w, h = _fit([np.asarray(f["corners2d"], dtype=float) for f in faces], size * _MM)
    owner: dict[frozenset, list[int]] = {}
    for i, f in enumerate(faces):
        c3 = [tuple(c) for c in f["corners3d"]]
        for k in range(4):
            owner.setdefault(frozenset((c3[k], c3[(k + 1) % 4])), []).append(i)
    lines: dict[str, tuple[list, list]] = {"GRID": ([], []), "CUT": ([], [])}
    for i, f in enumerate(faces):
        c3 = [tuple(c) for c in f["corners3d"]]
        c2 = place(f["corners2d"])
        for k in range(4):
            pair = owner[frozenset((c3[k], c3[(k + 1) % 4]))]
            folded = any(tuple(sorted((i, j))) in folds for j in pair if j != i)
            a, b = lines["GRID" if folded else "CUT"]
            a.append(c2[k])
            b.append(c2[(k + 1) % 4])
    squares = Polylines.from_list([place(f["corners2d"]) for f in faces], [True] * len(faces))
    return Page(w, h, {k: Polylines.from_segments(np.array(a).reshape(-1, 2), np.array(b).reshape(-1, 2))
                       for k, (a, b) in lines.items()}, fills=(Fill(squares, "#e8edf4"),))


def cubes_svg(cells: list[list[int]], size: int = 120) -> str:
    """:func:`cubes_page` as inline SVG."""
    return _svg(cubes_page(cells, size))


def net_svg(net: dict[str, Any], size: int = 160) -> str:
    """:func:`net_page` as inline SVG."""
    return _svg(net_page(net, size))


def _certificate_text(rec: dict[str, Any]) -> str:
    cert = rec.get("certificate") or {}
    if cert.get("kind") == "colours":
        return (f"colour count: corners {cert['corners'][0]} even, {cert['corners'][1]} odd; "
                f"flat vertices {cert['flats'][0]} even, {cert['flats'][1]} odd")
    if cert.get("kind") == "solver":
        return (f"solver: the path model with {len(cert['overlaps'])} overlap and {len(cert['slits'])} slit "
                "no-goods has no solution")
    return ""


def _figure(rec: dict[str, Any], note: str = "") -> str:
    text = f"{html.escape(rec['id'])}" + (f"<br>{html.escape(note)}" if note else "")
    return f'<figure>{cubes_svg(rec["cells"])}<figcaption>{text}</figcaption></figure>'


def write_page(outdir: Path, data: dict[str, Any]) -> Path:
    """Write ``outdir/census.html`` from the census data; return its path."""
    from voxfab._shared.atomic import write_text

    from ._resume import upgrade_rows

    data = upgrade_rows(data)  # a census of the first format names its counts otherwise
    shapes = data["shapes"]
    head = ["n", "one_sided", "free", "unfold_found", "unfold_none", "unfold_undecided", "manifold",
            "unzip_found", "unzip_none", "unzip_undecided", "edge_touching", "vertex_touching", "handle",
            "square_zipper_found", "square_zipper_none", "seconds", "cpu_seconds"]
    if not data["settings"].get("square_zipper"):
        head = [k for k in head if not k.startswith("square_zipper")]
    rows = "".join("<tr>" + "".join(f"<td>{row.get(k, '')}</td>" for k in head) + "</tr>" for row in data["rows"])
    parts = [
        "<!doctype html><html><head><meta charset='utf-8'><title>voxfab polycube census</title><style>"
        "body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}td,th{border:1px solid #bbb;"
        "padding:2px 6px;text-align:right}figure{display:inline-block;margin:4px;text-align:center;"
        "font-size:12px;vertical-align:top}</style></head><body>",
        f"<h1>Polycube census, 1 to {data['n']} cubes</h1>",
        f"<p>Seed {data['settings']['seed']}, {data['settings']['timeout']:g} s per search; "
        f"{data['run']['seconds']:g} s on {data['run']['workers']} worker(s) ({html.escape(data['run']['where'])})"
        f"{'' if data['complete'] else ' &mdash; not complete'}.</p>",
        "<p>One sided: polycubes up to rotation (OEIS A000162), the ones censused; free: up to rotation and "
        "reflection, a mirror image counted as the same (A038119). Unfold: edge unfolding, unit-square model (every square a face of the net). Unzip: edge-unzipping "
        "in the model of Demaine, Demaine, Eppstein and O'Rourke (2020): one cut path through every corner vertex, "
        "flat vertices optional, on polycubes whose surface is a 2-manifold of genus 0. Square zipper (when "
        "searched): the cut path visits every vertex. Seconds: the searches' time per n, added over the shapes "
        "(wall clock and CPU).</p>",
        "<table><tr>" + "".join(f"<th>{k.replace('_', ' ')}</th>" for k in head) + f"</tr>{rows}</table>",
    ]
    none = [r for r in shapes if r.get("unzip") == "none"]
    parts.append(f"<h2>Without an edge-unzipping ({len(none)})</h2>")
    parts.append("".join(_figure(r, _certificate_text(r)) for r in none[:_PICTURES]) or "<p>None.</p>")
    undecided = [r for r in shapes if "undecided" in (r.get("unzip"), r.get("unfold"))]
    parts.append(f"<h2>Undecided ({len(undecided)})</h2>")
    parts.append("".join(_figure(r) for r in undecided[:_PICTURES]) or "<p>None.</p>")
    for kind in ("handle", "vertex touching", "edge touching"):
        listed = [r for r in shapes if r.get("surface") == kind]
        parts.append(f"<h2>Outside the paper's model: {kind} ({len(listed)})</h2>")
        parts.append("".join(_figure(r) for r in listed[:_PICTURES]) or "<p>None.</p>")
    parts.append("<h2>An unzipping per n (cut path in red)</h2>")
    for row in data["rows"]:
        first = next((r for r in shapes if r.get("n") == row["n"] and r.get("unzip_net")), None)
        if first is None:
            continue
        try:
            net = json.loads((outdir / first["unzip_net"]).read_text())
        except (OSError, ValueError):
            continue
        parts.append(f'<figure>{cubes_svg(first["cells"])}{net_svg(net)}<figcaption>{first["id"]}'
                     "</figcaption></figure>")
    parts.append("</body></html>\n")
    page = outdir / "census.html"
    write_text(page, "".join(parts))
    return page
