"""Run the studio under uvicorn on a local address, and open the browser on it."""

from __future__ import annotations

import contextlib
import signal
import socket
import threading
import webbrowser
from collections.abc import Callable, Iterator
from pathlib import Path
from types import FrameType
from typing import Any

from voxfab.errors import InvalidShapeError, MissingDependencyError

#: Seconds a stopping server waits for requests in flight (then its jobs are cancelled: the whole stop is < 2 s).
SHUTDOWN_GRACE = 0.5


def _check_port(host: str, port: int) -> None:
    """Fail early with one line when the address is taken, instead of uvicorn's log."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            s.bind((host, port))
        except OSError as exc:
            raise InvalidShapeError(f"--port: cannot listen on {host}:{port}: {exc.strerror or exc}") from None


def serve(*, host: str = "127.0.0.1", port: int = 8765, repo: Path, open_browser: bool = True,
          work: Path | None = None, initial: Any = None) -> None:
    """Serve the studio until interrupted.

    Parameters
    ----------
    host, port : str, int
        Address to listen on (loopback by default: the studio is for this computer).
    repo : Path
        The repository database.
    open_browser : bool
        Open the page in the default browser once the server listens.
    work : Path, optional
        The session's work folder (default: a temporary folder removed at exit).
    initial : InitialShape, optional
        The shape the page opens with (``voxfab studio SHAPE``).
    """
    try:
        import uvicorn
    except ImportError:
        raise MissingDependencyError("uvicorn", "voxfab studio") from None
    from ._app import create_app
    from ._guard import allowed_hosts
    from ._session import Settings

    if not 1 <= port <= 65535:
        raise InvalidShapeError(f"--port: expected 1..65535, got {port}")
    _check_port(host, port)
    app = create_app(Settings(repo=Path(repo), hosts=allowed_hosts(host, port), work=work, initial=initial))
    shown = f"[{host}]" if ":" in host else host
    url = f"http://{shown}:{port}/"
    opened = f"; opens {initial.label}" if initial is not None else ""
    print(f"voxfab studio: {url}  (repository {repo}{opened}; Ctrl+C stops)", flush=True)
    if open_browser:
        threading.Timer(0.8, webbrowser.open, args=(url,)).start()
    config = uvicorn.Config(app, host=host, port=port, log_level="warning", lifespan="on",
                            timeout_graceful_shutdown=SHUTDOWN_GRACE)
    server = _server_class()(config)
    server.on_stop = app.app.state.cancel_jobs
    try:
        server.run()
    finally:
        # Also after a second Ctrl-C, when uvicorn skips the application's shutdown: jobs cancelled,
        # the session's folder removed (a no-op when the shutdown ran).  A Ctrl-C or SIGTERM now
        # would cut the clean-up short and leave the folder: it takes a second at most, undisturbed.
        with _signals_held():
            app.app.state.cleanup()
            print("voxfab studio: stopped", flush=True)


@contextlib.contextmanager
def _signals_held() -> Iterator[None]:
    """Ignore SIGINT and SIGTERM in the block (main thread only; elsewhere they cannot be set)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    held = {sig: signal.signal(sig, signal.SIG_IGN) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for sig, handler in held.items():
            signal.signal(sig, handler)


def _server_class() -> type:
    import uvicorn

    class Server(uvicorn.Server):
        """uvicorn's server, stopping at once: Ctrl-C cancels the jobs there and then, a second one forces the exit.

        uvicorn would first wait for the jobs' requests and then re-raise the
        signal; here the searches stop while it closes its connections, and the
        CLI ends normally.
        """

        on_stop: Callable[[], None] = staticmethod(lambda: None)

        async def shutdown(self, sockets: list[socket.socket] | None = None) -> None:
            await super().shutdown(sockets)
            if self.force_exit:  # uvicorn skips it then; it is bounded here (jobs are waited for at most 1 s)
                await self.lifespan.shutdown()

        def handle_exit(self, sig: int, frame: FrameType | None) -> None:
            self.on_stop()  # only sets the jobs' cancel events: safe inside a signal handler
            super().handle_exit(sig, frame)
            self._captured_signals.clear()

    return Server

