"""Check a census folder afterwards: every net refolds, every unzipping cuts one path, every proof holds.

This reads only ``census.json`` and the net files.  Nets are refolded by the
project's independent validator (:func:`voxfab.unfold.validate`), and each net
file's ``tree`` must be a spanning tree of its folds (F - 1 of them, connected,
no cycle); an unzipping's cut edges (the surface edges not in its folds) are
rebuilt from the net's 3D corners and must form one simple path through every
corner vertex, counted from the cubes; each "none" certificate goes to
:func:`.check_certificate`.  A resumed census keeps a record only when
:func:`record_problems` finds none.
"""

from __future__ import annotations

import dataclasses
import itertools
import json
import re
from pathlib import Path
from typing import Any

__all__ = ["CensusCheck", "cut_path_problem", "record_problems", "tree_problem", "verify_census"]


@dataclasses.dataclass(frozen=True)
class CensusCheck:
    """What :func:`verify_census` checked, and the problems it found (one line each)."""

    nets: int
    unzippings: int
    certificates: int
    problems: tuple[str, ...]


#: The 8 cells round a lattice point, as offsets down from it, and the 12 pairs of them that share a face.
_OCTANTS = list(itertools.product((0, 1), repeat=3))
_FACE_PAIRS = [(i, j) for i, j in itertools.combinations(range(8), 2)
               if sum(abs(u - v) for u, v in zip(_OCTANTS[i], _OCTANTS[j])) == 1]


def _corners(cells: list[list[int]]) -> set[tuple[int, int, int]]:
    """Lattice points where 3, 5 or 6 squares of the surface meet, from the cubes alone."""
    filled = {tuple(c) for c in cells}
    points = {(x + a, y + b, z + c) for x, y, z in filled for a, b, c in _OCTANTS}
    out = set()
    for p in points:
        inside = [(p[0] - a, p[1] - b, p[2] - c) in filled for a, b, c in _OCTANTS]
        squares = sum(inside[i] != inside[j] for i, j in _FACE_PAIRS)
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


def tree_problem(net: Any, tree: object) -> str | None:
    """Why ``tree`` is not a spanning tree of the net's folds (F - 1 folds, connected, no cycle), or None."""
    f = net.face_count
    if not isinstance(tree, list) or not all(isinstance(p, list) and len(p) == 2 for p in tree):
        return "no fold tree (tree: a list of face pairs)"
    if len(tree) != f - 1:
        return f"its fold tree has {len(tree)} folds for {f} squares, not {f - 1}"
    folds = {tuple(sorted(p)) for p in net.folds.tolist()}
    root = list(range(f))

    def find(a: int) -> int:
        while root[a] != a:
            root[a] = root[root[a]]
            a = root[a]
        return a

    for a, b in tree:
        if not all(type(v) is int and 0 <= v < f for v in (a, b)):
            return f"its fold tree names a square {str([a, b])[:40]} that is not one of its {f}"
        if (min(a, b), max(a, b)) not in folds:
            return f"its fold tree joins squares {a} and {b}, which no fold joins"
        ra, rb = find(a), find(b)
        if ra == rb:
            return f"its fold tree has a cycle through squares {a} and {b}"
        root[ra] = rb
    return None  # F - 1 edges without a cycle on F squares: connected


#: A census id: two digits of n, six of the index from 1.
SHAPE_ID = re.compile(r"[0-9]{2}-[0-9]{6}")  # fullmatch: no other digits, no line end
_OUTCOMES = ("found", "none", "undecided")


