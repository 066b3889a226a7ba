"""Soak run of the fuzz strategies of ``tests/fuzz``: many more inputs than the test suite tries.

Every reader, recipes (random TOML trees over the real schema keys, checked and
built), every command's options, and the hostile corpus go through the real CLI,
in this process.  Unlike the tests, a failure does not stop the run: each input is
classified and the run goes on, so one soak counts everything it finds.

Classes: ``ok`` (exit 0), ``error`` (one ``voxfab: error:`` line), ``usage``
(argparse refused the command line), and the faults: ``traceback`` (an exception
escaped), ``message`` (not exactly one error line), ``slow`` (over the time bound),
``wrong`` (a success that should have been a refusal: a corrupt repository row
exported as a shape) and ``leftover`` (a refusal that left a file or folder behind).

The newer surfaces get cases of their own: crafted repository rows (``repo``
show, export and check), the batch runner's options (on a real LocalCluster),
servers that send random bytes to ``batch --scheduler``, ``explore``'s numbers,
and the studio's ``--host`` and ``--repo``.

Usage::

    python bench/bench_fuzz.py [--examples N] [--seconds S] [--seed N] [--surfaces] [--smoke]

``--examples`` is per case (default 300); ``--smoke`` tries one input per case.  The exit status
is 1 when a fault was found.
"""

from __future__ import annotations

import argparse
import collections
import sys
import tempfile
import time
import traceback
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from _fuzz import (  # noqa: E402
    CLI_COMMANDS,
    CLI_FIXED,
    RunTimeout,
    argv_for,
    cli_corpus,
    cli_positionals,
    hostile_recipe_folder,
    mutated,
    put,
    recipe_trees,
    run_cli,
    toml_text,
    valid_files,
)
from hypothesis import HealthCheck, Phase, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from voxfab.cli import STRICT_EXIT  # noqa: E402

#: Classes that are faults.
FAULTS = ("traceback", "message", "slow", "wrong", "leftover")
READERS = [".npy", ".npz", ".txt", ".vox", ".binvox", ".png", "/", ".stl", ".stl-ascii", ".obj", ".ply", ".3mf"]


class Soak:
    """Counts of one soak run."""

    def __init__(self, seconds: float) -> None:
        self.seconds = seconds
        self.counts: dict[str, collections.Counter[str]] = {}
        self.faults: list[tuple[str, str, str]] = []
        self.slowest: tuple[float, str] = (0.0, "")

    def classify(self, case: str, label: str, run: Callable[[], object],
                 verdict: Callable[[object], str | None] | None = None) -> None:
        """Run one input and count its class; ``verdict(outcome)`` may name a fault the exit cannot show."""
        counter = self.counts.setdefault(case, collections.Counter())
        start = time.perf_counter()
        try:
            o = run()
        except RunTimeout:
            kind, detail = "slow", f"over {self.seconds} s"
        except Exception:  # noqa: BLE001 - a soak records every escaped exception and goes on
            kind, detail = "traceback", traceback.format_exc(limit=-3)
        else:
            elapsed = time.perf_counter() - start
            if elapsed > self.slowest[0]:
                self.slowest = (elapsed, f"{case}: {label[:160]}")
            errors = [x for x in o.err.splitlines() if x.startswith("voxfab: error:")]
            if "Traceback" in o.err:
                kind, detail = "traceback", o.err[-600:]
            elif o.code == 0 or (o.code == STRICT_EXIT and "--strict" in o.argv and not errors):
                kind, detail = "ok", ""  # --strict fails a run with warnings, on purpose
            elif o.usage:
                kind, detail = "usage", ""
            elif len(errors) == 1:
                kind, detail = "error", ""
            else:
                kind, detail = "message", o.err[-600:]
            if verdict is not None and kind in ("ok", "error", "usage"):
                found = verdict(o)
                if found is not None:
                    kind, detail = found, f"{o.err[-300:]}"
        counter[kind] += 1
        if kind in FAULTS:
            self.faults.append((case, label[:300], detail))

    def report(self, elapsed: float) -> int:
        kinds = ["ok", "error", "usage", *FAULTS]
        print(f"{'case':<28}" + "".join(f"{k:>10}" for k in kinds) + f"{'inputs':>10}")
        total: collections.Counter[str] = collections.Counter()
        for case, counter in self.counts.items():
            total.update(counter)
            print(f"{case:<28}" + "".join(f"{counter[k]:>10}" for k in kinds) + f"{sum(counter.values()):>10}")
        print(f"{'all':<28}" + "".join(f"{total[k]:>10}" for k in kinds) + f"{sum(total.values()):>10}")
        faults = sum(total[k] for k in FAULTS)
        print(f"\n{len(self.counts)} cases, {sum(total.values())} inputs tried in {elapsed:.0f} s; "
              f"{total['traceback']} tracebacks, {total['message']} bad messages, {total['slow']} slow runs, "
              f"{total['wrong']} wrong successes, {total['leftover']} leftovers")
        print(f"slowest run: {self.slowest[0]:.2f} s ({self.slowest[1]})")
        for case, label, detail in self.faults[:20]:
            print(f"\nFAULT in {case}: {label}\n{detail}")
        return 1 if faults else 0


