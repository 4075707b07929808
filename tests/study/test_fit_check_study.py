"""A precision study does not take its band for the precision while its fitted model fails the
fit check on the evaluated loads; the transforms the check reads are the model's own."""

import warnings

import numpy as np
import pytest
from scipy import stats

import pas
from pas import PAS, ModelBand, Stopping
from pas.stats.fit_check import uniform_check

N = 20_000
LF = np.random.default_rng(1).rayleigh(1.0, N)
SECOND = np.random.default_rng(2).random(N) < 0.5
SCATTER = np.exp(0.05 * np.random.default_rng(3).standard_normal(N))
MAX_HF = 50
FAST = PAS(z=5, families=("gaussian", "gumbel"),
           band=ModelBand(n_bootstrap=12, marginals="fitted"))


def two_branches(ev):
    """Loads on two branches, LF² and 6 LF²: no copula and HF marginal can follow both."""
    return float(np.where(SECOND[ev.index], 6.0, 1.0) * LF[ev.index] ** 2 * SCATTER[ev.index])


def one_branch(ev):
    return float(LF[ev.index] ** 2 * SCATTER[ev.index])


def run(oracle, **stopping):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return pas.run_pas(LF, oracle, n_waves=N, p_exp=1e-3, seed=0, max_hf=MAX_HF,
                           strategy=FAST, stopping=Stopping(k2=20, **stopping))


@pytest.fixture(scope="module")
def checked():
    return run(two_branches, precision=0.9)


def test_without_the_check_the_band_alone_stops_the_misfitting_model():
    res = run(two_branches, precision=0.9, fit_check=None)
    assert res.converged and res.n_hf < MAX_HF
    assert "fit_check_p" not in res.history


def test_the_check_keeps_that_band_from_being_taken_for_the_precision(checked):
    assert not checked.converged and checked.n_hf == MAX_HF
    failed = checked.history["fit_misfit"].notna()
    assert failed.sum() >= 5 and (checked.history.loc[failed, "fit_check_p"] < 0.01).all()
    line = checked.summary().splitlines()[0]
    assert "NOT converged" in line and "failed the fit check" in line


def test_a_right_model_passes_the_check_and_stops_as_it_would_without_it():
    res = run(one_branch, precision=0.9)
    assert res.converged and res.n_hf < MAX_HF
    assert (res.history["fit_check_p"].dropna() >= 0.01).all()
    # the check draws nothing and held nothing back: the study is the one without it
    plain = run(one_branch, precision=0.9, fit_check=None)
    assert (plain.n_hf, plain.mpm, plain.mpm_band) == (res.n_hf, res.mpm, res.mpm_band)


def test_the_transforms_are_the_gaussian_copulas_conditional_law():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        study = pas.make_study(pas.PAS(families=("gaussian",)), LF, n_waves=N, p_exp=1e-3,
                               eps1=1e-9, max_hf=30, seed=0)
        study.optimize(one_branch)
    model, pairs = study.strategy.model_, study.pairs()
    rho = float(model.copula.parameters[0])
    u = model.u_cond[pairs.position]
    v = model.hf_marginal.cdf(pairs.hf)
    closed = stats.norm.cdf((stats.norm.ppf(v) - rho * stats.norm.ppf(u)) / np.sqrt(1 - rho**2))
    np.testing.assert_allclose(model.transforms(pairs), closed, atol=1e-9)
    assert not uniform_check(model.transforms(pairs)).rejects(0.01)
