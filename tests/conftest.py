"""Known-truth problems shared by the end-to-end tests.

Each problem returns the LF peaks, the HF value of every event (revealed to PAS
only through the oracle), ``n_w``, ``P_exp`` and a truth computed independently
of the code under test.
"""

import numpy as np
import pytest
import pyvinecopulib as pv
from scipy import stats

# Doctests cannot carry a marker.  These examples run a PAS study with its bootstrap band
# (about 10 s), so the fast path (``pytest -m "not slow"``) leaves them out; their functions
# keep fast tests in tests/.  tests/test_markers.py checks each name still has an example.
SLOW_DOCTESTS = frozenset({"pas.api.run_pas"})


def pytest_collection_modifyitems(config, items):
    """Mark the doctests in ``SLOW_DOCTESTS`` slow (seen when ``tests/`` is collected too)."""
    for item in items:
        if isinstance(item, pytest.DoctestItem) and item.name in SLOW_DOCTESTS:
            item.add_marker(pytest.mark.slow)


def empirical_at(values, n_waves, p):
    """Empirical exceedance value at ``p`` (d = k / n_w, interpolated on ln d)."""
    v = np.sort(np.asarray(values, float))[::-1]
    d = np.arange(1, v.size + 1) / n_waves
    return float(np.interp(np.log(p), np.log(d), v))


def monotone_problem(n=6000, n_waves=6500, p_exp=2.5e-3, seed=0):
    """HF a strictly increasing function of LF: the truth is the mapped LF quantile."""
    lf = np.random.default_rng(seed).rayleigh(2.0, n)
    g = lambda x: 1.2 * x**1.1 + 0.05 * x**2  # noqa: E731
    truth = g(empirical_at(lf, n_waves, p_exp))
    return lf, g(lf), n_waves, p_exp, truth


def gumbel_problem(n=8000, n_waves=9000, p_exp=2.5e-3, theta=3.0, seed=0):
    """Pairs from a Gumbel copula with Weibull marginals.

    Every event's HF value has the marginal ``hf_m``, so the population
    exceedance per encounter is ``(n / n_w) · sf(h)`` and the truth is
    ``hf_m.isf(P_exp · n_w / n)`` — exact, no sample needed.
    """
    lf_m = stats.weibull_min(2.0, scale=3.0)
    hf_m = stats.weibull_min(1.5, scale=100.0)
    cop = pv.Bicop(family=pv.BicopFamily.gumbel, parameters=np.array([[theta]]))
    uv = cop.sample(n, seeds=[seed + 7])
    return (
        lf_m.ppf(uv[:, 0]),
        hf_m.ppf(uv[:, 1]),
        n_waves,
        p_exp,
        float(hf_m.isf(p_exp * n_waves / n)),
    )


def threshold_problem(n=6000, n_waves=20000, p_exp=1e-3, seed=0):
    """Green-water-like: no load unless a noisy LF exceeds a freeboard.

    LF peaks over a 3 m threshold; HF = 0 (false positive) unless
    ``l + noise > 4 m``, then a momentum-like ``50 (l + noise − 4)^1.5 + noise``.
    The truth is the empirical value of the full HF set at ``P_exp``.
    """
    rng = np.random.default_rng(seed)
    lf = rng.rayleigh(1.3, n) + 0.5
    excess = lf + rng.normal(0, 0.35, n) - 4.0
    hf = np.where(excess > 0, 50 * np.clip(excess, 0, None) ** 1.5 * rng.lognormal(0, 0.15, n), 0.0)
    truth = empirical_at(hf, n_waves, p_exp)
    return lf, hf, n_waves, p_exp, truth


@pytest.fixture
def table_oracle():
    def make(hf):
        calls = []

        def oracle(ev):
            calls.append(ev.index)
            return hf[ev.index]

        oracle.calls = calls
        return oracle

    return make


def no_band(**settings):
    """PAS without the model band (a faster test): ``PAS(band=ModelBand(n_bootstrap=0), ...)``."""
    from pas import PAS, ModelBand

    return PAS(band=ModelBand(n_bootstrap=0), **settings)

