"""Benchmark of ``voxfab studio``: preview latency at 25³ and the time of a gallery of 8 nets.

Run ``python bench/bench_studio.py [--strokes N] [--nets N] [--no-browser] [--smoke]``.  It starts a real
``voxfab studio`` server on 127.0.0.1 and measures:

* the preview round trip (POST ``/api/preview``, digitizing through the recipe path, 25³ bits
  back) for typed, drawn and bitmap sources, after a warm-up that pays imports and numba caches;
* in headless Chromium (when installed), the time from the end of a mouse stroke on the
  generatrix canvas to the redrawn 3D view, as the page itself measures it;
* a gallery of distinct nets (POST ``/api/nets``) of the default vase and of a slim column.

``--smoke``: one preview per case, one stroke in the browser, galleries of 2 nets.
Medians over runs; on a shared, busy machine the figures move: say so when quoting them.
"""

from __future__ import annotations

import argparse
import base64
import io
import json
import os
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _post(url: str, body: dict) -> dict:
    req = urllib.request.Request(url, data=json.dumps(body).encode(), headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(req, timeout=300) as r:
        return json.loads(r.read())


def _get(url: str) -> dict:
    with urllib.request.urlopen(url, timeout=300) as r:
        return json.loads(r.read())


def _png() -> str:
    from PIL import Image, ImageDraw

    im = Image.new("L", (100, 100), 255)
    ImageDraw.Draw(im).ellipse((10, 10, 90, 90), fill=0)
    buf = io.BytesIO()
    im.save(buf, format="PNG")
    return base64.b64encode(buf.getvalue()).decode()


def _stroke(i: int) -> dict:
    """A vase-like open generatrix, a little different each time (as strokes are)."""
    bulge = 60 + 7 * (i % 9)
    pts = [[20, 0], [70, 2], [bulge + 30, 60], [45 + i % 5, 140], [80, 200 + i % 7], [20, 255]]
    return {"kind": "drawn", "polylines": [{"points": pts, "closed": False}]}


def _median_ms(samples: list[float]) -> str:
    return f"median {1000 * statistics.median(samples):.0f} ms, max {1000 * max(samples):.0f} ms (n={len(samples)})"


def preview_latency(url: str, runs: int) -> None:
    circle = {"kind": "expr", "text": "x^2 + y^2 = 1"}
    disk = {"kind": "bitmap", "data": _png()}
    cases = {
        "typed x = g(y)": lambda i: {"curve": circle, "generatrix": {"kind": "expr",
                                                                     "text": f"x = 0.6 + 0.{i % 9 + 1}*sin(3*y)"}},
        "drawn generatrix": lambda i: {"curve": circle, "generatrix": _stroke(i), "axis": 20},
        "bitmap curve, drawn generatrix": lambda i: {"curve": disk, "generatrix": _stroke(i), "axis": 20},
    }
    for name, make in cases.items():
        for i in range(3):  # warm-up: imports, numba caches
            _post(f"{url}/api/preview", {"maker": "revolution", **make(i)})
        total, server = [], []
        for i in range(runs):
            t0 = time.perf_counter()
            r = _post(f"{url}/api/preview", {"maker": "revolution", **make(i)})
            total.append(time.perf_counter() - t0)
            server.append(r["ms"] / 1000)
        print(f"preview 25³, {name}: round trip {_median_ms(total)}; digitizing {_median_ms(server)}")


def browser_latency(url: str, strokes: int) -> None:
    chromium, driver_path = shutil.which("chromium"), shutil.which("chromedriver")
    if not chromium or not driver_path:
        print("browser: chromium or chromedriver missing, skipped")
        return
    from selenium import webdriver
    from selenium.webdriver import ActionChains

    opts = webdriver.ChromeOptions()
    opts.binary_location = chromium
    for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--window-size=1400,1000"):
        opts.add_argument(arg)
    d = webdriver.Chrome(options=opts, service=webdriver.ChromeService(executable_path=driver_path))
    try:
        d.get(url + "/")
        end = time.monotonic() + 30
        while not d.find_element("id", "latency").get_attribute("data-count") and time.monotonic() < end:
            time.sleep(0.05)
        d.find_element("css selector", '#src-generatrix input[value="drawn"]').click()
        canvas = d.find_element("css selector", "#src-generatrix canvas")
        samples = []
        for i in range(strokes + 2):
            d.find_element("css selector", "#src-generatrix button.clear").click()
            count = int(d.find_element("id", "latency").get_attribute("data-count") or 0)
            pts = [(22, 265), (90 + 3 * (i % 5), 262), (120, 220), (70, 150), (60 + i % 4, 110), (110, 40), (22, 15)]
            chain = ActionChains(d, duration=10)
            chain.move_to_element_with_offset(canvas, pts[0][0] - 138, pts[0][1] - 138).click_and_hold()
            for (xa, ya), (xb, yb) in zip(pts, pts[1:]):
                chain.move_by_offset(xb - xa, yb - ya)
            chain.release().perform()
            end = time.monotonic() + 30
            while int(d.find_element("id", "latency").get_attribute("data-count") or 0) <= count:
                if time.monotonic() > end:
                    raise RuntimeError("no preview after the stroke")
                time.sleep(0.02)
            if i >= 2:  # the first strokes warm the drawn-curve path up
                samples.append(int(d.find_element("id", "latency").get_attribute("data-ms")) / 1000)
        print(f"preview in the browser, stroke end to redrawn 3D view: {_median_ms(samples)}")
    finally:
        d.quit()


def gallery(url: str, count: int, shape: str, spec: dict, timeout: float) -> None:
    r = _post(f"{url}/api/preview", spec)
    t0 = time.perf_counter()
    job = _post(f"{url}/api/nets", {"grid": r["grid"], "count": count, "seed": 0,
                                        "options": {"timeout": timeout}})["job"]
    while True:
        s = _get(f"{url}/api/jobs/{job}")
        if s["state"] != "running":
            break
        time.sleep(0.1)
    wall = time.perf_counter() - t0
    if s["state"] != "done":
        print(f"gallery of {count} nets, {shape}: {s['message']}")
        return
    res = s["result"]
    faces = res["nets"][0]["faces"] if res["nets"] else 0
    print(f"gallery of {count} nets, {shape} ({r['facts']['volume']} voxels, {faces} faces): {res['found']} "
          f"distinct nets in {wall:.1f} s wall ({res['seconds']:.1f} s search and validation, "
          f"{res['options']['face_size']:g} mm faces)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--strokes", type=int, default=20, help="preview runs per case (default 20)")
    ap.add_argument("--nets", type=int, default=8, help="nets in the gallery (default 8)")
    ap.add_argument("--no-browser", action="store_true", help="skip the headless Chromium measurement")
    ap.add_argument("--timeout", type=float, default=5.0, help="seconds per net, as the page's default (5)")
    ap.add_argument("--only", choices=["preview", "gallery"], help="run one part only")
    ap.add_argument("--smoke", action="store_true", help="1 preview per case, 1 stroke, 2 nets per gallery")
    args = ap.parse_args()
    if args.smoke:
        args.strokes, args.nets = 1, 2
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    folder = Path(tempfile.mkdtemp(prefix="bench-studio-"))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.Popen([sys.executable, "-m", "voxfab", "studio", "--port", str(port), "--repo",
                             str(folder / "repo.sqlite"), "--no-browser"], env=env, stdout=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}"
    try:
        end = time.monotonic() + 30
        while True:
            try:
                _get(f"{url}/api/info")
                break
            except OSError:
                if time.monotonic() > end:
                    raise
                time.sleep(0.1)
        if args.only != "gallery":
            preview_latency(url, args.strokes)
            if not args.no_browser:
                browser_latency(url, args.strokes)
        if args.only == "preview":
            return
        circle = {"kind": "expr", "text": "x^2 + y^2 = 1"}
        gallery(url, args.nets, "slim column", {"maker": "revolution", "curve": circle,
                                                "generatrix": {"kind": "expr", "text": "x = 0.12"}}, args.timeout)
        gallery(url, args.nets, "default vase", {"maker": "revolution", "curve": circle,
                                                 "generatrix": {"kind": "expr", "text": "x = 0.6 + 0.3*sin(3*y)"}},
                args.timeout)
    finally:
        proc.terminate()
        proc.wait(10)
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main()
