"""Where a batch runs: a local Dask cluster or a running scheduler, with every wait bounded.

Dask's client trusts the server it connects to: a port that answers with other
bytes makes it allocate whatever size those bytes spell (petabytes), and a
server that says nothing keeps it waiting past any timeout.  So a scheduler
address is probed first with a plain socket: a Dask scheduler sends its
handshake as soon as a client connects, a small length-prefixed frame.  Only an
address that does gets a Dask client.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
import re
import shutil
import socket
import struct
import tempfile
import time
from pathlib import Path
from typing import Any

from voxfab._shared.limits import MAX_BATCH_WORKERS, MAX_WAIT_SECONDS, check_count
from voxfab._shared.numbers import is_digits
from voxfab.errors import MissingDependencyError, RepositoryError

__all__ = ["Cluster", "check_wait", "check_workers", "check_dashboard", "probe_scheduler", "connect"]

#: Largest handshake accepted from a scheduler: a real one is a few hundred bytes.
_MAX_HANDSHAKE = 1 << 20
#: ``[HOST]:PORT`` of a dashboard address.
_ADDRESS = re.compile(r"^(?P<host>[A-Za-z0-9.\-]*|\[[0-9A-Fa-f:.]+\]):(?P<port>\d{1,5})$")


def check_wait(seconds: object, *, name: str = "--connect-timeout") -> float:
    """Return ``seconds`` as a float in ``(0, MAX_WAIT_SECONDS]``; refuse NaN, infinities and the rest."""
    try:
        value = float(seconds)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise RepositoryError(f"{name}: expected a number of seconds, got {str(seconds)[:40]!r}") from None
    if not math.isfinite(value) or value <= 0:
        raise RepositoryError(f"{name}: expected a positive number of seconds, got {str(seconds)[:40]}")
    if value > MAX_WAIT_SECONDS:
        raise RepositoryError(f"{name}: {value:g} s is over the limit of {MAX_WAIT_SECONDS:g} s")
    return value


def check_workers(workers: object) -> int:
    """Return the number of local workers, 1 to ``MAX_BATCH_WORKERS``."""
    return check_count(workers, MAX_BATCH_WORKERS, name="--workers")


def check_dashboard(address: str | None) -> str | None:
    """Return a dashboard address ``[HOST]:PORT`` (port 0 to 65535; 0 picks a free one), or None."""
    if address is None:
        return None
    m = _ADDRESS.match(address)
    if not m or int(m.group("port")) > 65535:
        raise RepositoryError(
            f"--dashboard: expected [HOST]:PORT with a port of 0 to 65535 (such as :8787), got {address[:60]!r}"
        )
    return address


def _host_port(address: str) -> tuple[str, int] | None:
    """Host and port of a ``tcp://`` (or bare) scheduler address; None for other protocols."""
    rest = address
    if "://" in address:
        protocol, rest = address.split("://", 1)
        if protocol != "tcp":
            return None
    host, sep, port = rest.rpartition(":")
    if not sep or not is_digits(port) or len(port) > 5 or not 0 < int(port) <= 65535 or not host:
        raise RepositoryError(f"--scheduler: expected tcp://HOST:PORT, got {address[:80]!r}")
    return host.strip("[]"), int(port)


def _read_exactly(sock: socket.socket, n: int, deadline: float) -> bytes:
    data = b""
    while len(data) < n:
        left = deadline - time.monotonic()
        if left <= 0:
            raise TimeoutError
        sock.settimeout(left)
        chunk = sock.recv(n - len(data))
        if not chunk:
            raise ConnectionResetError
        data += chunk
    return data


def probe_scheduler(address: str, timeout: float) -> None:
    """Check that ``address`` is a Dask scheduler, within ``timeout`` seconds.

    Raises
    ------
    RepositoryError
        Nothing listens there, it says nothing (an HTTP server waits for a request),
        or it answers with bytes that are not a Dask handshake.
    """
    where = _host_port(address)
    if where is None:
        return  # tls://, ucx://...: left to Dask, within its timeout
    deadline = time.monotonic() + timeout
    try:
        sock = socket.create_connection(where, timeout=timeout)
    except OSError as exc:
        raise RepositoryError(f"--scheduler: cannot reach {address}: {exc.strerror or exc}") from None
    with sock:
        try:
            (size,) = struct.unpack("<Q", _read_exactly(sock, 8, deadline))
            if not 16 <= size <= _MAX_HANDSHAKE:
                raise ValueError
            (frames,) = struct.unpack("<Q", _read_exactly(sock, 8, deadline))
            if not 1 <= frames <= 64:
                raise ValueError
        except TimeoutError:
            raise RepositoryError(
                f"--scheduler: {address} is not a Dask scheduler: it sent nothing in {timeout:g} s"
            ) from None
        except (ValueError, OSError):
            raise RepositoryError(
                f"--scheduler: {address} is not a Dask scheduler: it answered with something else"
            ) from None


