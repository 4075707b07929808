"""Adaptive Screening (AS): the GPR comparison strategy of paper App. A (Eq. 20).

AS shares steps 1–6 with PAS (the LF screening set, the HF oracle, false
positives, the stopping rule: all in :mod:`pas.study`) and differs in three
steps, implemented here as plain functions strung together by :class:`AS`:

* **Step 7, order statistics.**  Each true-positive HF sample gets the LF
  exceedance probability of its event, ``d_H^sel ≈ d_L^sel``.  This is the
  screening assumption: when the indicator ranks events differently from the
  HF load (noise, timing, a different non-linearity) the HF tail is
  under-predicted, because the HF sample at LF rank ``k`` is a typical HF
  value of that LF level, not the ``k``-th largest HF value.
* **Step 8, range.**  The surrogate is evaluated on ``d*``, ``n_grid`` points
  uniform on ``ln d`` over ``[P_exp / range_factor, P_exp · range_factor]``
  (``range_factor = 10``) clipped to the LF exceedance range
  ``[d_L[0], d_L[-1]]`` (:func:`prediction_grid`).  It contains the stopping
  window ``[P_exp/2, 2 P_exp]`` of App. C whenever the LF pool reaches it.
* **Step 9, GPR.**  ``h`` over ``ln d`` with scikit-learn's
  :class:`~sklearn.gaussian_process.GaussianProcessRegressor` (kernel
  ``C · Matérn(ν = 5/2) + White`` on standardised targets, hyper-parameters by
  maximum marginal likelihood; the length scale is bounded below by
  ``LENGTH_MIN = 0.5`` in ``ln d`` units — an exceedance curve does not bend
  on a shorter scale, and without the bound noisy HF samples clustered by
  MVPD (spacing ≈ 1/k on ``ln d``) were fitted with length ≈ 0.02, the mean
  falling back to the prior between samples: one seeded noisy run gave −31 %
  instead of −14 %):

  - ``fidelity="single"``: one GP on ``[ln d_sel, h_sel]``;
  - ``fidelity="multi"`` (default, as in the paper): the autoregressive
    Kennedy–O'Hagan / Forrester model ``h(x) ≈ ρ · μ_L(x) + δ(x)``.  The low
    level ``GP_L`` is fitted to the LF curve ``[ln d_L, l]`` *thinned* to
    binned means on ``n_lf_bins`` (200) bins uniform on ``ln d``
    (:func:`thin_lf_curve`) — never to all ``n`` LF peaks, so the cost is
    ``O(n_lf_bins³)`` once per study, not ``O(n³)``.  ``GP_L`` depends only on
    the LF pool and is fitted once per :class:`~pas.strategies.screening.LFSet` and
    cached.  ``ρ`` is the ordinary least-squares slope of ``h_sel`` on
    ``μ_L(ln d_sel)`` (with intercept), a two-stage simplification of
    Forrester's joint likelihood estimate; ``δ`` is a GP on the residuals
    ``h_sel − ρ μ_L(ln d_sel)`` (its constant mean, from the target standardisation, is
    the intercept).

  The 95 % band is that of the *latent* curve: ``mean ± 1.96 σ`` with the
  fitted white-noise variance taken out of the GP's predictive variance (the
  band of the distribution, like PAS's band of the mean distribution, not of
  a new noisy observation); in the multi-fidelity model
  ``σ² = ρ² σ_L² + σ_δ²``.

Acquisition MVPD (Eq. 20): ``f1 = 1 − (ln d* − ln P_exp)²``,
``f2 = f1 − min f1`` and the target is ``argmax[h̄*_n · f2 / max f2]``, where
``h̄*_n`` is the previous iteration's mean prediction on ``d*`` normalised to
``[0, 1]`` by its minimum and maximum over ``d*`` (all ones when it is flat);
the nearest available LF pool peak on ``ln d`` is sampled
(:func:`mvpd_select`).

Every fit and prediction here runs under a one-thread BLAS limit
(:func:`pas._support.threads.one_blas_thread`: small GP matrices lose a lot to BLAS
threads on a loaded machine).
scikit-learn's ``ConvergenceWarning`` (a hyper-parameter at its bound, common
with a handful of samples) is silenced inside the fits.
"""

from __future__ import annotations

import warnings

import numpy as np
from sklearn.exceptions import ConvergenceWarning
from sklearn.gaussian_process import GaussianProcessRegressor
from sklearn.gaussian_process.kernels import ConstantKernel, Matern, WhiteKernel

from .._support.checks import check_option, check_positive, check_positive_int
from .._support.threads import one_blas_thread
from ..stats.dependence import kendall_tau
from .acquisition import nearest_available
from .base import Pairs, Prediction, Strategy, band95
from .screening import LFSet

