"""mkdocs hooks: fill each page's generated blocks from the code at build time (voxfab.cli._reference)."""

from __future__ import annotations

from pathlib import Path

from voxfab.cli._reference import fill

DATA = Path(__file__).resolve().parents[1] / "data"


def on_page_markdown(markdown, page, config, files):  # noqa: ARG001 - mkdocs' hook signature
    return fill(markdown, DATA)