@dataclasses.dataclass
class Cluster:
    """A Dask client, the local cluster it owns (None on a running scheduler), its worker count, and the
    local cluster's scratch folder (removed at close)."""

    client: Any
    cluster: Any
    workers: int
    scratch: Path | None = None

    def worker_count(self) -> int:
        """Workers the scheduler has now."""
        return len(self.client.scheduler_info().get("workers", {}))

    def close(self) -> None:
        try:
            self.client.close()
            if self.cluster is not None:
                self.cluster.close()
        finally:
            if self.scratch is not None:
                shutil.rmtree(self.scratch, ignore_errors=True)


def connect(scheduler: str | None, workers: int, dashboard: str | None, timeout: float) -> Cluster:
    """Connect to ``scheduler`` (probed first) or start a local cluster of ``workers`` processes.

    Raises
    ------
    RepositoryError
        The scheduler is unreachable, is not a Dask scheduler, or has no worker
        within ``timeout`` seconds.
    MissingDependencyError
        Dask distributed is not installed.
    """
    try:
        from distributed import Client, LocalCluster
    except ImportError as exc:
        raise MissingDependencyError("dask[distributed]", "voxfab batch") from exc
    if scheduler is not None:
        probe_scheduler(scheduler, timeout)
        try:
            client = Client(scheduler, timeout=timeout)
        except (OSError, TimeoutError, ValueError) as exc:
            # ValueError: an address distributed cannot parse (no port, unknown protocol).
            raise RepositoryError(f"--scheduler: cannot reach {scheduler}: {' '.join(str(exc).split())}") from None
        try:
            client.wait_for_workers(1, timeout=timeout)
        except TimeoutError:
            client.close()
            raise RepositoryError(f"--scheduler: {scheduler} has no worker after {timeout:g} s") from None
        return Cluster(client, None, len(client.scheduler_info()["workers"]))
    # One thread per process: the builds hold the GIL (numpy, shapely, PIL) and each
    # worker gets its own memory, which the dashboard shows per worker.
    # Only critical logs: a worker stopped by Ctrl-C or SIGTERM logs its lost heartbeat as an
    # error with a traceback, which is no news to the user who stopped it.
    # Without a dashboard the scheduler still serves its health routes over HTTP, by default on
    # port 8787 (with a warning when that port is taken): a free loopback port instead.
    quiet_http = {"dashboard_address": "127.0.0.1:0"} if dashboard is None else {}
    # A local cluster's scheduler runs in this process, which shares the workers' cores: by default it
    # holds back every task a worker cannot start at once, so a worker that finishes waits for this
    # process to be given a core before it gets the next (2 workers on 2 cores were idle 16 % of the
    # time).  Tasks are sent ahead instead; the callers keep few in flight, so none is sent far ahead.
    import dask

    # The workers' scratch space in a folder of this run's own, removed however the run ends (Dask's
    # default, TMPDIR/dask-scratch-space, is shared by every cluster and left behind with its locks).
    scratch = Path(tempfile.mkdtemp(prefix="voxfab-dask-"))
    cluster = None
    try:
        with dask.config.set({"distributed.scheduler.worker-saturation": "inf", "temporary-directory": str(scratch)}):
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                                   dashboard_address=dashboard, silence_logs=50, scheduler_kwargs=quiet_http,
                                   local_directory=str(scratch), preload=["voxfab.batch._preload"])
        return Cluster(Client(cluster, timeout=timeout), cluster, workers, scratch)
    except BaseException:  # Ctrl-C while the cluster starts included
        if cluster is not None:
            with contextlib.suppress(Exception):
                cluster.close()
        shutil.rmtree(scratch, ignore_errors=True)
        raise
