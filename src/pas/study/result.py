"""The result of a screening study: MPM, bands, distribution and full history."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..stats.exceedance import quantile_exceedance, value_at_exceedance

__all__ = ["ScreeningResult"]


@dataclass
class ScreeningResult:
    """What :func:`pas.run_pas` and :func:`pas.run_as` return.

    Attributes
    ----------
    mpm : float
        Most probable maximum at ``p_exp`` from the mean distribution (Eq. 12).
    mpm_band : tuple of float
        U95 of the MPM including model uncertainty: the union of the paper's
        z-draw band and the bootstrap band over the LF–HF pairs.
    mpm_band_sampling : tuple of float
        The paper's band, ``h* ± 1.96 σ_b`` read at ``p_exp`` (Eq. 10).
    mpm_band_model : tuple of float or None
        2.5–97.5 % of bootstrap MPMs (pairs resampled, model refitted).
    n_hf : int
        HF evaluations made, false positives included, failures excluded.
    n_false_positive, n_failed : int
        False positives (HF = 0) and failed oracle calls.
    converged : bool
        Whether the stopping criterion was met.
    history : pandas.DataFrame
        One row per HF evaluation (the evaluation sequence), with the fit of
        that iteration where one was made.
    distribution : pandas.DataFrame
        ``exceedance_probability``, ``h_mean``, ``h_low``, ``h_high``.
    pairs : pandas.DataFrame
        The true-positive LF–HF pairs.
    range_curves : pandas.DataFrame
        Mean distribution of every fitted iteration on the stopping range
        ``[P_exp/2, 2 P_exp]`` (columns are the probabilities), indexed by
        history row; used by the metrics M2/M3.
    """

    strategy: str
    mpm: float
    mpm_band: tuple
    mpm_band_sampling: tuple
    mpm_band_model: tuple | None
    n_hf: int
    n_false_positive: int
    n_failed: int
    converged: bool
    history: pd.DataFrame
    distribution: pd.DataFrame
    pairs: pd.DataFrame
    range_curves: pd.DataFrame
    p_exp: float
    n_waves: int
    seed: int
    family: str | None = None
    settings: dict = field(default_factory=dict)

    @property
    def fitted(self) -> pd.DataFrame:
        """History rows where a model was fitted (true-positive iterations)."""
        return self.history[self.history["mpm"].notna()]

    def value_at(self, p):
        """Mean predicted HF value at exceedance probability ``p`` (per encounter)."""
        d = self.distribution["exceedance_probability"].to_numpy()
        if not len(d):
            raise ValueError("the result has no predicted distribution yet")
        return value_at_exceedance(d, self.distribution["h_mean"].to_numpy(), p)

    def quantile(self, q: float) -> float:
        """The ``q``-quantile of the maximum over the exposure duration.

        With ``n_exp = 1 / P_exp`` encounters in the exposure, ``P(max ≤ h) =
        (1 − d(h))^{n_exp} = q`` gives ``d = 1 − q^{P_exp}``
        (:func:`pas.stats.exceedance.quantile_exceedance` with ``m/n = P_exp``).
        ``q = e^{-1}`` is the MPM level; ``q = 0.9`` a common design quantile.
        """
        return float(self.value_at(quantile_exceedance(q, self.p_exp, 1.0)))

    def summary(self) -> str:
        """A few human-readable lines."""
        lo, hi = self.mpm_band
        fam = f", copula {self.family}" if self.family else ""
        state = "converged" if self.converged else "NOT converged"
        return (f"{self.strategy.upper()}: MPM {self.mpm:.4g} (U95 {lo:.4g} – {hi:.4g}){fam}; "
                f"{self.n_hf} HF evaluations ({self.n_false_positive} false positive, "
                f"{self.n_failed} failed); {state}")

    def __repr__(self) -> str:
        return f"<ScreeningResult {self.summary()}>"

    def to_dict(self) -> dict:
        """JSON-friendly scalar summary."""
        return {
            "strategy": self.strategy, "mpm": self.mpm, "mpm_band": list(self.mpm_band),
            "mpm_band_sampling": list(self.mpm_band_sampling),
            "mpm_band_model": None if self.mpm_band_model is None else list(self.mpm_band_model),
            "n_hf": self.n_hf, "n_false_positive": self.n_false_positive,
            "n_failed": self.n_failed, "converged": self.converged, "family": self.family,
            "p_exp": self.p_exp, "n_waves": self.n_waves, "seed": self.seed,
        }


def distribution_frame(d, mean, low, high) -> pd.DataFrame:
    return pd.DataFrame({"exceedance_probability": np.asarray(d), "h_mean": mean,
                         "h_low": low, "h_high": high})
