"""One BLAS thread for small linear algebra.

Small matrices (a GP over 160 points, an L-BFGS-B step in five parameters) gain
nothing from BLAS threads and, on a loaded machine, lose a lot: OpenBLAS's
spinning threads can make such a fit ten to a hundred times slower when the
cores are busy.  Code that does such
work runs under :func:`one_blas_thread` (:mod:`threadpoolctl`, restored
afterwards).
"""

from __future__ import annotations

import functools
from contextlib import contextmanager

__all__ = ["one_blas_thread"]


@functools.cache
def _blas_controller():
    """The loaded BLAS libraries, inspected once (inspecting costs far more than limiting)."""
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


@contextmanager
def one_blas_thread():
    """Limit BLAS to one thread inside the ``with`` block (module docs)."""
    with _blas_controller().limit(limits=1, user_api="blas"):
        yield
