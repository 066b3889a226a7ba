import json
import subprocess
import sys

import numpy as np
import pytest
from _handnets import tree_net
from _voxart import write_animated_character
from PIL import Image

from voxfab.cli import main
from voxfab.render import png_bytes, render
from voxfab.repo import Repository
from voxfab.shape import examples


def voxfab(*args):
    return subprocess.run([sys.executable, "-m", "voxfab", *map(str, args)], capture_output=True, text=True)


def test_render_png_view_through_the_real_entry_point(tmp_path):
    g = examples.random_shape(7)
    np.save(tmp_path / "s.npy", g)
    r = voxfab("render", tmp_path / "s.npy", "-o", tmp_path / "s.png", "--view=-x", "--size", "150")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["kind"] == "view" and out["view"] == "-x" and out["width"] == 150
    data = (tmp_path / "s.png").read_bytes()
    assert data == png_bytes(render(g, view="-x", size=150))
    with Image.open(tmp_path / "s.png") as im:
        assert im.size == (150, 150)


def test_the_profile_view_and_where_it_has_no_shape(tmp_path, capsys):
    from pathlib import Path

    from voxfab.recipe import load_recipe, make_shape

    knight = make_shape(load_recipe(Path(__file__).parents[2] / "recipes" / "chess" / "knight.toml")).grid
    np.save(tmp_path / "k.npy", knight)
    assert main(["render", str(tmp_path / "k.npy"), "-o", str(tmp_path / "k.png"), "--view", "profile",
                 "--size", "90"]) == 0
    assert (tmp_path / "k.png").read_bytes() == png_bytes(render(knight, view="profile", size=90))
    assert (tmp_path / "k.png").read_bytes() != png_bytes(render(knight, view="iso", size=90))
    # A folding net has no voxels to choose a profile from: one line, no traceback.
    (tmp_path / "n.json").write_text(tree_net(np.ones((2, 1, 1), dtype=bool)).to_json())
    capsys.readouterr()
    assert main(["render", "--fold", str(tmp_path / "n.json"), "-o", str(tmp_path / "f.gif"),
                 "--view", "profile"]) != 0
    assert capsys.readouterr().err.strip().splitlines() == [
        "voxfab: error: view: 'profile' is chosen from a shape's voxels; this picture has none"]


def test_negative_view_written_with_a_space(tmp_path):
    g = examples.random_shape(7)
    np.save(tmp_path / "s.npy", g)
    assert main(["render", str(tmp_path / "s.npy"), "-o", str(tmp_path / "a.png"), "--view", "-y",
                 "--size", "90"]) == 0
    assert (tmp_path / "a.png").read_bytes() == png_bytes(render(g, view="-y", size=90))


def test_render_gif_turntable(tmp_path):
    np.save(tmp_path / "s.npy", examples.random_shape(8))
    assert main(["render", str(tmp_path / "s.npy"), "-o", str(tmp_path / "t.gif"), "--size", "64",
                 "--frames", "5"]) == 0
    with Image.open(tmp_path / "t.gif") as im:
        assert im.n_frames == 5 and im.size == (64, 64)


def test_render_triptych_png_and_pdf_with_a_given_net(tmp_path, capsys):
    g = np.ones((2, 1, 1), dtype=bool)
    np.save(tmp_path / "bar.npy", g)
    (tmp_path / "bar.json").write_text(tree_net(g).to_json())
    for ext in ("png", "pdf"):
        rc = main(["render", str(tmp_path / "bar.npy"), "--triptych", "--net", str(tmp_path / "bar.json"),
                   "-o", str(tmp_path / f"t.{ext}"), "--size", "160"])
        assert rc == 0
        summary = json.loads(capsys.readouterr().out)
        assert summary["kind"] == "triptych" and summary["shape"] == "bar"
    with Image.open(tmp_path / "t.png") as im:
        assert im.size == (summary["width"], summary["height"])
    pdf = (tmp_path / "t.pdf").read_bytes()
    assert pdf.startswith(b"%PDF") and b"(bar)" in pdf
    # Same command, same bytes.
    main(["render", str(tmp_path / "bar.npy"), "--triptych", "--net", str(tmp_path / "bar.json"),
          "-o", str(tmp_path / "again.pdf"), "--size", "160"])
    assert (tmp_path / "again.pdf").read_bytes() == pdf


def test_render_slices_and_net_pictures(tmp_path):
    g = np.ones((1, 1, 1), dtype=bool)
    np.save(tmp_path / "c.npy", g)
    (tmp_path / "c.json").write_text(tree_net(g).to_json())
    assert main(["render", str(tmp_path / "c.npy"), "--slices", "-o", str(tmp_path / "s.png")]) == 0
    assert main(["render", str(tmp_path / "c.npy"), "--net", str(tmp_path / "c.json"), "-o",
                 str(tmp_path / "n.png"), "--size", "300"]) == 0
    with Image.open(tmp_path / "n.png") as im:
        assert im.size == (300, 300)


