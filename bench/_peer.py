"""The peer for nets in pieces: Blender's bundled Export Paper Model add-on, run headless.

Used by the benches only, and only when ``blender`` is on the PATH.  The peer
gets the same surface as voxfab: one quad per exposed voxel face, vertices
shared, wound counter-clockwise seen from outside, 1 unit = 1 mm at the face
size asked for.  It lays out the pieces on pages of the sheet (10 mm margin,
tabs and numbers on) and writes an SVG per page; the pages are counted from
the files, and the time is the whole Blender process, start-up included, as a
maker would wait for it.
"""

from __future__ import annotations

import dataclasses
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

#: Sheet sizes the add-on takes, mm (its page_size_preset names).
PEER_SHEETS = {"A4": (210.0, 297.0), "Letter": (215.9, 279.4), "A3": (297.0, 420.0), "mat12": (304.8, 304.8)}

_SCRIPT = r'''
import sys
import addon_utils
import bpy

obj, out, w, h, margin = sys.argv[sys.argv.index("--") + 1:]
w, h, margin = float(w), float(h), float(margin)
addon_utils.enable("io_export_paper_model", default_set=True)
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o, do_unlink=True)
bpy.ops.wm.obj_import(filepath=obj, forward_axis="Y", up_axis="Z")
scene = bpy.context.scene
scene.unit_settings.scale_length = 0.001
o = bpy.context.selected_objects[0]
bpy.context.view_layer.objects.active = o
scene.paper_model.limit_by_page = True
scene.paper_model.use_auto_scale = False
scene.paper_model.output_size_x = (w - 2 * margin - 11.0) / 1000.0
scene.paper_model.output_size_y = (h - 2 * margin - 17.0) / 1000.0
bpy.ops.export_mesh.paper_model(filepath=out, file_format="SVG", page_size_preset="USER",
                                output_size_x=w / 1000.0, output_size_y=h / 1000.0, output_margin=margin / 1000.0,
                                do_create_stickers=True, do_create_numbers=True, sticker_width=0.005, scale=1.0)
print("PEER-DONE")
'''


@dataclasses.dataclass(frozen=True)
class PeerRun:
    """What the peer made: pages written (0 when it failed), the whole process's time, and its error."""

    pages: int
    seconds: float
    error: str = ""


def peer_available() -> bool:
    """Whether Blender (with the add-on Debian ships) is on the PATH."""
    return shutil.which("blender") is not None


def surface_obj(grid: np.ndarray, face_mm: float) -> str:
    """The voxel surface as OBJ text: one quad per exposed face, shared vertices, outward winding, in mm."""
    from voxfab.shape import surface_graph

    corners = surface_graph(np.asarray(grid, dtype=bool)).corners.reshape(-1, 3)
    points, index = np.unique(corners, axis=0, return_inverse=True)
    quads = index.reshape(-1, 4) + 1
    lines = [f"v {x * face_mm:g} {y * face_mm:g} {z * face_mm:g}" for x, y, z in points.tolist()]
    lines += [f"f {a} {b} {c} {d}" for a, b, c, d in quads.tolist()]
    return "\n".join(lines) + "\n"


def run_peer(grid: np.ndarray, face_mm: float, sheet: str, margin: float = 10.0, timeout: float = 300.0) -> PeerRun:
    """Run Blender's Export Paper Model on ``grid``'s surface; its pages and time."""
    w, h = PEER_SHEETS[sheet]
    with tempfile.TemporaryDirectory(prefix="voxfab-peer-") as tmp:
        d = Path(tmp)
        (d / "shape.obj").write_text(surface_obj(grid, face_mm))
        (d / "peer.py").write_text(_SCRIPT)
        out = d / "net.svg"
        cmd = ["blender", "-b", "--factory-startup", "-noaudio", "-P", str(d / "peer.py"), "--",
               str(d / "shape.obj"), str(out), f"{w:g}", f"{h:g}", f"{margin:g}"]
        t = time.perf_counter()
        try:
            done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return PeerRun(0, time.perf_counter() - t, "timed out")
        seconds = time.perf_counter() - t
        pages = len(list(d.glob("net*.svg")))
        if "PEER-DONE" not in done.stdout or pages == 0:
            lines = [x for x in (done.stdout + done.stderr).splitlines() if "Error" in x or "error" in x]
            return PeerRun(0, seconds, (lines[-1] if lines else "no pages written")[:120])
        return PeerRun(pages, seconds)


if __name__ == "__main__":
    # python bench/_peer.py SHAPE.npy [SHEET] [FACE_MM]
    g = np.load(sys.argv[1])
    print(run_peer(g, float(sys.argv[3]) if len(sys.argv) > 3 else 8.6, sys.argv[2] if len(sys.argv) > 2 else "A4"))
