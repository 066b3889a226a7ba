"""Check a census folder afterwards: every net refolds, every unzipping cuts one path, every proof holds.

This reads only ``census.json`` and the net files.  Nets are refolded by the
project's independent validator (:func:`voxfab.unfold.validate`); an unzipping's
cut edges (the surface edges not in its folds) are rebuilt from the net's 3D
corners and must form one simple path through every corner vertex, counted from
the cubes; each "none" certificate goes to :func:`.check_certificate`.
"""

from __future__ import annotations

import dataclasses
import itertools
import json
from pathlib import Path
from typing import Any

__all__ = ["CensusCheck", "cut_path_problem", "verify_census"]


@dataclasses.dataclass(frozen=True)
class CensusCheck:
    """What :func:`verify_census` checked, and the problems it found (one line each)."""

    nets: int
    unzippings: int
    certificates: int
    problems: tuple[str, ...]


def _corners(cells: list[list[int]]) -> set[tuple[int, int, int]]:
    """Lattice points where 3, 5 or 6 squares of the surface meet, from the cubes alone."""
    filled = {tuple(c) for c in cells}
    out = set()
    for x, y, z in filled:
        for p in itertools.product((x, x + 1), (y, y + 1), (z, z + 1)):
            octs = [(p[0] - a, p[1] - b, p[2] - c) for a, b, c in itertools.product((0, 1), repeat=3)]
            inside = [o in filled for o in octs]
            squares = sum(inside[i] != inside[j] for i, j in itertools.combinations(range(8), 2)
                          if sum(abs(u - v) for u, v in zip(octs[i], octs[j])) == 1)
            if squares not in (0, 4):
                out.add(p)
    return out


def cut_path_problem(cells: list[list[int]], net: Any) -> str | None:
    """Why the net's cut edges are not one simple path through every corner vertex, or None when they are."""
    owners: dict[frozenset, list[int]] = {}
    for i, c3 in enumerate(net.corners3d.tolist()):
        for k in range(4):
            owners.setdefault(frozenset((tuple(c3[k]), tuple(c3[(k + 1) % 4]))), []).append(i)
    folds = {tuple(sorted(p)) for p in net.folds.tolist()}
    cuts = [tuple(e) for e, o in owners.items() if tuple(sorted(o)) not in folds]
    if not cuts:
        return "no edge is cut"
    degree: dict[tuple, int] = {}
    adj: dict[tuple, list[tuple]] = {}
    for p, q in cuts:
        for a, b in ((p, q), (q, p)):
            degree[a] = degree.get(a, 0) + 1
            adj.setdefault(a, []).append(b)
    if max(degree.values()) > 2 or sorted(degree.values()).count(1) != 2 or len(degree) != len(cuts) + 1:
        return "the cut edges do not form one simple path"
    seen, todo = {cuts[0][0]}, [cuts[0][0]]
    while todo:
        for b in adj[todo.pop()]:
            if b not in seen:
                seen.add(b)
                todo.append(b)
    if seen != set(degree):
        return "the cut edges do not form one simple path"
    missed = _corners(cells) - set(degree)
    if missed:
        return f"the cut path misses {len(missed)} corner vertices (e.g. {sorted(missed)[0]})"
    return None


def verify_census(outdir: str | Path) -> CensusCheck:
    """Check every net and certificate a census wrote into ``outdir``."""
    from voxfab.errors import VoxfabError
    from voxfab.unfold import Net, validate

    from ._certificate import check_certificate
    from ._topology import grid_of

    out = Path(outdir)
    data = json.loads((out / "census.json").read_text())
    problems: list[str] = []
    nets = unzippings = certificates = 0
    for rec in data["shapes"]:
        sid, cells = rec["id"], rec["cells"]
        g = grid_of(cells)
        for key, outcome in (("net", rec.get("unfold")), ("unzip_net", rec.get("unzip"))):
            path = rec.get(key)
            if (outcome == "found") != (path is not None):
                problems.append(f"{sid}: {key} is {path!r} for an outcome {outcome!r}")
                continue
            if path is None:
                continue
            try:
                net = Net.from_json((out / path).read_text())
                validate(g, net)
            except (OSError, VoxfabError) as exc:
                problems.append(f"{sid}: {path}: {' '.join(str(exc).split())}")
                continue
            if key == "net":
                nets += 1
                continue
            unzippings += 1
            why = cut_path_problem(cells, net)
            if why:
                problems.append(f"{sid}: {path}: {why}")
        if rec.get("unzip") == "none":
            certificates += 1
            try:
                check_certificate(cells, rec.get("certificate") or {})
            except (ValueError, KeyError, TypeError) as exc:
                problems.append(f"{sid}: certificate: {exc}")
    return CensusCheck(nets, unzippings, certificates, tuple(problems))