__all__ = [
    "AS",
    "prediction_grid",
    "thin_lf_curve",
    "mvpd_score",
    "mvpd_select",
]

FIDELITIES = ("single", "multi")
LENGTH_MIN = 0.5


def prediction_grid(lfset: LFSet, *, range_factor: float = 10.0, n_grid: int = 101) -> np.ndarray:
    """Step 8: the exceedance probabilities ``d*`` of the surrogate, ascending.

    ``n_grid`` points uniform on ``ln d`` over
    ``[P_exp / range_factor, P_exp · range_factor]`` clipped to the LF pool's
    range ``[d_L[0], d_L[-1]]``.
    """
    lo = max(lfset.p_exp / range_factor, lfset.d[0])
    hi = min(lfset.p_exp * range_factor, lfset.d[-1])
    return np.geomspace(lo, hi, n_grid)


def thin_lf_curve(ln_d, lf, *, n_bins: int = 200):
    """Thin the LF curve ``[ln d_L, l]`` to binned means for ``GP_L`` (Step 9).

    The ``ln d`` range is cut into ``n_bins`` equal bins; each non-empty bin
    gives the mean ``ln d`` and mean ``l`` of its peaks.  In the rare tail the
    bins hold single peaks (kept as they are); in the bulk they average
    hundreds.  Returns ``(x, y)`` with at most ``n_bins`` points, ``x``
    ascending.

    Examples
    --------
    >>> x, y = thin_lf_curve([-4.0, -3.0, -1.0, 0.0], [4.0, 3.0, 2.0, 1.0], n_bins=2)
    >>> np.round(y, 3).tolist()
    [3.5, 1.5]
    """
    ln_d = np.asarray(ln_d, dtype=float)
    lf = np.asarray(lf, dtype=float)
    n_bins = check_positive_int(n_bins, "n_lf_bins")
    lo, hi = ln_d.min(), ln_d.max()
    if hi == lo:
        return np.array([lo]), np.array([lf.mean()])
    b = np.minimum(((ln_d - lo) / (hi - lo) * n_bins).astype(int), n_bins - 1)
    cnt = np.bincount(b, minlength=n_bins)
    keep = cnt > 0
    x = np.bincount(b, ln_d, n_bins)[keep] / cnt[keep]
    y = np.bincount(b, lf, n_bins)[keep] / cnt[keep]
    return x, y


def _kernel(length_bounds=(LENGTH_MIN, 1e2), noise_bounds=(1e-10, 1.0)):
    return (ConstantKernel(1.0, (1e-3, 1e3)) * Matern(1.0, length_bounds, nu=2.5)
            + WhiteKernel(1e-4, noise_bounds))


class _GP:
    """A scikit-learn GP on standardised targets (so the white noise has known units)."""

    def __init__(self, x, y, *, noise_bounds, n_restarts, random_state):
        y = np.asarray(y, dtype=float)
        self.y_mean = float(y.mean())
        self.y_std = float(y.std()) or 1.0
        self.gp = GaussianProcessRegressor(_kernel(noise_bounds=noise_bounds), normalize_y=False,
                                           n_restarts_optimizer=n_restarts,
                                           random_state=random_state)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)
            self.gp.fit(np.asarray(x, float)[:, None], (y - self.y_mean) / self.y_std)
        self.kernel_ = self.gp.kernel_

    def mean(self, x) -> np.ndarray:
        return self.y_mean + self.y_std * self.gp.predict(np.asarray(x, float)[:, None])

    def latent(self, x):
        """Mean and latent standard deviation (fitted white noise removed) at ``x``."""
        mean, sd = self.gp.predict(np.asarray(x, float)[:, None], return_std=True)
        var = np.maximum(sd**2 - self.kernel_.k2.noise_level, 0.0)
        return self.y_mean + self.y_std * mean, self.y_std * np.sqrt(var)


def mvpd_score(d, h_mean, p_exp: float) -> np.ndarray:
    """The MVPD objective of Eq. 20 on the prediction grid ``d*``.

    ``h̄*_n · f2 / max f2`` with ``f1 = 1 − (ln d* − ln P_exp)²``,
    ``f2 = f1 − min f1`` and ``h̄*_n`` the mean prediction normalised to
    ``[0, 1]`` over ``d*`` (ones when the prediction is flat).

    Examples
    --------
    >>> d = 1e-3 * np.exp([-2.0, -1.0, 0.0, 1.0, 2.0])
    >>> np.round(mvpd_score(d, [10.0, 9.0, 6.0, 5.0, 2.0], 1e-3), 5).tolist()
    [0.0, 0.65625, 0.5, 0.28125, 0.0]
    """
    ln_d = np.log(np.asarray(d, dtype=float))
    h = np.asarray(h_mean, dtype=float)
    f1 = 1.0 - (ln_d - np.log(p_exp)) ** 2
    f2 = f1 - f1.min()
    f2 = f2 / f2.max() if f2.max() > 0 else np.ones_like(f2)
    span = np.ptp(h)
    h_n = (h - h.min()) / span if span > 0 else np.ones_like(h)
    return h_n * f2


