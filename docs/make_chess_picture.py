"""Draw docs/chess_set.png: the six chess pieces of recipes/chess side by side, at their true sizes.

Run from the repository root: ``python docs/make_chess_picture.py``.
"""

from __future__ import annotations

from pathlib import Path

from PIL import Image, ImageChops, ImageDraw

from voxfab.recipe import load_recipe, make_shape
from voxfab.render import render

HERE = Path(__file__).resolve().parent
CHESS = HERE.parent / "recipes" / "chess"
ORDER = ("king", "queen", "bishop", "knight", "rook", "pawn")
#: Pixels per millimetre of the print: every piece is drawn at one scale.
PX_PER_MM = 3.2
GAP = 24


def piece_picture(name: str) -> Image.Image:
    """The piece in its profile view (isometric for the lathe-turned pieces), cropped to its pixels."""
    recipe = load_recipe(CHESS / f"{name}.toml")
    image = render(make_shape(recipe), view="profile", size=520, scale=PX_PER_MM * recipe.pitch).convert("RGB")
    ink = ImageChops.difference(image, Image.new("RGB", image.size, "white")).getbbox()
    return image.crop(ink)


def main() -> None:
    pictures = [piece_picture(name) for name in ORDER]
    label_room = 28
    width = sum(p.width for p in pictures) + GAP * (len(pictures) + 1)
    height = max(p.height for p in pictures) + 2 * GAP + label_room
    sheet = Image.new("RGB", (width, height), "white")
    draw = ImageDraw.Draw(sheet)
    x = GAP
    for name, picture in zip(ORDER, pictures):
        sheet.paste(picture, (x, height - label_room - GAP - picture.height))
        recipe = load_recipe(CHESS / f"{name}.toml")
        text = f"{name} {25 * recipe.pitch:g} mm"
        draw.text((x + picture.width // 2, height - label_room), text, fill="black", anchor="mt")
        x += picture.width + GAP
    target = HERE / "chess_set.png"
    tmp = target.with_suffix(".part.png")
    sheet.quantize(colors=64).save(tmp, optimize=True)
    tmp.replace(target)
    print(f"{target}: {sheet.width} x {sheet.height} px, {target.stat().st_size // 1024} KB")


if __name__ == "__main__":
    main()
