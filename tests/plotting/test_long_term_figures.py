"""The long-term figures draw what the result holds, and say what is missing."""

import _longterm_problem as problem
import numpy as np
import pytest

import pas
from pas.plotting.long_term import (
    plot_long_term_allocation,
    plot_long_term_convergence,
    plot_long_term_distribution,
    save_long_term_figures,
)


@pytest.fixture(scope="module")
def result():
    table = problem.table(n_waves=2000).assign(hs=4 * problem.SIGMA, tp=1.3 * problem.PERIOD)
    return pas.run_long_term(table, problem.lf_peaks(1, n_waves=2000), problem.Oracle(),
                             p_exceed=1e-3, max_hf=12, seed=4, precision=0.05, model_band=False,
                             strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)))


def test_distribution_draws_the_band_and_the_truth(result):
    truth = problem.true_value(1e-3)
    fig, ax = plot_long_term_distribution(result, truth=truth, unit="kN")
    labels = ax.get_legend_handles_labels()[1]
    assert any(t.startswith("value ") for t in labels) and any("truth" in t for t in labels)
    star = [line for line in ax.get_lines() if line.get_marker() == "*"][0]
    assert star.get_ydata()[0] == pytest.approx(truth)
    assert ax.xaxis_inverted()


def test_allocation_marks_every_sea_state_and_the_hf_it_got(result):
    fig, ax = plot_long_term_allocation(result)
    c = result.contributions
    given, none = ax.collections[1], ax.collections[0]
    assert len(given.get_offsets()) == int((c["n_hf"] > 0).sum())
    assert len(none.get_offsets()) == int((c["n_hf"] == 0).sum())
    texts = sorted(int(t.get_text()) for t in ax.texts)
    assert texts == sorted(c.loc[c["n_hf"] > 0, "n_hf"].tolist())
    with pytest.raises(ValueError, match="no column 'heading'.*sigma, hs, tp"):
        plot_long_term_allocation(result, x="heading")


def test_convergence_draws_the_history_and_the_target(result):
    fig, ax = plot_long_term_convergence(result)
    line = [ln for ln in ax.get_lines() if ln.get_label() == "long-term value"][0]
    pas_rounds = ~result.history["lf_only"].to_numpy()
    assert pas_rounds.any() and not pas_rounds[0]            # round 0: no HF, no PAS model
    assert np.asarray(line.get_ydata())[pas_rounds] == pytest.approx(
        result.history["value"].to_numpy()[pas_rounds])
    assert np.isnan(np.asarray(line.get_ydata())[~pas_rounds]).all()
    assert any("target ±5 %" in t for t in ax.get_legend_handles_labels()[1])


def test_save_writes_the_three_figures(result, tmp_path):
    paths = save_long_term_figures(result, tmp_path / "f")
    assert [p.name for p in paths] == ["long_term_distribution.png", "long_term_allocation.png",
                                       "long_term_convergence.png"]
    assert all(p.stat().st_size > 1000 for p in paths)


@pytest.fixture(scope="module")
def impact_result():
    table = problem.table(n_waves=2000).assign(hs=4 * problem.SIGMA, tp=1.3 * problem.PERIOD)
    return pas.run_long_term(table, problem.lf_peaks(1, n_waves=2000),
                             problem.Oracle(problem.hf_impact), p_exceed=1e-3, max_hf=12, seed=4,
                             precision=0.05, model_band=False,
                             strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)))


def _covers(collection, q, level):
    """True when one of the polygons of a fill_between holds the point (q, level)."""
    from matplotlib.path import Path

    return any(Path(p.vertices).contains_point((q, level), radius=1e-9)
               for p in collection.get_paths())


def test_distribution_draws_no_tight_band_where_the_level_is_an_lf_proxy(impact_result):
    # far above p_exceed the impact load's true level is 0 (no LF peak reaches the impact
    # level that often): a U95 band there must not claim a tight range above it
    q_far = 0.1
    assert problem.true_lf_level(q_far) < problem.IMPACT_LF  # so the true level there is 0
    fig, ax = plot_long_term_distribution(impact_result, unit="kN")
    fills = {c.get_label(): c for c in ax.collections}
    u95 = fills["U95 band"]
    assert not any(_covers(u95, q_far, y) for y in np.linspace(0.5, 30.0, 60))
    proxy = [c for label, c in fills.items() if "LF-proxy" in label]
    assert proxy and _covers(proxy[0], q_far, 0.0)
    # at p_exceed the band is drawn and holds the truth
    truth = problem.true_value(1e-3, problem.hf_impact)
    assert _covers(u95, 1e-3 * 0.99, truth)


def test_convergence_scales_on_the_rounds_with_a_value(result):
    # an impact load reads 0 until a PAS model reaches the level: those rounds must not
    # squash the rest of the history against the top of the axis
    from dataclasses import replace

    h = result.history.copy()
    first = h.index[:3]
    h.loc[first, ["value", "low_sampling", "high_sampling"]] = 0.0
    h.loc[first, ["low", "high", "halfwidth"]] = np.nan
    fig, ax = plot_long_term_convergence(replace(result, history=h), unit="kN")
    rest = h.iloc[3:]
    low, high = ax.get_ylim()
    assert low > 0.5 * rest["low_sampling"].min()
    assert high >= rest["high_sampling"].max()
    marks = [ln for ln in ax.get_lines() if "no PAS model" in ln.get_label()]
    assert len(marks) == 1 and list(marks[0].get_xdata()) == h["n_hf"].iloc[:3].tolist()
    assert ax.get_ylabel().endswith("[kN]")


def test_convergence_keeps_the_lf_only_rounds_off_the_value_axis(result, impact_result):
    # before any sea state has a PAS model the value is the LF-only proxy's, in the LF's
    # unit: the analysis says so per round, and those rounds are marked, not drawn as values
    for res in (result, impact_result):
        h = res.history
        assert "lf_only" in h and h["lf_only"].dtype == bool
        assert not h["lf_only"].iloc[-1]
    from dataclasses import replace

    h = result.history.copy()
    h.loc[h.index[:2], "lf_only"] = True
    h.loc[h.index[:2], "value"] = 1e3 * h["value"].max()     # a level in another unit
    fig, ax = plot_long_term_convergence(replace(result, history=h), unit="kN")
    assert ax.get_ylim()[1] < 10 * result.history["value"].max()
    value_line = [ln for ln in ax.get_lines() if ln.get_label() == "long-term value"][0]
    assert np.isnan(value_line.get_ydata()[:2]).all()
    marks = [ln for ln in ax.get_lines() if "no PAS model" in ln.get_label()]
    assert list(marks[0].get_xdata()) == h["n_hf"].iloc[:2].tolist()