def mvpd_select(ln_d, available, d, h_mean, p_exp: float, q: int = 1) -> list[int]:
    """MVPD acquisition (Eq. 20): the ``q`` pool positions for the best targets.

    Grid points of ``d*`` are taken in descending :func:`mvpd_score`; each is
    mapped to the nearest still-available pool peak on ``ln d``
    (:func:`~pas.strategies.acquisition.nearest_available`), which then
    becomes unavailable, until ``q`` distinct positions are chosen (fewer when
    the pool runs out).

    Parameters
    ----------
    ln_d : ndarray
        ``ln d`` of the whole pool, ascending.
    available : ndarray of bool
        Pool positions that may be chosen.
    d, h_mean : array-like
        The previous iteration's prediction grid ``d*`` and mean prediction.
    p_exp : float
        Target exceedance probability.
    q : int, default 1
        Batch size.
    """
    score = mvpd_score(d, h_mean, p_exp)
    targets = np.log(np.asarray(d, dtype=float))[np.argsort(-score, kind="stable")]
    available = np.array(available, dtype=bool, copy=True)
    out: list[int] = []
    for t in targets:
        if len(out) >= q:
            break
        p = nearest_available(ln_d, available, t)
        if p < 0:
            break
        out.append(p)
        available[p] = False
    return out


class _LFModel:
    """``GP_L`` on the thinned LF curve of one LF set, with its prediction on ``d*``."""

    def __init__(self, lfset: LFSet, grid, *, n_bins, n_restarts, random_state):
        self.lfset = lfset
        x, y = thin_lf_curve(lfset.ln_d, lfset.lf, n_bins=n_bins)
        self.n_points = x.size
        self.grid = grid
        self.gp = _GP(x, y, noise_bounds=(1e-10, 1e-1), n_restarts=n_restarts,
                      random_state=random_state)
        self.mu_grid, self.sd_grid = self.gp.latent(np.log(grid))
        self._mu_pos: dict[int, float] = {}

    def at_positions(self, positions) -> np.ndarray:
        """``μ_L`` at pool positions (memoised: positions recur every iteration)."""
        new = [int(p) for p in positions if int(p) not in self._mu_pos]
        if new:
            mu = self.gp.mean(self.lfset.ln_d[new])
            self._mu_pos.update(zip(new, mu.tolist()))
        return np.array([self._mu_pos[int(p)] for p in positions], dtype=float)


