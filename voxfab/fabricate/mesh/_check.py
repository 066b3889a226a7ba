"""An independent mesh checker, run before every write.

It looks only at the triangle list, never at how the mesh was made: every edge
in exactly two triangles by vertex index, each directed edge once (consistent
orientation), one fan around every vertex, no degenerate triangle, positive
volume per part, and optionally the exact volume, the bounding box and the
number of bodies.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt

from voxfab.errors import FabricationError

from ._data import MeshData


@dataclasses.dataclass(frozen=True)
class MeshReport:
    """What the checker measured on a mesh that passed.

    Attributes
    ----------
    vertices, triangles : int
        Counts.
    shells : int
        Connected surface components (a cavity adds an inward shell).
    bodies : int
        Shells facing outward: separate solids.
    parts : int
        Parts as labelled in the mesh.
    volume : float
        Enclosed volume in mm³.
    bounds : tuple of tuple of float
        Minimum and maximum corner in mm.
    """

    vertices: int
    triangles: int
    shells: int
    bodies: int
    parts: int
    volume: float
    bounds: tuple[tuple[float, float, float], tuple[float, float, float]]


def _fail(what: str, problem: str, where: npt.NDArray[np.float64] | None = None) -> FabricationError:
    at = ""
    if where is not None and len(where):
        pts = "; ".join("(" + ", ".join(f"{c:g}" for c in p) + ")" for p in np.asarray(where)[:5])
        at = f" near {pts} mm" + (f" and {len(where) - 5} more" if len(where) > 5 else "")
    return FabricationError(f"mesh check failed for {what}: {problem}{at}")


def check_mesh(
    mesh: MeshData,
    *,
    what: str = "mesh",
    expected_volume: float | tuple[float, float] | None = None,
    expected_bounds: npt.ArrayLike | None = None,
    expected_bodies: int | None = None,
    tolerance: float = 1e-6,
) -> MeshReport:
    """Check a mesh edge by edge; raise :class:`FabricationError` on the first problem.

    Parameters
    ----------
    mesh : MeshData
        The mesh to check.
    what : str
        Name used in error messages.
    expected_volume : float or (float, float), optional
        Exact volume in mm³ (relative ``tolerance``) or an inclusive range.
    expected_bounds : (2, 3) array_like, optional
        Expected minimum and maximum corner in mm (absolute ``tolerance`` × size).
    expected_bodies : int, optional
        Required number of outward shells.
    tolerance : float
        Relative tolerance of the volume and bounds comparisons.

    Returns
    -------
    MeshReport
        Counts and measures of the checked mesh.
    """
    v = np.asarray(mesh.vertices, dtype=np.float64)
    t = np.asarray(mesh.triangles)
    nv, nt = v.shape[0], t.shape[0]
    if nt == 0:
        raise _fail(what, "no triangles")
    if v.ndim != 2 or v.shape[1] != 3 or t.ndim != 2 or t.shape[1] != 3:
        raise _fail(what, f"bad array shapes {v.shape} and {t.shape}")
    if not np.isfinite(v).all():
        raise _fail(what, "non-finite vertex coordinates")
    if mesh.part.shape != (nt,):
        raise _fail(what, f"part labels have shape {mesh.part.shape}, expected ({nt},)")
    from ._edges import edge_fan_shells, index_problems, triangle_measures, vertex_bounds

    t = np.ascontiguousarray(t, dtype=np.int64)
    outside, unused, repeats = index_problems(t, nv)
    if outside:
        raise _fail(what, f"triangle indices outside 0..{nv - 1}")
    if unused:
        raise _fail(what, f"{unused} vertices used by no triangle")
    if repeats:
        bad = (t[:, 0] == t[:, 1]) | (t[:, 1] == t[:, 2]) | (t[:, 0] == t[:, 2])
        raise _fail(what, f"{repeats} triangles repeat a vertex", v[t[bad, 0]])
    v = np.ascontiguousarray(v)
    bmin, bmax = vertex_bounds(v)
    # One cross product per triangle serves the area test and the volumes, as
    # cones from the box centre r (well conditioned): det[a-r, b-r, c-r] = (a-r) . ((b-a) x (c-a)).
    tri_vol, area2 = triangle_measures(v, t, (bmin + bmax) / 2.0)
    scale = float((bmax - bmin).max()) or 1.0
    flat = area2 <= (1e-12 * scale * scale)
    if flat.any():
        raise _fail(what, f"{int(flat.sum())} triangles have zero area", v[t[flat, 0]])

    status, labels, n_shells = edge_fan_shells(t, nv)
    if status:
        _edge_and_fan_problems(what, v, t)
        raise _fail(what, f"edge or fan test {status} failed")  # the detailed pass always raises first
    svol = np.bincount(labels, weights=tri_vol, minlength=n_shells)
    bodies = int(np.count_nonzero(svol > 0))
    part = np.asarray(mesh.part)
    n_parts = int(part.max()) + 1
    pvol = np.bincount(part, weights=tri_vol, minlength=n_parts)
    if (pvol <= 0).any():
        raise _fail(what, f"{int((pvol <= 0).sum())} parts enclose no positive volume (inside out?)")
    # A shell belongs to one part only.
    shell_part = np.full(n_shells, -1, dtype=np.int64)
    shell_part[labels] = part
    if not np.array_equal(shell_part[labels], part):
        raise _fail(what, "a connected shell is split between parts")
    total = float(svol.sum())
    if expected_volume is not None:
        if isinstance(expected_volume, tuple):
            lo, hi = expected_volume
            if not (lo * (1 - tolerance) <= total <= hi * (1 + tolerance)):
                raise _fail(what, f"volume {total:.6g} mm³ outside the expected range [{lo:.6g}, {hi:.6g}]")
        elif abs(total - expected_volume) > tolerance * max(abs(expected_volume), 1e-9):
            raise _fail(what, f"volume {total:.9g} mm³, expected {expected_volume:.9g}")
    if expected_bounds is not None:
        eb = np.asarray(expected_bounds, dtype=np.float64)
        if np.abs(np.stack([bmin, bmax]) - eb).max() > tolerance * scale:
            raise _fail(what, f"bounding box {bmin.tolist()}..{bmax.tolist()} mm, expected {eb.tolist()}")
    if expected_bodies is not None and bodies != expected_bodies:
        raise _fail(what, f"{bodies} separate bodies, expected {expected_bodies}")
    return MeshReport(
        vertices=nv,
        triangles=nt,
        shells=n_shells,
        bodies=bodies,
        parts=n_parts,
        volume=total,
        bounds=(tuple(map(float, bmin)), tuple(map(float, bmax))),  # type: ignore[arg-type]
    )


def _edge_and_fan_problems(what: str, v: npt.NDArray[np.float64], t: npt.NDArray[np.int64]) -> None:
    """The edge and fan tests with numpy, raising with the places of the first problem found."""
    nv, nt = v.shape[0], t.shape[0]
    # Every undirected edge must be in exactly two triangles, once in each direction.
    a = t.ravel()
    b = np.roll(t, -1, axis=1).ravel()
    ukey = np.minimum(a, b).astype(np.int64) * nv + np.maximum(a, b)
    order = np.argsort(ukey)
    ks = ukey[order]
    paired = ks.size % 2 == 0 and bool(np.array_equal(ks[0::2], ks[1::2]))
    if paired and ks.size > 2:
        paired = not bool((ks[1:-1:2] == ks[2::2]).any())
    if not paired:
        _, first, counts = np.unique(ks, return_index=True, return_counts=True)
        if (counts > 2).any():
            e = ks[first[counts > 2]]
            raise _fail(what, f"{e.size} edges in more than two triangles", v[e // nv])
        e = ks[first[counts == 1]]
        raise _fail(what, f"{e.size} edges in only one triangle (open or flipped)", v[e // nv])
    h1, h2 = order[0::2], order[1::2]
    same = a[h1] == a[h2]
    if same.any():
        raise _fail(
            what, f"{int(same.sum())} directed edges used twice (inconsistent orientation)", v[a[h1[same]]]
        )
    twin = np.empty(3 * nt, dtype=np.int64)
    twin[h1] = h2
    twin[h2] = h1

    # One fan per vertex: the corners around a vertex must form a single cycle.
    # Half-edge h = 3*tri + j runs t[tri, j] -> t[tri, j+1]; the corner at its start
    # is followed around that vertex by the corner at the end of its twin.  This
    # is a permutation of the corners; its cycles are the fans, labelled by their
    # smallest corner through pointer doubling (a cycle is no longer than the
    # number of corners at its vertex).
    nxt = (twin // 3) * 3 + (twin % 3 + 1) % 3
    lab = np.arange(3 * nt)
    longest = int(np.bincount(a, minlength=nv).max())
    step = 1
    while step < longest:
        lab = np.minimum(lab, lab[nxt])
        nxt = nxt[nxt]
        step *= 2
    n_fans = int(np.count_nonzero(lab == np.arange(3 * nt)))
    if n_fans != nv:
        fan_vertex = a[lab == np.arange(3 * nt)]
        multi = np.bincount(fan_vertex, minlength=nv) > 1
        raise _fail(what, f"{int(multi.sum())} vertices joined by more than one fan (pinched)", v[multi])
