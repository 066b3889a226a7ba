"""``census.html``: the census table per n, with pictures of the polycubes it names.

The page is one self-contained file: the table of ``census.json``'s rows, the
polycubes without an unzipping (each with its proof), those left undecided and
those outside the paper's model (touchings, handles), each drawn as an
isometric picture, and for each n the unzipping net of its first polycube with
the cut path in red.  Pictures are inline SVG, so the page needs no other file.
"""

from __future__ import annotations

import html
import json
from pathlib import Path
from typing import Any

__all__ = ["cubes_svg", "net_svg", "write_page"]

#: Pictures drawn per list on the page (the lists themselves are complete in census.json).
_PICTURES = 24


def cubes_svg(cells: list[list[int]], size: int = 120) -> str:
    """An isometric picture of unit cubes: visible faces painted back to front, shaded by direction."""
    filled = {tuple(c) for c in cells}
    # Screen position of a lattice point, looking from (+1, +1, +1) with z up.
    def at(x: float, y: float, z: float) -> tuple[float, float]:
        return ((x - y) * 0.866, (x + y) * 0.5 - z)

    faces = []
    for x, y, z in filled:
        for d, shade, quad in (
            ((1, 0, 0), "#8fa8c8", ((1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1))),
            ((0, 1, 0), "#6d88ad", ((0, 1, 0), (1, 1, 0), (1, 1, 1), (0, 1, 1))),
            ((0, 0, 1), "#c9d7ea", ((0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1))),
        ):
            if (x + d[0], y + d[1], z + d[2]) in filled:
                continue
            pts = [at(x + a, y + b, z + c) for a, b, c in quad]
            faces.append((x + y + z + sum(d) * 0.5, shade, pts))
    faces.sort(key=lambda f: f[0])
    xs = [p[0] for _, _, pts in faces for p in pts]
    ys = [p[1] for _, _, pts in faces for p in pts]
    w, h = max(xs) - min(xs), max(ys) - min(ys)
    s = (size - 8) / max(w, h, 1.0)
    ox, oy = 4 - min(xs) * s + (size - 8 - w * s) / 2, 4 - min(ys) * s + (size - 8 - h * s) / 2
    polys = "".join(
        f'<polygon points="{" ".join(f"{ox + px * s:.1f},{oy + py * s:.1f}" for px, py in pts)}" '
        f'fill="{shade}" stroke="#223" stroke-width="0.8"/>'
        for _, shade, pts in faces)
    return f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}">{polys}</svg>'


def net_svg(net: dict[str, Any], size: int = 160) -> str:
    """A ``voxfab-net/1`` net: squares in grey, folds thin, cut edges (the others) thick red."""
    faces = net["faces"]
    folds = {tuple(sorted(p)) for p in net["folds"]}
    cx = [c[0] for f in faces for c in f["corners2d"]]
    cy = [c[1] for f in faces for c in f["corners2d"]]
    w, h = max(cx) - min(cx), max(cy) - min(cy)
    s = (size - 8) / max(w, h, 1)
    x0, y1 = min(cx), max(cy)

    def pt(c: list[int]) -> str:
        return f"{4 + (c[0] - x0) * s:.1f},{4 + (y1 - c[1]) * s:.1f}"

    body = [f'<polygon points="{" ".join(pt(c) for c in f["corners2d"])}" fill="#e8edf4"/>' for f in faces]
    # A net edge is a fold when the two faces sharing it in 3D are listed in folds; else it is cut.
    owner: dict[tuple, list[int]] = {}
    for i, f in enumerate(faces):
        c3 = [tuple(c) for c in f["corners3d"]]
        for k in range(4):
            owner.setdefault(frozenset((c3[k], c3[(k + 1) % 4])), []).append(i)
    for i, f in enumerate(faces):
        c3 = [tuple(c) for c in f["corners3d"]]
        c2 = f["corners2d"]
        for k in range(4):
            pair = owner[frozenset((c3[k], c3[(k + 1) % 4]))]
            others = [j for j in pair if j != i]
            folded = any(tuple(sorted((i, j))) in folds for j in others)
            style = 'stroke="#9aa" stroke-width="0.6"' if folded else 'stroke="#c00" stroke-width="1.6"'
            a, b = pt(c2[k]).split(","), pt(c2[(k + 1) % 4]).split(",")
            body.append(f'<line x1="{a[0]}" y1="{a[1]}" x2="{b[0]}" y2="{b[1]}" {style}/>')
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{w * s + 8:.0f}" height="{h * s + 8:.0f}">'
            f'{"".join(body)}</svg>')


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

    shapes = data["shapes"]
    head = ["n", "free", "free_mirror", "unfold_found", "unfold_none", "unfold_undecided", "manifold",
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
        "<p>Unfold: edge unfolding, unit-square model (every square a face of the net). Unzip: edge-unzipping "
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