def record_problems(out: Path, rec: dict[str, Any], cells: list[list[int]] | None = None,
                    square_zipper: bool | None = None) -> tuple[list[str], tuple[int, int, int]]:
    """The problems of one census record and its files, and the nets, unzippings and certificates it checked.

    ``cells``, when given, are the polycube the record's id names (from the enumeration); ``square_zipper``
    whether the census searched that zipper.
    """
    from voxfab.errors import VoxfabError
    from voxfab.unfold import Net, validate
    from voxfab.unfold._hunt import HUNT_ZIPPER

    from ._certificate import check_certificate
    from ._task import net_paths
    from ._topology import SURFACE_KINDS, grid_of

    sid = rec.get("id")
    if not isinstance(sid, str) or not SHAPE_ID.fullmatch(sid):
        return [f"{str(sid)[:40]!r}: not a census id (NN-NNNNNN)"], (0, 0, 0)
    if "error" in rec:
        return [f"{sid}: an error, not an answer"], (0, 0, 0)
    got = rec.get("cells")
    if cells is not None and got != cells:
        return [f"{sid}: its cells are not those of polycube {sid}"], (0, 0, 0)
    try:
        g = grid_of(got)
    except (VoxfabError, TypeError, ValueError):
        return [f"{sid}: its cells are not a polycube"], (0, 0, 0)
    problems: list[str] = []
    if rec.get("n") != int(sid[:2]) or len(got) != int(sid[:2]):
        problems.append(f"{sid}: n is {rec.get('n')!r} for {len(got)} cubes")
    surface = rec.get("surface")
    if surface not in SURFACE_KINDS:
        problems.append(f"{sid}: surface {str(surface)[:40]!r} is no surface kind")
    if rec.get("unfold") not in _OUTCOMES:
        problems.append(f"{sid}: unfold {str(rec.get('unfold'))[:40]!r} is not one of {', '.join(_OUTCOMES)}")
    unzips = _OUTCOMES if surface == "manifold" else (None,)
    if rec.get("unzip") not in unzips:
        problems.append(f"{sid}: unzip {str(rec.get('unzip'))[:40]!r} for a surface {str(surface)[:40]!r}")
    if square_zipper is not None:
        zipped = HUNT_ZIPPER[:3] if square_zipper else ("skipped",)
        if rec.get("square_zipper") not in zipped:
            problems.append(f"{sid}: square_zipper {str(rec.get('square_zipper'))[:40]!r}")
    nets = unzippings = certificates = 0
    for key, outcome, expected in (("net", rec.get("unfold"), net_paths(sid)[0]),
                                   ("unzip_net", rec.get("unzip"), net_paths(sid)[1])):
        path = rec.get(key)
        if (outcome == "found") != (path is not None):
            problems.append(f"{sid}: {key} is {str(path)[:80]!r} for an outcome {str(outcome)[:40]!r}")
            continue
        if path is None:
            continue
        if path != expected:  # never a file outside DIR/nets, nor another shape's
            problems.append(f"{sid}: {key} is {str(path)[:80]!r}, not {expected}")
            continue
        try:
            data = json.loads((out / path).read_text())
            net = Net.from_dict(data)
            validate(g, net)
        except OSError as exc:  # missing, a folder, unreadable
            problems.append(f"{sid}: {path}: {exc.strerror or exc}")
            continue
        except RecursionError:
            problems.append(f"{sid}: {path}: nested too deep for a net")
            continue
        except (ValueError, VoxfabError) as exc:  # not JSON, not a net, not a net of this polycube
            problems.append(f"{sid}: {path}: {' '.join(str(exc).split())[:200]}")
            continue
        why = tree_problem(net, data.get("tree"))
        if why is None and key == "unzip_net":
            why = cut_path_problem(got, net)
        if why:
            problems.append(f"{sid}: {path}: {why}")
            continue
        if key == "net":
            nets += 1
        else:
            unzippings += 1
    if rec.get("unzip") == "none":
        certificates += 1
        cert = rec.get("certificate")
        try:
            if not isinstance(cert, dict):
                raise TypeError(f"expected an object, got {str(cert)[:40]!r}")
            check_certificate(got, cert)
        except (ValueError, KeyError, TypeError, IndexError) as exc:
            problems.append(f"{sid}: certificate: {' '.join(str(exc).split())[:200]}")
    return problems, (nets, unzippings, certificates)


def verify_census(outdir: str | Path) -> CensusCheck:
    """Check every net and certificate a census wrote into ``outdir``."""
    out = Path(outdir)
    data = json.loads((out / "census.json").read_text())
    problems: list[str] = []
    nets = unzippings = certificates = 0
    for rec in data["shapes"]:
        found, (a, b, c) = record_problems(out, rec)
        problems += found
        nets, unzippings, certificates = nets + a, unzippings + b, certificates + c
    return CensusCheck(nets, unzippings, certificates, tuple(problems))
