"""What the joint fit computes once and shares: the pairs' scores, the cold start, old fits."""

import numpy as np
import pytest
from scipy import stats

from pas.models.copula_densities import (
    GRADIENT_FAMILIES,
    censored_terms,
    logc_grad,
    logh_grad,
    scores,
)
from pas.models.joint import fit_joint, fit_joint_all

RNG = np.random.default_rng(5)
U, V = RNG.uniform(0.002, 0.998, 300), RNG.uniform(0.002, 0.998, 300)
PARAMETERS = {"gaussian": [0.6], "student": [0.5, 6.0], "clayton": [2.0], "gumbel": [1.8],
              "frank": [5.0]}


@pytest.mark.parametrize("family", GRADIENT_FAMILIES)
@pytest.mark.parametrize("kept", [False, True])
def test_censored_terms_are_the_density_and_at_the_censored_the_h_function(family, kept):
    p = PARAMETERS[family]
    censored = np.array([0, 7, 150, 299])
    u_scores = scores(family, p, U) if kept and family != "student" else None
    terms = censored_terms(family, p, U, V, censored, u_scores=u_scores)
    density = np.ones(U.size, dtype=bool)
    density[censored] = False
    for full, dens, cens in zip(terms, logc_grad(family, p, U[density], V[density]),
                                logh_grad(family, p, U[censored], V[censored])):
        np.testing.assert_allclose(full[density], dens, rtol=1e-12)
        np.testing.assert_allclose(full[censored], cens, rtol=1e-12)


def _pairs(n=60, seed=2):
    rng = np.random.default_rng(seed)
    u = np.sort(rng.uniform(0.5, 0.999, n))
    return u, stats.weibull_min(1.4, loc=2.0, scale=3.0).ppf(
        np.clip(u + rng.normal(0, 0.05, n), 0.01, 0.99))


def test_fitting_the_families_together_gives_each_familys_own_fit():
    # the families share one cold start (Kendall τ, the least-squares marginals); each
    # fit must still start from its own marginal's, whichever is asked for first
    from pas.models.joint_starts import DataStarts, _lognormal_start, _weibull_start

    u, h = _pairs()
    for order in (("weibull", "lognormal"), ("lognormal", "weibull")):
        data = DataStarts(u, h, True)
        starts = {m: data.marginal(m) for m in order}
        np.testing.assert_allclose(starts["weibull"], _weibull_start(h, True), rtol=1e-12)
        np.testing.assert_allclose(starts["lognormal"], _lognormal_start(h, True), rtol=1e-12)
    together = fit_joint_all(u, h, ("gaussian", "gumbel"), marginals=("weibull", "lognormal"))
    for (name, marginal), fit in together.items():
        alone = fit_joint(name, u, h, marginal=marginal)
        np.testing.assert_allclose(fit.x, alone.x, rtol=1e-12)
        assert fit.copula.loglik == pytest.approx(alone.copula.loglik, rel=1e-12)


