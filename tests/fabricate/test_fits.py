""""Does it fit this sheet?": yes with a net, no (proved), or undecided, from the exact strategy."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("ortools")

from voxfab.errors import InvalidShapeError  # noqa: E402
from voxfab.fabricate.fits import fits_sheet  # noqa: E402
from voxfab.fabricate.netdraw import parse_sheet  # noqa: E402
from voxfab.unfold import validate  # noqa: E402

CUBE = np.ones((1, 1, 1), dtype=bool)


def test_the_cube_fits_3x5_faces_and_not_3x3():
    # 60 x 70 mm less margins and tabs leaves 3 x 3 faces of 10 mm: none of the cube's
    # eleven nets (3 x 4 or 2 x 5 faces) fits, and the search proves it.
    no = fits_sheet(CUBE, "60x70", 10.0)
    assert (no.answer, no.box, no.faces, no.net) == ("no", (3, 3), 6, None)
    assert no.message.startswith("no: ") and "(proved)" in no.message
    yes = fits_sheet(CUBE, "60x90", 10.0)
    assert (yes.answer, yes.box) == ("yes", (3, 5))
    assert validate(CUBE, yes.net, strict=True).ok
    x0, y0, x1, y1 = yes.net.bounds()
    w, h = x1 - x0, y1 - y0
    assert (w <= 3 and h <= 5) or (h <= 3 and w <= 5)
    sw, sh = parse_sheet("60x90")
    assert min(w, h) * 10.0 <= sw and max(w, h) * 10.0 <= sh


def test_a_tight_box_with_little_time_is_undecided():
    # The 2x2x2 cube in 3 x 8 faces: the exact strategy neither finds a net nor proves none in a second.
    fit = fits_sheet(np.ones((2, 2, 2), dtype=bool), "60x120", 10.0, timeout=1.0)
    assert (fit.answer, fit.box, fit.net) == ("undecided", (3, 8), None)
    assert fit.message.startswith("undecided: ")


def test_a_face_larger_than_the_sheet_is_no():
    fit = fits_sheet(CUBE, "A4", 400.0)
    assert (fit.answer, fit.box) == ("no", (0, 0))


@pytest.mark.parametrize(("kw", "match"), [({"sheet": "B99"}, "sheet"), ({"face_size": 0.0}, "face_size"),
                                           ({"timeout": 0}, "timeout"), ({"timeout": float("nan")}, "timeout")])
def test_bad_input_is_one_line(kw, match):
    with pytest.raises(InvalidShapeError, match=match):
        fits_sheet(CUBE, **{"sheet": "A4", "face_size": 10.0, **kw})
