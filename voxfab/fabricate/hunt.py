"""The hunt output: does a shape have a one-piece net, and a zipper net?  (``[outputs.hunt]``)

It writes ``hunt.json`` (what :func:`voxfab.unfold.hunt_shape` found), and the
nets it found: ``hunt-net.json`` (a one-piece net) and ``hunt-zipper.json`` (a
net whose cut edges form one path).  Over a repository range it is the hunt
of a batch run (``voxfab batch --outputs hunt.toml``), whose index counts the
outcomes.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path
from typing import Any

from voxfab._shared.options import Options, option

from ._outputs import Artefact, OutputFile

__all__ = ["HUNT_FORMAT", "HuntOptions", "fabricate_hunt", "read_hunt"]

HUNT_FORMAT = "voxfab-hunt/1"
#: Longest time limit of one search, seconds.
MAX_HUNT_TIMEOUT = 3600.0


@dataclasses.dataclass(frozen=True)
class HuntOptions(Options):
    """The time limits of a hunt's three searches, declared once (recipe keys, checks, README table)."""

    timeout: float = option(10.0, help="random engine's budget for a one-piece net", unit="s", low=0.0,
                            low_open=True, high=MAX_HUNT_TIMEOUT, cli=False)
    exact_timeout: float = option(10.0, help="exact search's budget for a one-piece net, when the random "
                                  "engine found none", unit="s", low=0.0, low_open=True, high=MAX_HUNT_TIMEOUT,
                                  cli=False)
    zipper: bool = option(True, help="also look for a zipper net (cut edges forming one path)", cli=False)
    zipper_timeout: float = option(2.0, help="exact zipper search's budget", unit="s", low=0.0, low_open=True,
                                   high=MAX_HUNT_TIMEOUT, cli=False)


def fabricate_hunt(shape: Any, options: HuntOptions, outdir: Path, *, name: str, seed: int) -> Artefact:
    """Hunt ``shape``'s nets and write ``hunt.json`` and the nets found into ``outdir``.

    Parameters
    ----------
    shape : VoxelShape
    options : HuntOptions
    outdir : Path
    name : str
        Recorded in ``hunt.json``.
    seed : int
        The random engine's seed.

    Returns
    -------
    Artefact
        ``report`` holds ``hunt.json``'s values and the searches' times;
        ``gives["hunt_net"]`` and ``gives["zipper_net"]`` the nets found (None: none).
    """
    from voxfab._shared.atomic import write_text
    from voxfab.unfold import hunt_shape

    outcome = hunt_shape(shape.grid, seed=seed, timeout=options.timeout, exact_timeout=options.exact_timeout,
                         zipper_timeout=options.zipper_timeout, zipper=options.zipper)
    record = {"format": HUNT_FORMAT, "name": name, "seed": seed, **outcome.to_dict()}
    outdir.mkdir(parents=True, exist_ok=True)
    write_text(outdir / "hunt.json", json.dumps(record, indent=1, sort_keys=True) + "\n")
    files = [OutputFile("hunt.json", "the hunt's outcome: one-piece net (random, exact, none, undecided) and "
                                     "zipper net (found, none, undecided)")]
    for file, net, what in (("hunt-net.json", outcome.one_piece, "a one-piece net the hunt found"),
                            ("hunt-zipper.json", outcome.zipper_net, "a zipper net: its cut edges form one path")):
        if net is not None:
            write_text(outdir / file, net.to_json())
            files.append(OutputFile(file, what))
    report = dict(record, seconds=[round(s, 3) for s in outcome.seconds])
    return Artefact(tuple(files), (), report,
                    gives={"hunt_net": outcome.one_piece, "zipper_net": outcome.zipper_net})


def read_hunt(path: Path) -> dict[str, Any] | None:
    """The values of a ``hunt.json``, or None when the file is missing or is not one."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("format") != HUNT_FORMAT:
        return None
    return data
