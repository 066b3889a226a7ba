"""The studio's downloads of the queen: the triptych of a chosen net in pieces, and the files inside its zips.

The queen's gallery is searched once for the module (a net in pieces for A4);
every file is read back on its own terms: the triptych's net panel measured
pixel by pixel, the SVG sheets parsed, the DXF sheets audited, the JSON pieces
refolded onto the queen.
"""

from __future__ import annotations

import io
import re
import zipfile

import numpy as np
import pytest
from PIL import Image

from voxfab.studio._grid import pack

from ._helpers import queen, wait_job

pytestmark = pytest.mark.slow

#: The names the files take in the zips: after the shape, no folder.
NET_SHEET = re.compile(r"queen-net\.sheet-\d+\.(svg|dxf)")
NET_PIECE = re.compile(r"queen-net\.piece-\d+\.json")
PLATES = re.compile(r"queen-plates-[A-Za-z0-9_.-]+")


@pytest.fixture(scope="module")
def studio(tmp_path_factory):
    """The studio app in-process, with the queen's gallery of one net in pieces for A4 already searched."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        from starlette.testclient import TestClient

    from voxfab.studio import Settings, create_app

    tmp = tmp_path_factory.mktemp("downloads")
    app = create_app(Settings(repo=tmp / "repo.sqlite", hosts=frozenset({"testserver"}), work=tmp / "work",
                              warm_up=False))
    with TestClient(app) as client:
        grid = queen()
        options = {"sheet": "A4", "pieces": "auto", "timeout": 5.0}
        r = client.post("/api/nets", json={"grid": pack(grid), "count": 1, "seed": 0, "options": options})
        assert r.status_code == 200, r.text
        s = wait_job(client, r.json()["job"], 300)
        assert s["state"] == "done", s
        net = s["result"]["nets"][0]
        assert net["pieces"] > 1 and net["fit"]["sheets"] > 1
        options["face_size"] = s["result"]["options"]["face_size"]
        yield {"client": client, "grid": grid, "job": r.json()["job"], "net": net, "options": options}


def _make(studio, artefact: str, *, net: bool = True, options: dict | None = None) -> tuple[str, bytes]:
    client = studio["client"]
    body = {"grid": pack(studio["grid"]), "artefact": artefact, "pitch": 2.0, "title": "queen",
            "options": options if options is not None else {}}
    if net:
        body["net"] = {"job": studio["job"], "index": 0}
    r = client.post("/api/make", json=body)
    assert r.status_code == 200, r.text
    s = wait_job(client, r.json()["job"], 240)
    assert s["state"] == "done", s
    (f,) = s["files"]
    return f["name"], client.get(f"/api/files/{r.json()['job']}/0").content


def _paper_pieces(panel: np.ndarray, background: tuple[int, int, int]) -> list[int]:
    """The pixel areas of the separate bits of paper drawn in a net panel (above its legend strip)."""
    from scipy import ndimage

    strip = max(18, panel.shape[0] // 22)
    paper = (np.abs(panel[: panel.shape[0] - strip].astype(int) - background).sum(axis=-1) > 30)
    # close the hairline gaps between a tab and its face, so that a piece and its tabs count once
    paper = ndimage.binary_closing(paper, iterations=2)
    labels, n = ndimage.label(paper, structure=np.ones((3, 3)))
    areas = np.bincount(labels.ravel())[1:]
    return sorted((int(a) for a in areas if a > 200), reverse=True)  # seam labels' specks are not pieces


def test_the_triptych_draws_the_chosen_net_in_its_pieces(studio):
    from voxfab.render import triptych_layout
    from voxfab.render._raster import parse_color

    name, raw = _make(studio, "triptych.png")
    assert name == "queen-triptych.png"
    with Image.open(io.BytesIO(raw)) as im:
        picture = np.asarray(im.convert("RGB"))
    # The studio's triptych is 600 px a panel; its net panel is the first.
    lay = triptych_layout(600)
    assert picture.shape[:2] == (lay.height, lay.width)
    left, top, right, bottom = lay.panels[0]
    bg = parse_color("white", name="background")
    areas = _paper_pieces(picture[top:bottom, left:right], bg)
    net = studio["net"]
    # One outline per piece of the chosen net, not the one uncut outline of a net of its own.
    assert len(areas) == net["pieces"], areas
    # ... and each as big as its faces: the pieces' areas rank as their face counts do.
    faces = sorted(np.bincount(net["layout"]["piece"]).tolist(), reverse=True)
    ratios = np.array(areas) / np.array(faces)
    assert ratios.max() < 2.0 * ratios.min(), (areas, faces)


@pytest.mark.parametrize("kind", ["svg", "dxf", "json"])
def test_the_net_zips_hold_files_named_after_the_shape(studio, kind):
    import ezdxf
    from lxml import etree

    from voxfab.unfold import Net, validate

    name, raw = _make(studio, f"net.{kind}", options=studio["options"])
    assert name == f"queen-net-{kind}.zip"
    archive = zipfile.ZipFile(io.BytesIO(raw))
    names = archive.namelist()
    pattern = NET_PIECE if kind == "json" else NET_SHEET
    assert names and all(pattern.fullmatch(n) for n in names), names
    if kind == "json":
        assert len(names) == studio["net"]["pieces"]
        pieces = [Net.from_json(archive.read(n).decode()) for n in names]
        assert validate(studio["grid"], pieces).ok
        return
    assert len(names) == studio["net"]["fit"]["sheets"]
    for n in names:
        if kind == "svg":
            assert etree.fromstring(archive.read(n)).get("width") == "210mm"
        else:
            assert not ezdxf.read(io.StringIO(archive.read(n).decode())).audit().has_errors


def test_the_plates_zip_holds_files_named_after_the_shape(studio):
    import json

    import ezdxf

    name, raw = _make(studio, "plates.zip", net=False, options={"thickness": 3.0})
    assert name == "queen-plates.zip"
    archive = zipfile.ZipFile(io.BytesIO(raw))
    names = archive.namelist()
    assert all(PLATES.fullmatch(n) for n in names), names
    assert "queen-plates-sheet-01.dxf" in names and "queen-plates-plates.json" in names
    assert not ezdxf.read(io.StringIO(archive.read("queen-plates-sheet-01.dxf").decode())).audit().has_errors
    report = json.loads(archive.read("queen-plates-plates.json"))
    assert report["name"] == "queen" and report["sheets"] == sum(n.endswith(".dxf") for n in names)