class AS(Strategy):
    """Adaptive Screening: GPR of HF over ``ln d`` with MVPD acquisition (App. A).

    Steps 1–6 (screening, HF oracle, false positives) and the stopping rule
    are those of PAS, run by :class:`~pas.study.study.Study`; this class does
    Steps 7–9 (order statistics, range ``d*``, GPR) and Eq. 20.  See the
    module docs for every modelling choice.

    Parameters
    ----------
    fidelity : {"multi", "single"}, default "multi"
        Multi-fidelity (autoregressive, LF curve as low level; the paper's
        choice) or single-fidelity GPR.
    range_factor : float, default 10.0
        ``d*`` spans ``[P_exp / range_factor, P_exp · range_factor]``
        clipped to the LF range (Step 8); must be ≥ 2 so the App. C window fits.
    n_grid : int, default 101
        Points of ``d*``, uniform on ``ln d``.
    n_lf_bins : int, default 200
        Bins of the thinned LF curve for ``GP_L`` (multi-fidelity only).
    n_restarts : int, default 0
        Extra random restarts of the hyper-parameter optimiser per GP fit.

    Attributes
    ----------
    lf_model_ : object or None
        The cached ``GP_L`` (multi-fidelity), fitted on first use per LF set.

    Examples
    --------
    >>> import numpy as np, pas
    >>> lf = np.random.default_rng(0).rayleigh(1.0, 3000)
    >>> res = pas.run_as(lf, lambda ev: 1.2 * ev.lf ** 1.1, n_waves=3000, p_exp=1e-2,
    ...                  eps1=0.05, seed=1, max_hf=30)
    >>> res.strategy
    'as'
    """

    name = "as"
    n_initial = 2
    min_pairs = 2
    spreads_samples = False  # MVPD clusters samples near P_exp

    def __init__(self, *, fidelity: str = "multi", range_factor: float = 10.0, n_grid: int = 101,
                 n_lf_bins: int = 200, n_restarts: int = 0):
        self.fidelity = check_option(fidelity, "fidelity", FIDELITIES)
        self.range_factor = check_positive(range_factor, "range_factor")
        if self.range_factor < 2.0:
            raise ValueError(f"range_factor must be ≥ 2 so d* covers the stopping window "
                             f"[P_exp/2, 2 P_exp], got {range_factor!r}")
        self.n_grid = check_positive_int(n_grid, "n_grid")
        if self.n_grid < 3:
            raise ValueError(f"n_grid must be at least 3, got {n_grid!r}")
        self.n_lf_bins = check_positive_int(n_lf_bins, "n_lf_bins")
        if self.n_lf_bins < 5:
            raise ValueError(f"n_lf_bins must be at least 5, got {n_lf_bins!r}")
        if isinstance(n_restarts, bool) or int(n_restarts) != n_restarts or n_restarts < 0:
            raise ValueError(f"n_restarts must be a non-negative integer, got {n_restarts!r}")
        self.n_restarts = int(n_restarts)
        self.lf_model_ = None

    def reset(self, seed: int | None = None) -> None:
        self.lf_model_ = None

    def _lf_model(self, lfset: LFSet, grid, rng) -> _LFModel:
        m = self.lf_model_
        if m is None or m.lfset is not lfset or not np.array_equal(m.grid, grid):
            m = _LFModel(lfset, grid, n_bins=self.n_lf_bins, n_restarts=self.n_restarts,
                         random_state=int(rng.integers(2**31)))
            self.lf_model_ = m
        return m

    def predict(self, pairs: Pairs, lfset: LFSet, rng: np.random.Generator) -> Prediction:
        """Steps 7–9: GPR surrogate of the HF distribution on ``d*`` and its MPM.

        Parameters
        ----------
        pairs : Pairs
            True-positive LF–HF pairs (at least 2); ``pairs.d`` is the LF
            exceedance probability each HF sample is given (Step 7).
        lfset : LFSet
            The LF pool (for ``P_exp``, the range and ``GP_L``).
        rng : numpy.random.Generator
            Seeds the optimiser restarts (only used with ``n_restarts > 0``).
        """
        if len(pairs) < 2:
            raise ValueError(f"AS needs at least 2 true-positive pairs, got {len(pairs)}")
        grid = prediction_grid(lfset, range_factor=self.range_factor, n_grid=self.n_grid)
        x_sel = np.log(pairs.d)                      # Step 7: d_H^sel ≈ d_L^sel
        h_sel = np.asarray(pairs.hf, dtype=float)
        x_grid = np.log(grid)
        record = {"fidelity": self.fidelity, "tau": kendall_tau(pairs.lf, pairs.hf)}
        with one_blas_thread():
            if self.fidelity == "single":
                gp = _GP(x_sel, h_sel, noise_bounds=(1e-10, 1.0), n_restarts=self.n_restarts,
                         random_state=int(rng.integers(2**31)))
                mean, sd = gp.latent(x_grid)
                rho = float("nan")
            else:
                lf_model = self._lf_model(lfset, grid, rng)
                mu_sel = lf_model.at_positions(pairs.position)
                var_mu = np.var(mu_sel)
                rho = float(np.cov(mu_sel, h_sel, bias=True)[0, 1] / var_mu) if var_mu > 0 else 0.0
                gp = _GP(x_sel, h_sel - rho * mu_sel, noise_bounds=(1e-10, 1.0),
                         n_restarts=self.n_restarts, random_state=int(rng.integers(2**31)))
                delta, sd_delta = gp.latent(x_grid)
                mean = rho * lf_model.mu_grid + delta
                sd = np.sqrt(rho**2 * lf_model.sd_grid**2 + sd_delta**2)
                record["kernel_lf"] = str(lf_model.gp.kernel_)
                record["n_lf_points"] = lf_model.n_points
        record["kernel"] = str(gp.kernel_)
        record["rho"] = rho
        return Prediction.read_at(lfset.p_exp, grid, mean, *band95(mean, sd), record)

    def propose(self, selected_d, lfset: LFSet, available: np.ndarray,
                last: Prediction | None, q: int = 1) -> list[int]:
        """Next ``q`` positions by MVPD (Eq. 20) on the previous prediction.

        Falls back to the base MD acquisition (Eq. 16–17) while there is no
        prediction yet (e.g. an initial sample was a false positive).
        """
        if q <= 0:
            return []
        if last is None:
            return super().propose(selected_d, lfset, available, last, q)
        return mvpd_select(lfset.ln_d, available, last.d, last.h_mean, lfset.p_exp, q)