def test_contact_sheet_through_the_real_entry_point(tmp_path):
    repo_path = tmp_path / "r.sqlite"
    with Repository(repo_path) as repo:
        repo.add(examples.random_shape(1))
        repo.add(examples.random_shape(2))
    r = voxfab("render", "--contact-sheet", "--repo", repo_path, "-o", tmp_path / "sheet.png", "--size", "64")
    assert r.returncode == 0, r.stderr
    with Image.open(tmp_path / "sheet.png") as im:
        assert im.width == 128


def test_render_by_repository_name(tmp_path):
    repo_path = tmp_path / "r.sqlite"
    g = examples.random_shape(3)
    with Repository(repo_path) as repo:
        name = repo.add(g).name
    r = voxfab("render", name, "--repo", repo_path, "-o", tmp_path / "v.png", "--size", "80")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["shape"] == name


@pytest.mark.parametrize(
    ("args", "code", "text"),
    [
        (["{s}", "-o", "{d}/x.jpg"], 4, "x.jpg"),
        (["{s}", "--triptych", "-o", "{d}/x.gif"], 4, "triptych"),
        (["-o", "{d}/x.png"], 3, "SHAPE"),
        (["{s}", "-o", "{d}/x.png", "--size", "2"], 3, "size"),
        (["{d}/missing.npy", "-o", "{d}/x.png"], None, "missing.npy"),
    ],
)
def test_errors_are_one_line_with_an_exit_code(tmp_path, args, code, text, capsys):
    np.save(tmp_path / "s.npy", examples.ball(2))
    argv = [a.format(s=tmp_path / "s.npy", d=tmp_path) for a in args]
    rc = main(["render", *argv])
    err = capsys.readouterr().err
    assert rc != 0
    if code is not None:
        assert rc == code
    assert err.startswith("voxfab: error:") and text in err
    assert len(err.strip().splitlines()) == 1


def test_an_error_through_the_real_entry_point(tmp_path):
    np.save(tmp_path / "s.npy", examples.ball(2))
    r = voxfab("render", tmp_path / "s.npy", "-o", tmp_path / "x.bmp")
    assert r.returncode == 4
    assert r.stderr.startswith("voxfab: error:") and "x.bmp" in r.stderr
    assert not (tmp_path / "x.bmp").exists()


def test_triptych_net_comes_from_the_engine_with_the_seed(tmp_path):
    import voxfab.unfold as unfold

    if not hasattr(unfold, "unfold"):
        pytest.skip("voxfab.unfold.unfold not available")
    from voxfab.render import triptych

    g = examples.ball(2)
    np.save(tmp_path / "b.npy", g)
    assert main(["render", str(tmp_path / "b.npy"), "--triptych", "--seed", "4", "-o", str(tmp_path / "t.png"),
                 "--size", "120"]) == 0
    expected = triptych(g, name="b", net=unfold.unfold(g, rng=4), panel=120)
    assert (tmp_path / "t.png").read_bytes() == png_bytes(expected)


def test_render_is_the_pictures_pipeline_with_one_picture(tmp_path, capsys):
    from voxfab.render import Picture, PictureKind, PictureOptions, render_pictures

    g = np.ones((1, 1, 1), dtype=bool)
    np.save(tmp_path / "c.npy", g)
    (tmp_path / "c.json").write_text(tree_net(g).to_json())
    assert main(["render", str(tmp_path / "c.npy"), "--net", str(tmp_path / "c.json"), "-o",
                 str(tmp_path / "n.pdf"), "--size", "100", "--background", "#eeeeee"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary == {"output": str(tmp_path / "n.pdf"), "shape": "c", "kind": "net", "width": 100, "height": 100}
    lib = tmp_path / "lib"
    lib.mkdir()
    render_pictures(g, PictureOptions(size=100, background="#eeeeee"), lib, name="c", seed=0,
                    net=tree_net(g), pictures=(Picture(PictureKind.NET, "n.pdf"),))
    assert (lib / "n.pdf").read_bytes() == (tmp_path / "n.pdf").read_bytes()
    # A turntable without --size is half the default picture side, as in a recipe.
    assert main(["render", str(tmp_path / "c.npy"), "-o", str(tmp_path / "t.gif"), "--frames", "2"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert (summary["kind"], summary["width"], summary["frames"]) == ("turntable", 400, 2)


def test_render_reads_the_frame_asked_of_an_animation(tmp_path):
    from voxfab import io

    write_animated_character(tmp_path / "anim.vox")
    for k in (1, 2):
        r = voxfab("render", tmp_path / "anim.vox", "--frame", k, "-o", tmp_path / f"f{k}.png", "--size", "120")
        assert r.returncode == 0, r.stderr
        alone = tmp_path / f"alone{k}.png"
        io.write(io.read(tmp_path / "anim.vox", frame=k).shape(), tmp_path / f"alone{k}.vox")
        assert voxfab("render", tmp_path / f"alone{k}.vox", "-o", alone, "--size", "120").returncode == 0
        assert (tmp_path / f"f{k}.png").read_bytes() == alone.read_bytes()
    assert (tmp_path / "f1.png").read_bytes() != (tmp_path / "f2.png").read_bytes()
    r = voxfab("render", tmp_path / "anim.vox", "--frame", 3, "-o", tmp_path / "f3.png")
    assert r.returncode != 0 and r.stderr.strip().endswith("frame 3: the file holds 2 frames")
