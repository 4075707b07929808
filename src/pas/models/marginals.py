"""Marginal distributions between copula space and physical space (paper §2.3).

PAS needs parametric marginals only to interpolate conditional copula draws
back to physical loads (Step 9).  Both the LF and the HF marginal are
three-parameter Weibull distributions fitted by least squares
(:func:`pas.stats.weibull.fit_weibull3_ls`); without an LF threshold the
paper's upper-tail mode fits only the upper part of larger samples.
"""

from __future__ import annotations

from ..stats.weibull import Weibull3, fit_weibull3_ls, upper_tail_fraction

__all__ = ["fit_marginal"]


def fit_marginal(values, *, upper_tail: bool) -> Weibull3:
    """Fit the 3-parameter Weibull marginal of one fidelity level (§2.3).

    Parameters
    ----------
    values : array-like
        The selected LF or HF samples (pairs in use this iteration).
    upper_tail : bool
        Apply the upper-tail mode (:func:`~pas.stats.weibull.upper_tail_fraction`):
        the paper uses it when no LF threshold is set, and fits all data when
        a threshold is given.
    """
    n = len(values)
    frac = upper_tail_fraction(n) if upper_tail else 1.0
    return fit_weibull3_ls(values, top_fraction=frac)
