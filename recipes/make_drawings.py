"""Regenerate the input drawings (SVG, JSON, PNG) of the shipped recipes.

Run ``python recipes/make_drawings.py``; the outputs are small and deterministic.
"""

from __future__ import annotations

import io
import json
from pathlib import Path

from PIL import Image, ImageDraw

from voxfab._shared.atomic import write_bytes, write_text

HERE = Path(__file__).resolve().parent


def svg(width: int, height: int, body: str) -> str:
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
        f'viewBox="0 0 {width} {height}">\n{body}\n</svg>\n'
    )


def png(image: Image.Image) -> bytes:
    buf = io.BytesIO()
    image.save(buf, format="PNG", optimize=True)
    return buf.getvalue()


def queen() -> str:
    # open generatrix from the axis (x = 10) at the foot to the axis at the crown; y down
    d = (
        "M 10 200 L 62 200 L 62 190 L 52 184 L 52 178 L 40 172 "
        "C 30 150, 22 110, 22 80 L 36 74 L 36 68 L 24 64 L 34 46 L 24 40 "
        "C 20 34, 16 32, 10 30"
    )
    return svg(80, 210, f'<path d="{d}" fill="none" stroke="black"/>')


def king() -> str:
    # closed half-section (region) of the king, axis at x = 10
    d = (
        "M 10 200 L 64 200 L 64 188 L 52 180 L 42 170 C 32 140, 26 110, 26 84 L 40 78 L 40 70 "
        "L 28 66 L 38 50 L 20 46 L 20 36 L 28 36 L 28 28 L 20 28 L 20 16 L 10 16 Z"
    )
    return svg(80, 210, f'<path d="{d}" fill="black"/>')


def rook_section() -> str:
    # closed octagon, drawn around the axis: the rook's curve of revolution
    import math

    pts = [(50 + 40 * math.cos(math.pi / 8 + i * math.pi / 4), 50 + 40 * math.sin(math.pi / 8 + i * math.pi / 4)) for i in range(8)]
    d = "M " + " L ".join(f"{x:.3f} {y:.3f}" for x, y in pts) + " Z"
    return svg(100, 100, f'<path d="{d}" fill="black"/>')


def rook_generatrix() -> dict:
    # (rho, z) points, open, from the axis at the foot to the axis at the top
    # taller than wide, as a playing piece: 60 mm tall on a 45 mm foot
    return {"points": [[0, 0], [9, 0], [9, 1.5], [7.5, 2.5], [6, 3.5], [5.4, 16.5], [7, 18], [7, 23.5], [5, 23.5],
                       [5, 22], [0, 22]]}


def top_generatrix() -> dict:
    # spinning top: a one-voxel tip on the axis (the thin stem at the bottom), a 45 degree cone (each
    # printed layer at most one voxel wider than the one below), wide body, thin handle
    return {"points": [[0, 0], [0.35, 0], [0.35, 0.8], [1.2, 1.6], [6, 6.2], [10, 10], [10.5, 11], [9, 12], [2, 13],
                       [1.2, 13.5], [1.2, 17.5], [0, 18]]}


def bishop() -> Image.Image:
    # region half-section of the bishop: dark = inside, axis on the left edge of the dark pixels
    im = Image.new("L", (40, 100), 255)
    dr = ImageDraw.Draw(im)
    dr.polygon([(2, 98), (32, 98), (32, 92), (24, 88), (18, 84), (12, 40), (22, 36), (22, 32), (12, 30)], fill=0)
    dr.ellipse((-12, 8, 18, 34), fill=0)
    dr.ellipse((-3, 1, 7, 10), fill=0)
    dr.rectangle((0, 0, 1, 99), fill=255)
    dr.rectangle((2, 4, 3, 97), fill=0)
    return im


def vase() -> Image.Image:
    # half-section of a vase wall with a bottom: dark = material
    im = Image.new("L", (60, 120), 255)
    dr = ImageDraw.Draw(im)
    outer = [(0, 118), (34, 118), (46, 90), (50, 70), (40, 45), (28, 25), (36, 4), (40, 2)]
    inner = [(37, 6), (29, 26), (32, 44), (44, 70), (40, 90), (29, 108), (0, 108)]
    dr.polygon(outer + inner, fill=0)
    return im


def top_section() -> Image.Image:
    # star-shaped (scalloped) section for the spinning top
    import math

    im = Image.new("L", (101, 101), 255)
    pts = []
    for i in range(360):
        a = math.radians(i)
        r = 40 + 6 * math.cos(8 * a)
        pts.append((50 + r * math.cos(a), 50 + r * math.sin(a)))
    ImageDraw.Draw(im).polygon(pts, fill=0)
    return im


def three_disks() -> Image.Image:
    # profile of the interlaced tubes: three disks that overlap a little
    import math

    im = Image.new("L", (64, 64), 255)
    dr = ImageDraw.Draw(im)
    for i in range(3):
        a = math.radians(90 + 120 * i)
        cx, cy = 32 + 15 * math.cos(a), 32 - 15 * math.sin(a)
        dr.ellipse((cx - 14, cy - 14, cx + 14, cy + 14), fill=0)
    return im


def main() -> None:
    write_text(HERE / "chess" / "queen_generatrix.svg", queen())
    write_text(HERE / "chess" / "king_generatrix.svg", king())
    write_text(HERE / "chess" / "rook_section.svg", rook_section())
    write_text(HERE / "chess" / "rook_generatrix.json", json.dumps(rook_generatrix()) + "\n")
    write_bytes(HERE / "chess" / "bishop_generatrix.png", png(bishop()))
    write_text(HERE / "top_generatrix.json", json.dumps(top_generatrix()) + "\n")
    write_bytes(HERE / "top_section.png", png(top_section()))
    write_bytes(HERE / "vase_generatrix.png", png(vase()))
    write_bytes(HERE / "tubes" / "three_disks.png", png(three_disks()))


if __name__ == "__main__":
    main()
