"""Draw the pictures of the documentation pages from bundled recipes, through voxfab's own commands.

Run from the repository root: ``python docs/make_pictures.py``. Each picture is a PNG of at most
64 colours, well under 300 KB: ``docs/img/triptych.png`` (the queen: net | slices | 3D),
``docs/img/slices.png`` (the queen's layers, the plates of a stack), ``docs/img/colour.png`` (the egg
painted by two ``paint`` operations), ``docs/img/fold.png`` (the vase's net folding up, one frame) and
``docs/img/swordsman.png`` (the bundled voxel-art swordsman: his print in four filaments, his net, his picture).
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

from PIL import Image

HERE = Path(__file__).resolve().parent
RECIPES = HERE.parent / "recipes"
IMG = HERE / "img"

PAINT = """
[[operations]]
op = "paint"
colour = "#c03020"
where = "z - 12"

[[operations]]
op = "paint"
colour = "#2050c0"
where = "(x - 12)^2 + (y - 12)^2 - 40"
"""


def voxfab(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "voxfab", *args], check=True)


def keep(picture: Path, name: str, colours: int = 64) -> None:
    """Save ``picture`` as docs/img/NAME in ``colours`` colours, through a temporary name."""
    target = IMG / name
    tmp = target.with_suffix(".part.png")
    Image.open(picture).convert("RGB").quantize(colors=colours).save(tmp, optimize=True)
    tmp.replace(target)
    print(f"{target}: {target.stat().st_size // 1024} KB")


def main() -> None:
    IMG.mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        queen = (RECIPES / "chess" / "queen.toml").read_text(encoding="utf-8")
        head = queen.split("[outputs.", 1)[0]
        (work / "queen.toml").write_text(head, encoding="utf-8")
        for svg in (RECIPES / "chess").glob("queen_*"):
            (work / svg.name).write_bytes(svg.read_bytes())
        voxfab("build", str(work / "queen.toml"), "-o", str(work / "out"))
        shape = work / "queen.npz"  # the triptych is titled with the file's name
        shape.write_bytes((work / "out" / "queen" / "shape.npz").read_bytes())
        voxfab("render", str(shape), "--triptych", "-o", str(work / "triptych.png"), "--size", "360")
        keep(work / "triptych.png", "triptych.png")
        voxfab("render", str(shape), "--slices", "-o", str(work / "slices.png"), "--size", "480")
        keep(work / "slices.png", "slices.png")

        egg = (RECIPES / "egg.toml").read_text(encoding="utf-8").split("[outputs.", 1)[0].replace('name = "egg"', 'name = "painted_egg"')
        (work / "painted_egg.toml").write_text(egg + PAINT, encoding="utf-8")
        voxfab("build", str(work / "painted_egg.toml"), "-o", str(work / "out"))
        egg_shape = work / "painted_egg.npz"
        egg_shape.write_bytes((work / "out" / "painted_egg" / "shape.npz").read_bytes())
        voxfab("render", str(egg_shape), "-o", str(work / "colour.png"), "--size", "360")
        keep(work / "colour.png", "colour.png")
        swordsman(work)


def swordsman(work: Path) -> None:
    """Three panels of the swordsman recipe: the print in the filaments mesh.json lists, the net, the figure."""
    import numpy as np

    from voxfab import io
    from voxfab.shape import VoxelColours, parse_colour

    voxfab("build", str(RECIPES / "character" / "swordsman.toml"), "-o", str(work / "out"))
    built = work / "out" / "swordsman"
    shape = io.read(built / "shape.npz").shape()
    # The print: each colour in the filament it merged into.
    filament = {}
    for f in json.loads((built / "mesh.json").read_text())["colours"]["filaments"]:
        for hex_colour in [f["colour"], *f["merged"]]:
            filament[hex_colour] = parse_colour(f["colour"])
    palette = np.array(shape.colours.palette, copy=True)
    for i in shape.colours.used:
        palette[i] = filament[shape.colours.hex(int(i))]
    printed = shape.with_colours(VoxelColours(shape.colours.index, palette))
    io.write(printed, work / "print.npz")
    voxfab("render", str(work / "print.npz"), "--view", "profile", "-o", str(work / "print.png"), "--size", "300")
    voxfab("render", str(built / "shape.npz"), "--view", "profile", "-o", str(work / "figure.png"), "--size", "300")
    voxfab("render", str(built / "shape.npz"), "--net", str(built / "net.json"), "-o", str(work / "net.png"),
           "--size", "300")
    panels = [Image.open(work / f"{n}.png").convert("RGB") for n in ("print", "net", "figure")]
    strip = Image.new("RGB", (sum(p.width for p in panels), max(p.height for p in panels)), "white")
    x = 0
    for panel in panels:
        strip.paste(panel, (x, 0))
        x += panel.width
    strip.save(work / "swordsman.png")
    keep(work / "swordsman.png", "swordsman.png", colours=128)


if __name__ == "__main__":
    main()
