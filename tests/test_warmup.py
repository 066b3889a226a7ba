import importlib
import os
import subprocess
import sys

import pytest

from voxfab.errors import InvalidShapeError
from voxfab.warmup import ENTRY_KERNELS, GROUPS, compile_aside, is_compiled, warm_up


def run_python(code, cache, **env):
    """Run ``code`` in a fresh interpreter whose numba cache is the folder ``cache``."""
    environ = {**os.environ, "NUMBA_CACHE_DIR": str(cache), **env}
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=environ, timeout=600)
    assert r.returncode == 0, r.stderr
    return r.stdout.strip()


def test_every_group_names_real_kernels():
    assert set(ENTRY_KERNELS) == set(GROUPS)
    for kernels in ENTRY_KERNELS.values():
        for module, name in kernels:
            kernel = getattr(importlib.import_module(module), name)
            assert hasattr(kernel, "_cache") and kernel._cache._cache_file is not None, (module, name)


def test_unknown_groups_are_refused():
    with pytest.raises(InvalidShapeError, match="unknown kernel group 'paint'"):
        warm_up(["print", "paint"])


def test_a_warm_cache_starts_nothing_aside():
    warm_up(["net"], processes=1)
    assert is_compiled("net")
    with compile_aside(["net"]) as aside:
        assert aside.groups == ()


def test_nothing_compiles_aside_without_an_idle_core(monkeypatch):
    import voxfab.warmup as warmup

    monkeypatch.setattr(warmup, "is_compiled", lambda group: False)
    monkeypatch.setattr(warmup, "_cores", lambda: 2)
    monkeypatch.setattr(warmup.os, "getloadavg", lambda: (1.5, 1.0, 1.0))  # the other core is busy
    assert warmup.compile_aside(["net"]).groups == ()
    monkeypatch.setattr(warmup, "_cores", lambda: 1)
    monkeypatch.setattr(warmup.os, "getloadavg", lambda: (0.0, 0.0, 0.0))
    assert warmup.compile_aside(["net"]).groups == ()


@pytest.mark.slow
def test_warmup_fills_a_fresh_cache_with_the_build_kernels(tmp_path):
    check = "from voxfab.warmup import is_compiled; print(is_compiled('print'), is_compiled('net'))"
    # A cold cache (nothing compiled) with an idle core: the net kernels start compiling aside; stopping leaves
    # no broken entry.  One interpreter checks the cache and starts the compile, as it finds them.
    started = run_python(f"{check}\nimport voxfab.warmup as w\nw._idle_core = lambda: True\n"
                         "a = w.compile_aside(['net', 'net'])\nprint(a.groups)\na.stop()", tmp_path)
    assert started.splitlines() == ["False False", "('net',)"]
    out = run_python("from voxfab.warmup import warm_up; print(warm_up(['print'], processes=1)[0].group)", tmp_path)
    assert out == "print"
    assert run_python(check, tmp_path) == "True False"
    assert any(p.suffix == ".nbi" for p in tmp_path.rglob("*"))



def test_the_warm_up_net_search_leaves_its_kernels_time_to_compile(monkeypatch, tmp_path):
    """The search's clock runs while its kernels compile: on a loaded machine a first compile took over the
    60 s a net search has by default, and the warm-up failed with "no one-piece net in 60 s"."""
    from voxfab.fabricate import netdraw
    from voxfab.warmup import GROUPS

    seen = []
    monkeypatch.setattr(netdraw, "fabricate_net", lambda shape, net, drawing, folder, **kw: seen.append(net))
    GROUPS["net"](tmp_path)
    assert len(seen) == 1 and seen[0].timeout >= 600
