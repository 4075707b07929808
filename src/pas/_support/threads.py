"""One BLAS thread for small linear algebra.

Small matrices (a GP over 160 points, an L-BFGS-B step in five parameters) gain
nothing from BLAS threads and, on a loaded machine, lose a lot: OpenBLAS's
spinning threads made a 157-point GP fit take 5 s instead of 60 ms, and a
joint copula fit 0.5 s instead of 50 ms, on 2 busy cores.  Code that does such
work runs under :func:`one_blas_thread` (:mod:`threadpoolctl`, restored
afterwards).
"""

from __future__ import annotations

import functools
from contextlib import contextmanager

__all__ = ["one_blas_thread"]


@functools.cache
def _blas_controller():
    """The loaded BLAS libraries, inspected once (≈ 4 ms a time, 0.03 ms to limit them)."""
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


@contextmanager
def one_blas_thread():
    """Limit BLAS to one thread inside the ``with`` block (module docs)."""
    with _blas_controller().limit(limits=1, user_api="blas"):
        yield