def soak(case: str, strategy: st.SearchStrategy, run: Callable[[object], object], s: Soak, examples: int,
         seed: int, verdict: Callable[[object, object], str | None] | None = None) -> None:
    """Draw ``examples`` inputs from ``strategy`` and classify each run (``verdict(value, outcome)``)."""

    @settings(max_examples=examples, database=None, deadline=None, phases=[Phase.generate],
              suppress_health_check=list(HealthCheck))
    @given(value=strategy)
    def body(value: object) -> None:
        judge = None if verdict is None else (lambda o: verdict(value, o))
        s.classify(case, repr(value)[:300], lambda: run(value), judge)

    # A fixed seed per case: the same soak finds the same inputs.
    import hypothesis

    hypothesis.seed(seed + sum(map(ord, case)))(body)()
    print(f"  {case}: {sum(s.counts.get(case, {}).values())} inputs", file=sys.stderr, flush=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--examples", type=int, default=300, help="inputs per case (default 300)")
    parser.add_argument("--seconds", type=float, default=60.0, help="time bound of one run (default 60)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--surfaces", action="store_true",
                        help="only the batch runner, repository rows, explore and the studio's command line")
    parser.add_argument("--smoke", action="store_true", help="one input per case")
    args = parser.parse_args()
    if args.smoke:
        args.examples = 1
    s = Soak(args.seconds)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        if args.surfaces:
            soak_surfaces(root / "surfaces", s, args.examples, args.seed, args.seconds)
            return s.report(time.perf_counter() - start)
        valid = valid_files(root / "valid")
        for ext in READERS:
            soak(f"reader {ext}", st.one_of(mutated(valid[ext]), st.binary(max_size=200)),
                 lambda data, ext=ext: run_cli(["info", put(root / "fuzz", ext, data), "--json"],
                                               seconds=args.seconds), s, args.examples, args.seed)
        folder = root / "recipes" / "r"
        hostile_recipe_folder(folder)

        def check(tree: dict) -> object:
            (folder / "fuzz.toml").write_text(toml_text(tree))
            return run_cli(["build", folder / "fuzz.toml", "--check"], seconds=args.seconds)

        def build(tree: dict) -> object:
            tree["name"] = "fuzz"
            (folder / "fuzz.toml").write_text(toml_text(tree))
            return run_cli(["build", folder / "fuzz.toml", "-o", root / "out"], seconds=args.seconds)

        soak("recipe --check", recipe_trees(), check, s, args.examples, args.seed)
        soak("recipe build", recipe_trees(with_outputs=False, strict=True), build, s, max(1, args.examples // 3), args.seed)
        cli = root / "cli"
        cli.mkdir()
        cli_corpus(cli)
        for command in CLI_COMMANDS:
            strategy = argv_for(command, cli_positionals(cli, command), fixed=CLI_FIXED.get(command, ()))
            soak(f"cli {command}", strategy, lambda argv: run_cli(argv, seconds=args.seconds), s,
                 args.examples, args.seed)
        soak_surfaces(root / "surfaces", s, args.examples, args.seed, args.seconds)
    return s.report(time.perf_counter() - start)


# ---- the batch runner, the repository, explore and the studio's command line -------------------------

#: Values written over one column of a stored row.
ROW_VALUES = [b"", b"\x00", b"\xff" * 3, "", "text", "{", "[1]", "[]", "null", 0, -1, 7, 10**12, 2.5, None]
ROW_COLUMNS = ["bits", "volume", "nx", "ny", "nz", "key", "symmetric_key", "reasons", "meta"]


def _entries(folder: Path) -> set[Path]:
    return set(folder.rglob("*")) if folder.exists() else set()


def soak_surfaces(root: Path, s: Soak, examples: int, seed: int, seconds: float) -> None:
    """The cases of the newer surfaces, each judged for wrong successes and leftovers too."""
    import socket
    import sqlite3
    import threading

    from voxfab.repo import Repository

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    from _batch_fixtures import make_repo, write_outputs

    root.mkdir(parents=True)
    good = root / "good.sqlite"
    make_repo(good)
    with Repository(good) as repo:
        name = repo.list()[0].name
        stored = repo.packed(name)

    # Crafted rows: a damaged row may only ever be refused, and a refusal writes nothing.
    def damaged(value: tuple[str, object]) -> object:
        column, new = value
        path = root / "rows.sqlite"
        path.write_bytes(good.read_bytes())
        with sqlite3.connect(path) as db:
            # As another tool might: the schema's CHECKs guard only writers that keep them on.
            db.execute("PRAGMA ignore_check_constraints = ON")
            db.execute(f"UPDATE shapes SET {column} = ? WHERE name = ?", (new, name))
        out = root / "rows-out"
        out.mkdir(exist_ok=True)
        results = [run_cli(["repo", action, name, *extra, "--repo", path], seconds=seconds)
                   for action, extra in (("show", []), ("export", [out / "x.npy"]))]
        results.append(run_cli(["repo", "check", "--repo", path], seconds=seconds))
        return max(results, key=lambda o: ("Traceback" in o.err, o.code == 0))

    def row_verdict(value: tuple[str, object], o: object) -> str | None:
        column, new = value
        out = root / "rows-out" / "x.npy"
        if o.code == 0 and column == "bits" and new != stored[0]:  # type: ignore[attr-defined]
            return "wrong"
        with Repository(root / "rows.sqlite", create=False) as repo:
            sound = not repo.check()
        if out.exists():
            out.unlink()
            return None if sound else "wrong"
        return None

    # NULL only where the schema allows it (meta): SQLite refuses the others whatever the writer.
    rows = st.tuples(st.sampled_from(ROW_COLUMNS), st.sampled_from(ROW_VALUES)).filter(
        lambda v: v[1] is not None or v[0] == "meta")
    soak("repo rows", rows, damaged, s, max(1, examples // 3), seed, row_verdict)

    # explore's numbers: a refused run leaves no repository.
    def explore(value: tuple[str, str | None, str | None]) -> object:
        count, attempts, volume = value
        target = root / "explore" / "r.sqlite"
        target.parent.mkdir(exist_ok=True)
        target.unlink(missing_ok=True)
        argv = ["explore", "--count", count, "--repo", target]
        argv += [] if attempts is None else ["--max-attempts", attempts]
        argv += [] if volume is None else ["--volume", volume]
        return run_cli(argv, seconds=seconds)

    def explore_verdict(value: object, o: object) -> str | None:
        made = (root / "explore" / "r.sqlite").exists()
        return "leftover" if o.code != 0 and made and not _stored(root / "explore" / "r.sqlite") else None  # type: ignore[attr-defined]

    small = ["0", "-1", "1", "2", "3", "x", "1e3", str(10**7), str(10**12), str(2**63)]
    soak("explore", st.tuples(st.sampled_from(small), st.one_of(st.none(), st.sampled_from(small)),
                              st.one_of(st.none(), st.sampled_from(["", ":", "25:30", "1:3", "x", "30:25", "25:"]))),
         explore, s, max(1, examples // 3), seed, explore_verdict)

    # The batch runner's options on a real LocalCluster: a refusal leaves no folder.
    outputs = write_outputs(root / "outputs.toml")
    (root / "a_file").write_text("x")
    batch_root = root / "batch"
    batch_root.mkdir()
    paths = {
        "repo": st.sampled_from([str(good), str(root / "missing.sqlite"), str(root / "a_file"), "/dev/null"]),
        "outputs": st.sampled_from([str(outputs), "/dev/zero", str(root / "a_file"), str(root / "none.toml")]),
        "output": st.sampled_from([str(batch_root / "out"), "", str(root / "a_file" / "x"),
                                   str(batch_root / "m" / "a" / "b"), "/proc/voxfab"]),
    }
    batch_argv = argv_for("batch", paths, fixed=("--no-index", "--no-dashboard", "--connect-timeout", "5"))

    def batch(argv: list[str]) -> object:
        import shutil

        shutil.rmtree(batch_root / "out", ignore_errors=True)
        return run_cli(argv, seconds=seconds)

    def batch_verdict(argv: list[str], o: object) -> str | None:
        if o.code != 0 and "shapes failed" not in o.err and _entries(batch_root):  # type: ignore[attr-defined]
            return "leftover"
        return None

    soak("batch options", batch_argv, batch, s, max(min(3, examples), examples // 10), seed, batch_verdict)

    # Servers that are not Dask schedulers: random bytes, then silence.
    def scheduler(data: bytes) -> object:
        server = socket.create_server(("127.0.0.1", 0))
        port = server.getsockname()[1]

        def answer() -> None:
            try:
                conn, _ = server.accept()
                with conn:
                    conn.sendall(data)
                    time.sleep(6)
            except OSError:
                pass

        thread = threading.Thread(target=answer, daemon=True)
        thread.start()
        try:
            return run_cli(["batch", "--repo", good, "--outputs", outputs, "-o", batch_root / "out", "--no-index",
                            "--scheduler", f"tcp://127.0.0.1:{port}", "--connect-timeout", "2"], seconds=seconds)
        finally:
            server.close()

    def scheduler_verdict(data: bytes, o: object) -> str | None:
        if o.code == 0:  # type: ignore[attr-defined]
            return "wrong"
        return "leftover" if _entries(batch_root) else None

    frames = st.one_of(st.binary(max_size=64), st.tuples(st.integers(0, 2**64 - 1), st.binary(max_size=32)).map(
        lambda t: t[0].to_bytes(8, "little") + t[1]))
    soak("batch --scheduler", frames, scheduler, s, max(min(3, examples), examples // 10), seed, scheduler_verdict)

    # The studio's command line, on a port already taken on both loopbacks: it never serves.
    busy = socket.create_server(("127.0.0.1", 0))
    busy6 = socket.create_server(("::1", busy.getsockname()[1]), family=socket.AF_INET6)
    (root / "folder.sqlite").mkdir()
    (root / "text.sqlite").write_text("text")

    def studio(value: tuple[str, str]) -> object:
        host, repo = value
        return run_cli(["studio", "--no-browser", "--host", host, "--port", str(busy.getsockname()[1]),
                        "--repo", repo], seconds=seconds)

    # 192.0.2.1 (TEST-NET-1) is no local address: the warning path, without listening on the network.
    hosts = ["127.0.0.1", "", " ", "localhost", "::1", "no-such-host.invalid", "999.1.1.1", "192.0.2.1"]
    repos = [str(good), str(root / "folder.sqlite"), str(root / "text.sqlite"), str(root / "missing" / "r.sqlite"),
             str(root / "new.sqlite"), ""]

    def studio_verdict(value: object, o: object) -> str | None:
        return "leftover" if (root / "new.sqlite").exists() or (root / "missing").exists() else None

    soak("studio command line", st.tuples(st.sampled_from(hosts), st.sampled_from(repos)), studio, s,
         max(1, examples // 3), seed, studio_verdict)
    busy.close()
    busy6.close()


def _stored(path: Path) -> int:
    from voxfab.repo import Repository

    with Repository(path, create=False) as repo:
        return len(repo)


if __name__ == "__main__":
    sys.exit(main())
