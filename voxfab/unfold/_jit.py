"""The compiler of the search kernels: numba, or none for the plain-Python copy.

Loading numba and its first compiled call costs about half a second, more than
the whole search on a small surface takes in plain Python.  So the kernel
modules are also loaded a second time, as the package ``voxfab.unfold._pure``
(see :func:`voxfab.unfold._searchboard._kernels`), where this decorator leaves the
functions as they are.
"""

from __future__ import annotations

if __name__.rpartition(".")[0].endswith("._pure"):

    def njit(*args, **kwargs):  # noqa: ANN002, ANN003, ANN201 - mirrors numba.njit
        """Leave the function uncompiled."""
        if args and callable(args[0]):
            return args[0]
        return lambda f: f

else:
    from numba import njit as _numba_njit

    def njit(*args, **kwargs):  # noqa: ANN002, ANN003, ANN201 - mirrors numba.njit
        """``numba.njit`` releasing the GIL (``nogil=True``) unless told otherwise.

        The kernels touch only their own arrays, so they may run while other
        threads run Python: a server searching nets on its worker threads still
        answers requests, notices a cancel and stops on Ctrl-C at once (a compiled
        annealing chunk of the queen holds the CPU for about 0.4 s), and two
        searches share two cores.
        """
        kwargs.setdefault("nogil", True)
        return _numba_njit(*args, **kwargs)
