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
        """``numba.njit`` releasing the GIL (``nogil=True``), without reference counting, unless told otherwise.

        The kernels touch only their own arrays, so they may run while other
        threads run Python: a server searching nets on its worker threads still
        answers requests, notices a cancel and stops on Ctrl-C at once (a compiled
        annealing chunk of the queen holds the CPU for about 0.4 s), and two
        searches share two cores.

        Without numba's runtime (``_nrt=False``) a kernel may not allocate an
        array (copy a slice in a loop instead), and a call between kernels no
        longer takes and drops a reference to each array it passes: an atomic
        add and a call each, most of the cost of a growth step before.
        Numba's cache does not tell the two builds apart: after changing this,
        delete the ``*.nbi``/``*.nbc`` files of ``voxfab/unfold/__pycache__``.
        """
        kwargs.setdefault("nogil", True)
        kwargs.setdefault("_nrt", False)
        return _numba_njit(*args, **kwargs)


def inline(f):  # noqa: ANN001, ANN201 - a decorator
    """Compile ``f`` into each kernel that calls it (numba's ``inline="always"``).

    A call from one compiled kernel to another is a real call that passes each
    array as a struct of several words; the small helpers a growth step runs
    dozens of times (a placement re-checks a dozen half-edges) are inlined
    instead, which makes a step about a third cheaper.  Inlining the large
    ones too would lengthen numba's first compile for little more.  The
    plain-Python copy leaves them as they are.
    """
    return njit(cache=True, inline="always")(f)
