"""Soak run of the fuzz strategies of ``tests/fuzz``: many more inputs than the test suite tries.

Every reader, recipes (random TOML trees over the real schema keys, checked and
built), every command's options, and the hostile corpus go through the real CLI,
in this process.  Unlike the tests, a failure does not stop the run: each input is
classified and the run goes on, so one soak counts everything it finds.

Classes: ``ok`` (exit 0), ``error`` (one ``voxfab: error:`` line), ``usage``
(argparse refused the command line), and the faults: ``traceback`` (an exception
escaped), ``message`` (not exactly one error line), ``slow`` (over the time bound).

Usage::

    python bench/bench_fuzz.py [--examples N] [--seconds S] [--seed N]

``--examples`` is per case (default 300); the exit status is 1 when a fault was found.
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

from voxfab.cli._common import STRICT_EXIT  # noqa: E402

READERS = [".npy", ".npz", ".txt", ".vox", ".binvox", ".png", "/", ".stl", ".stl-ascii", ".obj", ".ply", ".3mf"]


class Soak:
    """Counts of one soak run."""

    def __init__(self, seconds: float) -> None:
        self.seconds = seconds
        self.counts: dict[str, collections.Counter[str]] = {}
        self.faults: list[tuple[str, str, str]] = []
        self.slowest: tuple[float, str] = (0.0, "")

    def classify(self, case: str, label: str, run: Callable[[], object]) -> None:
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
        counter[kind] += 1
        if kind in ("traceback", "message", "slow"):
            self.faults.append((case, label[:300], detail))

    def report(self, elapsed: float) -> int:
        kinds = ["ok", "error", "usage", "traceback", "message", "slow"]
        print(f"{'case':<28}" + "".join(f"{k:>10}" for k in kinds) + f"{'inputs':>10}")
        total: collections.Counter[str] = collections.Counter()
        for case, counter in self.counts.items():
            total.update(counter)
            print(f"{case:<28}" + "".join(f"{counter[k]:>10}" for k in kinds) + f"{sum(counter.values()):>10}")
        print(f"{'all':<28}" + "".join(f"{total[k]:>10}" for k in kinds) + f"{sum(total.values()):>10}")
        faults = total["traceback"] + total["message"] + total["slow"]
        print(f"\n{len(self.counts)} cases, {sum(total.values())} inputs tried in {elapsed:.0f} s; "
              f"{total['traceback']} tracebacks, {total['message']} bad messages, {total['slow']} slow runs")
        print(f"slowest run: {self.slowest[0]:.2f} s ({self.slowest[1]})")
        for case, label, detail in self.faults[:20]:
            print(f"\nFAULT in {case}: {label}\n{detail}")
        return 1 if faults else 0


def soak(case: str, strategy: st.SearchStrategy, run: Callable[[object], object], s: Soak, examples: int,
         seed: int) -> None:
    """Draw ``examples`` inputs from ``strategy`` and classify each run."""

    @settings(max_examples=examples, database=None, deadline=None, phases=[Phase.generate],
              suppress_health_check=list(HealthCheck))
    @given(value=strategy)
    def body(value: object) -> None:
        s.classify(case, repr(value)[:300], lambda: run(value))

    # A fixed seed per case: the same soak finds the same inputs.
    import hypothesis

    hypothesis.seed(seed + sum(map(ord, case)))(body)()
    print(f"  {case}: {sum(s.counts.get(case, {}).values())} inputs", file=sys.stderr, flush=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--examples", type=int, default=300, help="inputs per case (default 300)")
    parser.add_argument("--seconds", type=float, default=60.0, help="time bound of one run (default 60)")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    s = Soak(args.seconds)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
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
        soak("recipe build", recipe_trees(with_outputs=False, strict=True), build, s, args.examples // 3, args.seed)
        cli = root / "cli"
        cli.mkdir()
        cli_corpus(cli)
        for command in CLI_COMMANDS:
            strategy = argv_for(command, cli_positionals(cli, command), fixed=CLI_FIXED.get(command, ()))
            soak(f"cli {command}", strategy, lambda argv: run_cli(argv, seconds=args.seconds), s,
                 args.examples, args.seed)
    return s.report(time.perf_counter() - start)


if __name__ == "__main__":
    sys.exit(main())
