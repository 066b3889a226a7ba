"""Run by each local Dask worker process as it starts (a Dask preload): Ctrl-C is the client's to handle.

A terminal's Ctrl-C reaches every process of the foreground group: the workers of a
local cluster printed a KeyboardInterrupt traceback each while the client, which
owns them, stopped them anyway (its cluster's close).  The workers ignore it.
"""

from __future__ import annotations

import signal
import threading
from typing import Any


def dask_setup(worker: Any) -> None:
    """Ignore SIGINT in this worker process (only the main thread may set a handler)."""
    del worker
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
