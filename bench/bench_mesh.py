"""Benchmark of voxfab.fabricate.mesh against a manifold3d union of cubes, with size limits.

Run ``python bench/bench_mesh.py``.  Each case runs in a fresh subprocess so its
peak resident memory (``ru_maxrss``) is its own.  Goals (issue 4):

* at least 100x faster than a manifold3d union of unit cubes on a 25³ random blob;
  (cases report the best of 10 runs after a warm-up run, the checkerboards of 5, the 256³ shell
  of 2; the union, which takes seconds, runs once)
* a 25³ worst case under 100 ms: the 3D checkerboard (the most faces) kept split, the same
  with default options (cavities filled, contacts bridged), and random noise (half full,
  thousands of bridges); the checkerboard unfilled with every contact bridged is reported
  beside them as the extreme;
* a 256³ one-voxel sphere shell under 5 s and 2 GB;
* random noise at 256³ refused with a clear error before memory runs out.

``--smoke`` runs every case, all in one subprocess, on small inputs (a 10³ blob, a 40³ shell) and
once each: seconds in all.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time

CASES = [
    "cubes_union", "blob", "blob_split", "checker", "checker_default", "noise25", "checker_bridge", "shell256",
    "noise256",
]


def _shell(n: int = 256, r: float = 120.0):
    import numpy as np
    from scipy import ndimage

    c = np.arange(n) - (n - 1) / 2
    d = np.sqrt(c[:, None, None] ** 2 + c[None, :, None] ** 2 + c[None, None, :] ** 2)
    ball = d <= r
    # One voxel thick and face-connected: ball voxels with an outside voxel among their 26 neighbours.
    return ball & ~ndimage.binary_erosion(ball, np.ones((3, 3, 3), bool))


def run_case(name: str, smoke: bool = False) -> dict[str, object]:
    import numpy as np

    from voxfab.errors import VoxfabError
    from voxfab.fabricate.mesh import build_mesh, check_mesh, voxel_mesh
    from voxfab.shape import examples

    blob = examples.random_shape(0, side=10) if smoke else examples.random_shape(0)
    runs = {"blob": 1 if smoke else 10, "checker": 1 if smoke else 5, "shell": 1 if smoke else 2}
    out: dict[str, object] = {"case": name}
    if name == "cubes_union":
        import manifold3d as m3d

        cubes = [m3d.Manifold.cube((1.0, 1.0, 1.0)).translate(tuple(map(float, p))) for p in np.argwhere(blob)]
        t = time.perf_counter()
        u = m3d.Manifold.batch_boolean(cubes, m3d.OpType.Add)
        tris = u.num_tri()  # the union is lazy: this forces it
        out.update(seconds=time.perf_counter() - t, triangles=tris, voxels=int(blob.sum()), volume=u.volume())
        return out
    if name in ("blob", "blob_split"):
        mode = "bridge" if name == "blob" else "split"
        build_mesh(blob, contacts=mode)  # warm-up: imports and compiled kernels load on the first call
        times = []
        for _ in range(runs["blob"]):
            t = time.perf_counter()
            r = build_mesh(blob, contacts=mode)
            times.append(time.perf_counter() - t)
        out.update(seconds=min(times), triangles=r.report.triangles, voxels=int(blob.sum()),
                   bodies=r.report.bodies, bridges=r.bridges, volume=r.report.volume)
        return out
    if name in ("checker", "checker_default", "checker_bridge", "noise25"):
        if name == "noise25":
            g = np.random.default_rng(1).random((25, 25, 25)) < 0.5
        else:
            g = np.indices((25, 25, 25)).sum(axis=0) % 2 == 0
        options = {
            "checker": dict(fill=False, contacts="split"),  # the most faces a 25³ grid can have
            "checker_default": {},  # default options: cavities filled, contacts bridged
            "noise25": {},
            "checker_bridge": dict(fill=False),  # every one of its 43200 edge contacts bridged
        }[name]
        build_mesh(g, **options)  # warm-up
        times = []
        for _ in range(runs["checker"]):
            t = time.perf_counter()
            r = build_mesh(g, **options)
            times.append(time.perf_counter() - t)
        out.update(seconds=min(times), triangles=r.report.triangles, bodies=r.report.bodies, bridges=r.bridges)
        return out
    if name == "shell256":
        g = _shell(40, 18.0) if smoke else _shell()
        times = []
        for _ in range(runs["shell"]):
            t = time.perf_counter()
            r = build_mesh(g, fill=False)
            times.append(time.perf_counter() - t)
        plain = voxel_mesh(g, merge=False)
        check_mesh(plain)
        out.update(seconds=min(times), triangles=r.report.triangles, unmerged_triangles=len(plain.triangles),
                   voxels=int(g.sum()), contacts=r.contacts, shells=r.report.shells)
        return out
    if name == "noise256":
        g = np.random.default_rng(0).random((256, 256, 256)) < 0.5
        t = time.perf_counter()
        try:
            build_mesh(g)
            out.update(error="none (no refusal!)")
        except VoxfabError as exc:
            out.update(error=f"{type(exc).__name__}: {exc}")
        out.update(seconds=time.perf_counter() - t)
        return out
    raise SystemExit(f"unknown case {name}")


def main() -> None:
    smoke = "--smoke" in sys.argv[1:]
    if len(sys.argv) >= 3 and sys.argv[1] == "--case":
        import resource

        for name in sys.argv[2].split(","):
            res = run_case(name, smoke)
            res["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
            print(json.dumps(res), flush=True)
        return
    results, failed = {}, []
    # Each case in a process of its own, so that its peak memory is its own; the smoke run's small cases share
    # one process (one interpreter start-up, not nine), their peaks the largest so far.
    for cases in [",".join(CASES)] if smoke else CASES:
        run = subprocess.run([sys.executable, __file__, "--case", cases, *(["--smoke"] if smoke else [])],
                             capture_output=True, text=True)
        if run.returncode != 0:
            print(f"{cases}: failed\n{run.stderr[-2000:]}")
            failed += cases.split(",")
            continue
        for line in run.stdout.strip().splitlines():
            if line.startswith("{"):
                res = json.loads(line)
                results[res["case"]] = res
    print(f"{'case':<16}{'seconds':>10}{'peak MB':>10}{'triangles':>11}  notes")
    for case, r in results.items():
        notes = {k: v for k, v in r.items() if k not in ("case", "seconds", "peak_rss_mb", "triangles")}
        print(f"{case:<16}{r['seconds']:>10.3f}{r['peak_rss_mb']:>10.0f}{r.get('triangles', ''):>11}  {notes}")
    if "cubes_union" in results and "blob" in results:
        u, b, s = results["cubes_union"], results["blob"], results.get("blob_split", {})
        print(f"\nspeed-up over the manifold3d union of cubes: {u['seconds'] / b['seconds']:.0f}x with bridges, "
              f"{u['seconds'] / s.get('seconds', float('nan')):.0f}x split (goal >= 100x)")
    worst = [(c, results[c]) for c in ("checker", "checker_default", "noise25") if c in results]
    if worst:
        print("25³ worst cases (goal < 100 ms): " + ", ".join(f"{c} {r['seconds'] * 1000:.0f} ms" for c, r in worst))
    if "checker_bridge" in results:
        r = results["checker_bridge"]
        print(f"unfilled checkerboard with all {r['bridges']} contacts bridged: {r['seconds'] * 1000:.0f} ms")
    if "shell256" in results:
        r = results["shell256"]
        side = "40³" if smoke else "256³"
        print(f"{side} shell: {r['seconds']:.2f} s, {r['peak_rss_mb']:.0f} MB peak (goals < 5 s, < 2048 MB)")
    if "noise256" in results:
        r = results["noise256"]
        print(f"256³ noise: refused in {r['seconds']:.2f} s at {r['peak_rss_mb']:.0f} MB peak")
    if failed:
        sys.exit(f"{len(failed)} cases failed: {', '.join(failed)}")


if __name__ == "__main__":
    main()
