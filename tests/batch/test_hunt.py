"""The hunt over a repository on a real LocalCluster: outcomes recorded per shape, nets checked, index counts."""

from __future__ import annotations

import json

import numpy as np
import pytest
from _batch_fixtures import write_outputs
from _zipper_checks import cuts_form_one_path

pytest.importorskip("ortools")

from voxfab.batch import hunt_summary, run_batch  # noqa: E402
from voxfab.generate import explore  # noqa: E402
from voxfab.repo import Repository  # noqa: E402
from voxfab.unfold import Net, validate  # noqa: E402

HUNT = "seed = 3\n\n[outputs.hunt]\ntimeout = 10\nzipper_timeout = 30\n"


def _ring_on_a_column() -> np.ndarray:
    """A well-formed shape with a handle: a 3x3 ring at the foot of a column spanning the grid."""
    g = np.zeros((3, 3, 25), dtype=bool)
    g[:, :, 0] = True
    g[1, 1, 0] = False
    g[0, 0, :] = True
    return g


def test_hunt_over_explored_shapes(tmp_path):
    repo_path = tmp_path / "r.sqlite"
    with Repository(repo_path) as repo:
        explore(repo, 4, seed=0, volume=(25, 27))
        ring = repo.add(_ring_on_a_column(), symmetric=True).name
        names = [e.name for e in repo.list(drafts=False)]
    outputs = write_outputs(tmp_path / "hunt.toml", HUNT)
    out = tmp_path / "out"
    report = run_batch(repo_path, outputs, out, workers=2, dashboard=None)
    assert (report.built, report.failed, report.workers) == (5, 0, 2)

    counted: dict[str, dict[str, int]] = {"net": {}, "zipper": {}}
    for name in names:
        folder = out / name
        grid = np.load(folder / "shape.npy")
        record = json.loads((folder / "hunt.json").read_text())
        assert record["name"] == name and record["seed"] == 3
        for key in ("net", "zipper"):
            counted[key][record[key]] = counted[key].get(record[key], 0) + 1
        # Explored shapes are small: the random engine unfolds every one.
        assert record["net"] == "random"
        net = Net.from_json((folder / "hunt-net.json").read_text())
        assert validate(grid, net).ok and net.face_count == record["faces"]
        zipper = folder / "hunt-zipper.json"
        assert zipper.exists() == (record["zipper"] == "found")
        if zipper.exists():
            znet = Net.from_json(zipper.read_text())
            assert validate(grid, znet).ok and cuts_form_one_path(grid, znet)
    assert json.loads((out / ring / "hunt.json").read_text())["zipper"] == "none"
    assert counted["zipper"].get("found", 0) >= 1

    # The report and the index count what the shapes' files say.
    counts = report.hunt.counts()
    assert {k: {o: n for o, n in v.items() if n} for k, v in counts.items()} == counted
    from lxml import html

    page = html.parse(str(out / "index.html")).getroot()
    for group, outcomes in counts.items():
        for outcome, n in outcomes.items():
            assert page.get_element_by_id(f"hunt-{group}-{outcome}").text_content() == str(n)
    listed = page.xpath('//h3[starts-with(., "no zipper net (proved)")]/following-sibling::p[1]//a/text()')
    assert listed == [ring]
    assert all((out / "thumbs" / f"{n}-net.png").is_file() for n in names)

    # Run again: every folder is sound and skipped, and the hunt is counted from the folders.
    again = run_batch(repo_path, outputs, out, workers=2, dashboard=None)
    assert (again.built, again.skipped) == (0, 5)
    assert again.hunt.counts() == counts == hunt_summary(out, names).counts()


def test_voxfab_batch_prints_the_hunt(tmp_path):
    """``voxfab batch --outputs hunt.toml``: the last lines give the hunt's counts, as the folders say."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    from _batch_fixtures import make_repo

    names = make_repo(tmp_path / "r.sqlite")[:2]
    outputs = write_outputs(tmp_path / "hunt.toml", HUNT)
    root = Path(__file__).resolve().parents[2]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(root), os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run([sys.executable, "-m", "voxfab", "batch", "--repo", str(tmp_path / "r.sqlite"), "--outputs",
                        str(outputs), "-o", str(tmp_path / "out"), "--limit", "2", "--no-dashboard", "--no-index"],
                       capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 0, r.stderr
    zipped = [json.loads((tmp_path / "out" / n / "hunt.json").read_text())["zipper"] for n in names]
    line = next(x for x in r.stdout.splitlines() if x.startswith("hunt of "))
    assert line == (f"hunt of 2 shapes: one-piece net found by the random engine 2, only by the exact strategy 0, "
                    f"proved none 0, undecided 0; zipper net found {zipped.count('found')}, proved none "
                    f"{zipped.count('none')}, undecided {zipped.count('undecided')}")
