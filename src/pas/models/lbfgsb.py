"""scipy's L-BFGS-B stepped through its reverse-communication routine (``setulb``).

:func:`minimise_together` runs one L-BFGS-B per problem with the defaults
of :func:`scipy.optimize.minimize` and asks for the objectives of all the
problems that want one at a step in one call: the model band's replicates
(:mod:`pas.models.joint_batch`) and, one problem at a time, every joint fit
of :func:`pas.models.joint.minimise_bounded` — the same iterates as
``scipy.optimize.minimize(method="L-BFGS-B", jac=True)``, without its
per-call and per-evaluation wrapping (``tests/models/test_joint_batch.py``).

``setulb`` is scipy's private routine: should a scipy release change how it
is called, :func:`driver_works` finds out once, on a small problem, and the
problems are then solved one at a time by ``scipy.optimize.minimize`` (the
same iterates, slower) with a warning that says so.
"""

from __future__ import annotations

import functools
import warnings

import numpy as np
from scipy import optimize
from scipy.optimize import OptimizeResult

try:
    from scipy.optimize import _lbfgsb
except ImportError:  # a scipy without the private module: driver_works() says so
    _lbfgsb = None

try:
    from scipy.optimize._lbfgsb_py import status_messages, task_messages
except ImportError:  # their text only names why an optimiser stopped
    status_messages, task_messages = {}, {}

__all__ = ["driver_works", "minimise_one", "minimise_together"]

_MAXCOR, _FTOL, _GTOL, _MAXLS, _MAXFUN, _MAXITER = (
    10,
    2.2204460492503131e-09,
    1e-5,
    20,
    15000,
    15000,
)
"""scipy.optimize.minimize's L-BFGS-B defaults."""


def _bound_arrays(bounds):
    """scipy's ``(lower, upper, nbd)`` of L-BFGS-B bounds given as ``(lo or None, hi or None)``."""
    lo = np.array([-np.inf if b[0] is None else b[0] for b in bounds], float)
    hi = np.array([np.inf if b[1] is None else b[1] for b in bounds], float)
    nbd = np.where(np.isfinite(lo), 1, 0) + np.where(np.isfinite(hi), 2, 0)
    nbd = np.array([0, 1, 3, 2])[nbd].astype(np.int32)  # none, lower, upper, both
    return np.where(np.isfinite(lo), lo, 0.0), np.where(np.isfinite(hi), hi, 0.0), nbd, lo, hi


def _message(task) -> str:
    """scipy's text for why L-BFGS-B stopped."""
    status, detail = int(task[0]), int(task[1])
    return f"{status_messages.get(status, status)}: {task_messages.get(detail, detail)}"


@functools.cache
def driver_works() -> bool:
    """Whether scipy's private ``setulb`` still works as :func:`minimise_together` calls
    it: tried once, on a one-parameter quadratic, and remembered."""
    def square(X, rows):
        return (X[:, 0] - 1.0) ** 2, 2.0 * (X - 1.0)

    try:
        res = _step_through(square, [np.zeros(1)], [[(None, None)]], np.zeros(1, int))[0]
        works = bool(abs(res.x[0] - 1.0) < 1e-6)
    except Exception:  # noqa: BLE001 - any failure of a private routine means "not usable"
        works = False
    if not works:
        warnings.warn("this scipy's private L-BFGS-B routine (scipy.optimize._lbfgsb."
                      "setulb) is not called as pas expects: the joint fits use "
                      "scipy.optimize.minimize instead (the same results, slower)",
                      RuntimeWarning, stacklevel=2)
    return works


def minimise_together(objective, starts, bounds, rows):
    """Each problem's L-BFGS-B from ``starts[j]`` within ``bounds[j]``, the objectives
    evaluated together: ``objective(X, rows)`` for the problems that ask at a step.

    The iterates are those of ``scipy.optimize.minimize(method="L-BFGS-B",
    jac=True)`` on each problem alone (its defaults; module docs).  Returns one
    ``OptimizeResult`` (``x``, ``fun``, ``nfev``, ``nit``, ``success``, ``message``)
    per problem.
    """
    if driver_works():
        return _step_through(objective, starts, bounds, rows)
    return [_one_by_scipy(objective, x0, bnd, rows[j:j + 1])
            for j, (x0, bnd) in enumerate(zip(starts, bounds))]


def _one_by_scipy(objective, x0, bounds, row):
    """One problem of :func:`minimise_together` by ``scipy.optimize.minimize``."""
    def fun(x):
        f, g = objective(np.asarray(x, float)[None], row)
        return float(f[0]), np.asarray(g[0], float)

    lo = [-np.inf if b[0] is None else b[0] for b in bounds]
    hi = [np.inf if b[1] is None else b[1] for b in bounds]
    res = optimize.minimize(fun, np.clip(np.asarray(x0, float), lo, hi), jac=True,
                            method="L-BFGS-B", bounds=bounds)
    return OptimizeResult(x=res.x, fun=float(res.fun), nfev=int(res.nfev), nit=int(res.nit),
                          success=bool(res.success), message=str(res.message))


def _step_through(objective, starts, bounds, rows):
    """:func:`minimise_together` by stepping ``setulb`` (module docs)."""
    n = len(starts[0])
    m = _MAXCOR
    factr = _FTOL / np.finfo(float).eps
    args = []  # per problem setulb's arguments: x at 1, f at 5, g at 6, task at 11
    for x0, bnd in zip(starts, bounds):
        low, up, nbd, lo, hi = _bound_arrays(bnd)
        args.append([m, np.clip(np.asarray(x0, float), lo, hi), low, up, nbd, 0.0, np.zeros(n),
                     factr, _GTOL, np.zeros(2 * m * n + 5 * n + 11 * m * m + 8 * m),
                     np.zeros(3 * n, np.int32), np.zeros(2, np.int32), np.zeros(4, np.int32),
                     np.zeros(44, np.int32), np.zeros(29), _MAXLS, np.zeros(2, np.int32)])
    nfev, nit = np.zeros(len(args), int), np.zeros(len(args), int)
    setulb = _lbfgsb.setulb
    active = list(range(len(args)))
    while active:
        asking = []
        for j in active:
            a = args[j]
            task = a[11]
            setulb(*a)
            while task[0] == 1:  # a new iterate; 3: wants f and g; anything else: stopped
                nit[j] += 1
                if nit[j] >= _MAXITER:
                    task[:] = 5, 504
                elif nfev[j] > _MAXFUN:
                    task[:] = 5, 502
                setulb(*a)
            if task[0] == 3:
                asking.append(j)
        if asking:
            f, g = objective(np.array([args[j][1] for j in asking]), rows[asking])
            for k, j in enumerate(asking):
                args[j][5] = float(f[k])
                args[j][6][:] = g[k]
            nfev[asking] += 1
        active = asking
    return [OptimizeResult(x=a[1], fun=a[5], nfev=int(nfev[j]), nit=int(nit[j]),
                           success=bool(a[11][0] == 4), message=_message(a[11]))
            for j, a in enumerate(args)]


def minimise_one(negloglik_grad, x0, bounds) -> OptimizeResult:
    """:func:`minimise_together` of one problem: ``negloglik_grad(x) -> (value, gradient)``."""
    def objective(X, rows):
        value, grad = negloglik_grad(X[0])
        return (value,), np.asarray(grad, float)[None]

    return minimise_together(objective, [x0], [bounds], np.zeros(1, int))[0]
