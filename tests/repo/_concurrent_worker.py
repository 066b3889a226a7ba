"""Worker run as a separate process by test_concurrency.py.

Usage: python _concurrent_worker.py DB WORKER COUNT

Prints ``ready``, waits for a line on stdin, then opens the repository (creating
it if needed) and adds: the shared shape, COUNT shapes of its own, the shared
shape again.  Prints one JSON line per add: [name, created].
"""

from __future__ import annotations

import itertools
import json
import sys

import numpy as np

from voxfab.repo import Repository
from voxfab.shape import examples


def own_shape(index: int) -> np.ndarray:
    """Distinct volume-27 shapes: a 1x1x25 column plus two voxels beside it."""
    pair = list(itertools.combinations(range(25), 2))[index]
    g = np.zeros((2, 1, 25), dtype=bool)
    g[0, 0, :] = True
    g[1, 0, list(pair)] = True
    return g


def main() -> None:
    db, worker, count = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    shared = examples.vase()
    mine = [own_shape(worker * count + i) for i in range(count)]
    print("ready", flush=True)
    sys.stdin.readline()
    with Repository(db) as repo:
        results = [repo.add(shared)]
        results += [repo.add(g, meta={"worker": worker, "i": i}) for i, g in enumerate(mine)]
        results.append(repo.add(shared))
    for r in results:
        print(json.dumps([r.name, r.created]), flush=True)


if __name__ == "__main__":
    main()
