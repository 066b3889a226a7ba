"""The net job, once for every front end: search, validation and files.

``voxfab net`` (:func:`net_files`), the recipe output ``net``
(:func:`voxfab.fabricate.netdraw.fabricate_net`) and the studio
(:func:`._gallery.net_gallery`, then ``fabricate_net`` with the net chosen)
all search with :func:`search_nets` and validate with
:func:`voxfab.unfold.validate` before a file is written, so the same shape,
options and seed give the same files whichever way they were asked for.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from voxfab.errors import InvalidShapeError, UnknownFormatError

from ._net_options import NetOptions, SheetNets
from ._options import DrawingOptions

if TYPE_CHECKING:
    from voxfab.unfold import EdgeConstraints, Net

_BOX = re.compile(r"\s*([0-9]+(?:\.[0-9]*)?)\s*[xX×]\s*([0-9]+(?:\.[0-9]*)?)\s*")  # ASCII digits, matched whole


def parse_box(text: str | None, face_size: float | None) -> tuple[int, int] | None:
    """A ``WxH`` box for JSON nets in faces: voxels, or mm when the face size is known (``--fit``/``--box``)."""
    if text is None:
        return None
    m = _BOX.fullmatch(text)
    if not m:
        raise InvalidShapeError(f"--fit: expected WxH such as 40x30, got {text!r}")
    w, h = float(m.group(1)), float(m.group(2))
    if face_size is not None:
        box = math.floor(w / face_size + 1e-9), math.floor(h / face_size + 1e-9)
        if min(box) < 1:  # in mm: say so, not "0x0" faces the user never wrote
            raise InvalidShapeError(f"--fit: {text} mm holds no {face_size:g} mm face; give a box at least "
                                    f"{face_size:g}x{face_size:g} mm, or smaller faces")
        return box
    if w != int(w) or h != int(h):
        raise InvalidShapeError(f"--fit: whole voxels expected without a face size, got {text!r}")
    return int(w), int(h)


#: Drawing options that only some formats read, by the suffixes of those formats.
FORMAT_OPTIONS: dict[str, tuple[str, ...]] = {"dxf_version": (".dxf",), "svg_lines": (".svg",)}


def check_request(net: NetOptions, outputs: Sequence[str | Path], *, box: bool,
                  drawing_given: Sequence[str] = ()) -> list[Path]:
    """Refuse bad outputs and option combinations before any search (the CLI's words); the drawings named.

    Every output's folder must exist, a drawing must have a known extension, and
    ``zipper``, ``min_box``, ``count`` and a box must make sense together.
    ``drawing_given`` names the :class:`DrawingOptions` the user set: each must be
    read by an output (a DXF version needs a .dxf, any of them a drawing), or it
    is refused by its flag rather than ignored.
    """
    from voxfab._shared.atomic import check_output
    from voxfab.drawing import FORMATS

    paths = [Path(p) for p in outputs]
    for p in paths:
        check_output(p)  # before the search, which may take minutes
    drawings = [p for p in paths if p.suffix.lower() != ".json"]
    for p in drawings:
        if p.suffix.lower() not in FORMATS:
            raise UnknownFormatError(f"{p}: unknown drawing format {p.suffix or '(none)'!r}; expected .json or "
                                     f"one of {', '.join(FORMATS)}")
    if net.zipper and (drawings or net.count > 1):
        raise InvalidShapeError("--zipper: for one JSON net (NET.json) with --strategy exact")
    if net.min_box and (drawings or box):
        raise InvalidShapeError("--min-box: for JSON nets without --box (drawings fit their sheet)")
    if net.count > 1 and net.pieces != "one":
        raise InvalidShapeError("--count: several nets need --pieces one")
    if drawings and box:
        raise InvalidShapeError("--fit: drawings fit their sheet (--sheet); --fit is for JSON nets only")
    from voxfab._shared.options import option_specs

    suffixes = {p.suffix.lower() for p in drawings}
    flags = {s.name: s.flag for s in option_specs(DrawingOptions)}
    for name in drawing_given:
        flag = flags[name]
        if not drawings:
            raise InvalidShapeError(f"{flag}: for drawings (-o with .svg, .dxf, .pdf or .png); a JSON net has none")
        wanted = FORMAT_OPTIONS.get(name)
        if wanted is not None and not suffixes & set(wanted):
            raise InvalidShapeError(f"{flag}: for {' and '.join(wanted)} drawings; none of -o is one "
                                    f"({', '.join(sorted(suffixes))})")
    return drawings


def search_nets(grid: Any, net: NetOptions, drawing: DrawingOptions | None, *, seed: int,
                constraints: EdgeConstraints | None = None, box: tuple[int, int] | None = None,
                progress: Callable[[int, int], None] | None = None) -> SheetNets:
    """The nets of a net job: fitted to the sheet of ``drawing``, or free (in ``box``) for JSON only.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
    net : NetOptions
        Search options; ``count`` nets with pairwise different outlines.
    drawing : DrawingOptions or None
        With drawings to make: the sheet they must fit (``pitch`` the face size, None
        for the largest that fits).  None for JSON nets only.
    seed : int
    constraints : EdgeConstraints, optional
    box : (int, int), optional
        JSON nets only: the box in faces the nets must lie in.  The exact
        strategy without one (nor ``min_box``, ``zipper`` or ``compact``) searches
        in a box that holds every net (:func:`voxfab.unfold.unfold`).

    Returns
    -------
    SheetNets
        The nets (each as its pieces), the drawing options settled, report notes.
    """
    from voxfab.unfold import unfold

    search: dict[str, Any] = dict(strategy=net.strategy, timeout=net.timeout, fill=net.fill, compact=net.compact,
                                  constraints=constraints)
    if drawing is not None:
        from ._fit import find_sheet_nets

        return find_sheet_nets(grid, drawing, rng=seed, pieces=net.pieces, count=net.count, budget=net.budget,
                               progress=progress, **search)
    notes: list[str] = []
    if net.count > 1:
        from voxfab.unfold import unfold_many

        found = unfold_many(grid, count=net.count, rng=seed, budget=net.budget, fit=box, progress=progress,
                            **search)
        if len(found) < net.count:
            notes.append(f"{len(found)} distinct nets found of the {net.count} asked for "
                         f"within the {net.budget:g} s budget")
        return SheetNets([[n] for n in found], DrawingOptions(), notes)
    one = unfold(grid, rng=seed, pieces=net.pieces, fit=box, min_box=net.min_box, zipper=net.zipper, **search)
    return SheetNets([one if isinstance(one, list) else [one]], DrawingOptions(), notes)


def validate_net(grid: Any, pieces: Sequence[Net], *, constraints: EdgeConstraints | None = None) -> Any:
    """Refold the net (its pieces) onto the shape it was searched on (cavities filled when it was)."""
    from voxfab.shape import fill_cavities
    from voxfab.unfold import validate

    g = fill_cavities(grid) if pieces[0].filled else grid
    return validate(g, list(pieces) if len(pieces) > 1 else pieces[0], constraints=constraints)


@dataclasses.dataclass(frozen=True)
class NetFiles:
    """What a net job wrote.

    Attributes
    ----------
    written : list of str
        Paths published, in order.
    nets : list of dict
        Per net: seed, faces, pieces, seams without tab room and, with drawings,
        face size and sheet fill.
    warnings : list of str
        What a maker must read (once per net).
    notes : list of str
        Report lines of the search (face size chosen, nets found).
    report : list of (str, str)
        ``(file name, line)`` of every drawing's report.
    """

    written: list[str]
    nets: list[dict[str, Any]]
    warnings: list[str]
    notes: list[str]
    report: list[tuple[str, str]]


def _named(path: Path, *tags: str) -> Path:
    tags = tuple(t for t in tags if t)
    if not tags:
        return path
    return path.with_name(f"{path.stem}-{'-'.join(tags)}{path.suffix}")


def net_files(shape: Any, net: NetOptions, drawing: DrawingOptions, outputs: Sequence[str | Path], *, title: str,
              seed: int, constraints: EdgeConstraints | None = None,
              box: tuple[int, int] | None = None) -> NetFiles:
    """Search, validate and write the nets of ``grid`` to ``outputs`` (``voxfab net``).

    ``NET.json`` outputs get the nets as voxfab-net/1 JSON (``NAME-pieceN.json`` per
    piece), drawings (``.svg .dxf .pdf .png``) are fitted to the sheet; with several
    nets (``count``) every file is numbered ``NAME-N.ext``.  Every file is published
    at the end, replacing the whole earlier set.

    Parameters
    ----------
    shape : VoxelShape or (X, Y, Z) bool array_like
        A coloured shape prints each face in its voxel's colour and writes it in the JSON.
    net, drawing : NetOptions, DrawingOptions
        ``drawing.pitch`` is the face size (None: the largest at which the net fits).
    outputs : sequence of path
    title : str
        Shape name for the drawings' title.
    seed : int
    constraints : EdgeConstraints, optional
    box : (int, int), optional
        JSON nets only: the box in faces.

    Returns
    -------
    NetFiles
    """
    from voxfab._shared.atomic import atomic_files, write_text

    from . import shape_colours, write_net_drawing

    grid, colours = shape_colours(shape)
    paths = [Path(p) for p in outputs]
    drawings = check_request(net, paths, box=box is not None)
    found = search_nets(grid, net, drawing if drawings else None, seed=seed, constraints=constraints, box=box)
    results, notes = found.nets, list(found.notes)
    if drawings:
        drawing = found.options  # the face size settled
    g, gc = shape_colours(shape, results[0][0].filled)
    if gc is not None:
        from voxfab.shape import VoxelShape

        g = VoxelShape(g, shape.pitch, gc)
    summary, warnings, report = [], [], []
    with atomic_files(*paths) as fileset:
        for t, pieces in enumerate(results):
            validate_net(grid, pieces, constraints=constraints)
            tag = str(t + 1) if len(results) > 1 else ""
            record: dict[str, Any] = {"seed": pieces[0].seed, "faces": sum(n.face_count for n in pieces),
                                      "pieces": len(pieces),
                                      "seams_without_tab_room": sum(n.seams_without_tab_room for n in pieces)}
            for path in paths:
                target = _named(path, tag)
                if path in drawings:
                    result = write_net_drawing(g, pieces, target, drawing, title=title)
                    report += [(target.name, line) for line in result.report]
                    # The drawing's own count: what its report and warnings print (the search's
                    # count knows only the cells of the layout, not the tabs the packing kept room for).
                    record.update(face_size=result.face_size, fill=[round(f, 4) for f in result.fill],
                                  seams_without_tab_room=result.seams_without_tab)
                    # Every drawing of one net says the same: once per net.
                    warnings += [w for w in (f"net {tag}: {x}" if tag else x for x in result.warnings)
                                 if w not in warnings]
                    continue
                for q, piece in enumerate(pieces):
                    write_text(_named(target, f"piece{q + 1}" if len(pieces) > 1 else ""), piece.to_json(colours))
            summary.append(record)
    return NetFiles([str(p) for p in fileset.written], summary, warnings, notes, report)
