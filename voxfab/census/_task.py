"""The census of one polycube: its surface, an edge unfolding and an edge-unzipping.

* **Edge unfolding, unit-square model** (every unit square a face of the net,
  the folds a spanning tree of the squares): the project's hunt step
  (:func:`voxfab.unfold.hunt_shape`), the random engine first and the exact
  CP-SAT strategy when it fails, which finds a net or proves that none exists.
* **Edge-unzipping, the paper's model** (:func:`voxfab.census.unzip`), on
  polycubes whose surface is a 2-manifold of genus 0; the others are listed by
  their surface kind and not unzipped.
* **Unit-square zipper** (``voxfab net --zipper``: the cut path visits every
  vertex, flat ones too), from the same hunt step, for comparison.

Each search has its own time limit; one that runs out is ``undecided``, never an
answer; one that is interrupted (a cancel, Ctrl-C) is no record at all.  A worker
writes the nets it finds under ``DIR/nets/`` (each file under a temporary name,
then renamed) and returns a small JSON record.

A net file is a ``voxfab-net/1`` net whose ``folds`` are every uncut edge (a
spanning tree of the squares, plus the edges whose two squares meet in the
plane anyway, which the validator requires; an unzipping's uncut edges close up
round the flat vertices its path leaves out), plus ``tree``: the fold tree, the
F - 1 folds the net is folded along (:func:`voxfab.unfold.fold_tree`).
"""

from __future__ import annotations

import dataclasses
import time
from pathlib import Path
from typing import Any

import numpy as np

from voxfab._shared.options import SeedOptions, option

__all__ = ["CensusSettings", "CensusTask", "census_shape", "census_task", "fold_tree_pairs", "net_paths", "net_text"]

#: Folder of DIR holding the nets.
NETS = "nets"


@dataclasses.dataclass(frozen=True)
class CensusSettings(SeedOptions):
    """The searches' seed and limits, declared once for the library and the CLI.

    They are part of a census's identity: a resumed run keeps only the records
    made with the same settings.
    """

    timeout: float = option(10.0, help="seconds for each search of one polycube (random engine, exact strategy, "
                            "unzipping, unit-square zipper); one that runs out is undecided",
                            unit="s", low=0, low_open=True, high=3600)
    square_zipper: bool = option(False, help="also search each polycube's unit-square zipper (the cut path "
                                 "through every vertex, as voxfab net --zipper)")

    def to_dict(self) -> dict[str, Any]:
        return {"seed": self.seed, "timeout": self.timeout, "square_zipper": self.square_zipper}


@dataclasses.dataclass(frozen=True)
class CensusTask:
    """A chunk of polycubes for one worker: ``(id, n, cells)`` each, the output folder and the settings."""

    shapes: tuple[tuple[str, int, tuple[tuple[int, int, int], ...]], ...]
    outdir: str
    settings: CensusSettings


def net_paths(shape_id: str) -> tuple[str, str]:
    """Paths relative to DIR of a shape's unfolding and unzipping nets."""
    return f"{NETS}/{shape_id}.net.json", f"{NETS}/{shape_id}.unzip.json"


def fold_tree_pairs(net: Any) -> list[list[int]]:
    """The net's fold tree as sorted face pairs: F - 1 of its folds, one parent per face but the root."""
    from voxfab.unfold import fold_tree

    _, parent, order = fold_tree(net)
    return sorted(sorted((int(parent[f]), int(f))) for f in order[1:])


def net_text(net: Any) -> str:
    """A census net file: the net's ``voxfab-net/1`` JSON with its fold tree as ``tree``."""
    import json

    text = net.to_json().rstrip()
    return f'{text[:-1]}, "tree": {json.dumps(fold_tree_pairs(net))}}}\n'


def census_shape(shape_id: str, cells: Any, outdir: str | Path | None, settings: CensusSettings) -> dict[str, Any]:
    """Census one polycube; write its nets under ``outdir`` (none when ``outdir`` is None).

    Returns
    -------
    dict
        ``id``, ``n``, ``cells``, ``surface``, ``unfold``, ``unzip``, ``net``,
        ``unzip_net``, ``square_zipper``, and ``certificate`` or ``why`` where they
        apply, plus ``seconds`` and ``cpu_seconds`` (taken out of the report's shapes: times vary).
    """
    from voxfab._shared.atomic import write_text
    from voxfab.unfold import hunt_shape

    from ._topology import grid_of, topology
    from ._unzip import unzip

    start, cpu = time.perf_counter(), time.process_time()
    c = np.asarray(cells, dtype=np.int64).reshape(-1, 3)
    g = grid_of(c)
    topo = topology(g)
    hunt = hunt_shape(g, seed=settings.seed, timeout=settings.timeout, exact_timeout=settings.timeout,
                      zipper_timeout=settings.timeout, zipper=settings.square_zipper)
    unfold = {"random": "found", "exact": "found"}.get(hunt.net, hunt.net)
    net_file, unzip_file = net_paths(shape_id)
    record: dict[str, Any] = {
        "id": shape_id, "n": int(c.shape[0]), "cells": c.tolist(), "surface": topo.kind,
        "corners": list(topo.corners), "flats": list(topo.flats),
        "unfold": unfold, "unfold_by": hunt.net if unfold == "found" else None,
        "net": net_file if hunt.one_piece is not None else None,
        "square_zipper": hunt.zipper,
    }
    why = list(hunt.why)
    if outdir is not None and hunt.one_piece is not None:
        write_text(Path(outdir) / net_file, net_text(hunt.one_piece))
    if topo.kind == "manifold":
        found = unzip(g, timeout=settings.timeout)
        record["unzip"] = found.outcome
        record["unzip_net"] = unzip_file if found.net is not None else None
        if found.net is not None:
            record["unzip_path"] = [list(p) for p in found.path]
            if outdir is not None:
                write_text(Path(outdir) / unzip_file, net_text(found.net))
        if found.certificate is not None:
            record["certificate"] = found.certificate
        if found.why:
            why.append(found.why)
    else:
        record["unzip"] = None  # outside the paper's model: counted by its surface kind
        record["unzip_net"] = None
    if why:
        record["why"] = why
    record["seconds"] = time.perf_counter() - start
    record["cpu_seconds"] = time.process_time() - cpu
    return record


def census_task(task: CensusTask) -> tuple[list[dict[str, Any]], str]:
    """Census every shape of a task; return the records and the worker's name."""
    import socket

    from voxfab.errors import CancelledError, VoxfabError

    try:
        from distributed import get_worker

        worker = get_worker().name
    except (ImportError, ValueError):
        worker = f"{socket.gethostname()}:serial"
    out = []
    for shape_id, _, cells in task.shapes:
        try:
            out.append(census_shape(shape_id, cells, task.outdir, task.settings))
        except CancelledError:
            raise  # an interrupted search is no answer: the shape stays to do
        except VoxfabError as exc:  # a shape the searches refuse is recorded, never a lost chunk
            out.append({"id": shape_id, "n": len(cells), "cells": [list(p) for p in cells], "error":
                        " ".join(str(exc).split())})
    return out, str(worker)
