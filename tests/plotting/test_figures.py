"""Result figures: each type is drawn into a file and checked for real content."""

import dataclasses

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

import pas  # noqa: E402
from pas.plotting import (  # noqa: E402
    conditional_quantile_curves,
    plot_aic,
    plot_distribution,
    plot_metrics,
    plot_mpm_convergence,
    plot_scatter,
)
from pas.stats.dependence import kendall_tau  # noqa: E402
from pas.stats.exceedance import exceedance_probabilities  # noqa: E402

N, NW, P = 3000, 3200, 3e-3


@pytest.fixture(scope="module")
def problem():
    """HF = 1.2 l^1.1 · lognormal noise, no impact below l = 1 (false positives)."""
    rng = np.random.default_rng(3)
    lf = rng.rayleigh(2.0, N)
    hf = np.where(lf < 1.0, 0.0, 1.2 * lf**1.1 * rng.lognormal(0.0, 0.08, N))
    return lf, hf


@pytest.fixture(scope="module")
def result(problem):
    lf, hf = problem
    study = pas.make_study(pas.PAS(band=pas.ModelBand(n_bootstrap=0)), lf, n_waves=NW, p_exp=P,
                           seed=2, max_hf=30, stopping=pas.Stopping(eps1=0.2, k1=9, k2=9),
                           stop_on_convergence=False)
    return study.optimize(lambda ev: hf[ev.index])


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def _save(fig, tmp_path, name):
    """Save ``fig`` and check it holds much more than an empty figure of its size."""
    path = tmp_path / f"{name}.png"
    fig.savefig(path, dpi=80)
    blank = plt.figure(figsize=fig.get_size_inches())
    blank.add_subplot()
    blank_path = tmp_path / f"{name}-blank.png"
    blank.savefig(blank_path, dpi=80)
    assert path.exists() and path.stat().st_size > 1.3 * blank_path.stat().st_size, \
        "figure file is (nearly) empty"
    return path


def _legend_texts(ax):
    leg = ax.get_legend()
    assert leg is not None, "no legend"
    return [t.get_text() for t in leg.get_texts()]


def test_result_has_what_the_figures_show(result):
    # the fixture problem must exercise false positives and convergence
    assert result.n_false_positive >= 1
    assert (result.history["stop"] == True).any()  # noqa: E712 (object column with NaN)


def test_mpm_convergence(result, tmp_path):
    fig, ax = plot_mpm_convergence(result, truth=11.0, unit="m")
    _save(fig, tmp_path, "mpm")
    fitted = result.fitted
    line = ax.get_lines()[0]
    np.testing.assert_allclose(line.get_xdata(), fitted["n_hf"])
    np.testing.assert_allclose(line.get_ydata(), fitted["mpm"])
    # one shaded band, the sampling part per iteration; the reported U95 as an error bar
    bands = [c for c in ax.collections if isinstance(c, matplotlib.collections.PolyCollection)]
    assert len(bands) == 1
    texts = _legend_texts(ax)
    assert any("sampling band" in t for t in texts)
    lo, hi = result.mpm_band
    assert any(f"final U95 {lo:.4g}–{hi:.4g}" in t for t in texts)
    assert any("false positive" in t and f"×{result.n_false_positive}" in t for t in texts)
    assert any("converged at" in t for t in texts)
    assert any("true MPM 11 m" in t for t in texts)
    assert ax.get_ylabel() == "MPM [m]" and "HF samples" in ax.get_xlabel()


def test_mpm_convergence_composes_on_one_axes(result, tmp_path):
    fig, ax = plot_mpm_convergence(result, label="run A")
    fig2, ax2 = plot_mpm_convergence(result, label="run B", ax=ax)
    assert fig2 is fig and ax2 is ax
    texts = _legend_texts(ax)
    assert any(t.startswith("run A") for t in texts) and any(t.startswith("run B") for t in texts)
    assert ax.get_lines()[0].get_color() != [ln for ln in ax.get_lines()
                                             if ln.get_label().startswith("run B: MPM")
                                             ][0].get_color()
    _save(fig, tmp_path, "mpm2")


def test_distribution(problem, result, tmp_path):
    lf, hf = problem
    truth = exceedance_probabilities(hf[hf > 0], NW)
    lfset = pas.LFSet(lf, n_waves=NW, p_exp=P)
    fig, ax = plot_distribution(result, lf=lfset, truth=truth, unit="kN")
    _save(fig, tmp_path, "distribution")
    assert ax.get_xscale() == "log" and ax.xaxis_inverted()
    assert ax.get_ylabel() == "HF load [kN]"
    texts = _legend_texts(ax)
    for needle in ("mean", "U95", "LF indicator", "at its LF exceedance", "truth", "P_{exp}",
                   "MPM"):
        assert any(needle in t for t in texts), needle
    mean_line = ax.get_lines()[0]
    np.testing.assert_allclose(mean_line.get_ydata(), result.distribution["h_mean"])
    # the P_exp marker sits at P_exp and the MPM
    pexp = [ln for ln in ax.get_lines() if "P_{exp}" in ln.get_label()][0]
    assert pexp.get_xdata()[0] == pytest.approx(P)
    # an (d, l) tuple works like an LFSet
    fig2, ax2 = plot_distribution(result, lf=(lfset.d, lfset.lf))
    assert len(ax2.get_lines()) == len(ax.get_lines()) - 1  # no truth line


def test_distribution_rejects_bad_lf(result):
    with pytest.raises(ValueError, match="lf"):
        plot_distribution(result, lf=np.arange(5.0))


def test_scatter_plain_and_with_result(problem, result, tmp_path):
    lf, hf = problem
    fig, ax = plot_scatter(lf, hf, lf_unit="m", unit="m")
    _save(fig, tmp_path, "scatter_plain")
    tau = kendall_tau(lf, hf)
    assert f"rank correlation (Kendall) {tau:.2f}" in ax.get_title()
    assert "tail dependence beyond the 90% quantile: upper " in ax.get_title()
    assert not any(sym in ax.get_title() for sym in ("τ", "λ", "$"))  # words, not symbols
    assert ax.get_xlabel() == "LF indicator peak [m]"

    fig, ax = plot_scatter(lf, hf, result=result, lf_unit="m", unit="m")
    _save(fig, tmp_path, "scatter_result")
    texts = _legend_texts(ax)
    assert any("selected HF samples" in t for t in texts)
    assert any(f"{result.family} copula" in t and "median" in t for t in texts)
    assert any("5%–95%" in t for t in texts)
    sel = [ln for ln in ax.get_lines() if "selected" in ln.get_label()][0]
    assert len(sel.get_xdata()) == len(result.pairs)


def test_conditional_quantile_curves_describe_the_population(problem, result):
    """The refitted copula's 5–95 % band covers most events and its median tracks the law."""
    lf, hf = problem
    l_min = result.pairs["lf"].min()
    grid = np.linspace(l_min, lf.max(), 100)
    q = conditional_quantile_curves(result, grid)
    assert set(q) == {0.05, 0.5, 0.95}
    assert np.all(q[0.05] < q[0.5]) and np.all(q[0.5] < q[0.95])
    # median close to the noise-free law 1.2 l^1.1 over the sampled LF range
    rel = q[0.5] / (1.2 * grid**1.1) - 1.0
    assert np.max(np.abs(rel)) < 0.15
    # coverage of the population events above min(l_sel)
    m = lf >= l_min
    lo = np.interp(lf[m], grid, q[0.05])
    hi = np.interp(lf[m], grid, q[0.95])
    coverage = np.mean((hf[m] >= lo) & (hf[m] <= hi))
    assert 0.7 < coverage <= 1.0


def test_aic_two_panels_and_single(result, tmp_path):
    fig, axes = plot_aic(result)
    _save(fig, tmp_path, "aic")
    top, bottom = axes
    aic_lines = [ln for ln in top.get_lines() if ln.get_linestyle() == "-"]
    assert len(aic_lines) == 5
    assert {ln.get_label() for ln in aic_lines} == set(pas.models.copulas.PAPER_FAMILIES)
    # selected family per iteration: one marker per fitted iteration
    n_marks = sum(len(ln.get_xdata()) for ln in bottom.get_lines())
    assert n_marks == len(result.fitted)
    assert [t.get_text() for t in bottom.get_yticklabels()] == list(
        pas.models.copulas.PAPER_FAMILIES
    )

    fig, ax = plt.subplots()
    fig2, ax2 = plot_aic(result, ax=ax)
    assert ax2 is ax and "AIC" in ax.get_ylabel()


def test_aic_needs_a_pas_result(problem):
    lf, hf = problem
    res = pas.make_study("as", lf, n_waves=NW, p_exp=P, eps1=0.05, seed=2, max_hf=8,
                         stop_on_convergence=False).optimize(lambda ev: hf[ev.index])
    with pytest.raises(ValueError, match="AIC"):
        plot_aic(res)
    # the other figures work for AS too
    plot_mpm_convergence(res)
    plot_distribution(res)
    plot_scatter(lf, hf, result=res)


def test_metrics(tmp_path):
    table = pd.DataFrame({
        "case": ["1a", "1a", "2a", "2a", "3a", "3a"],
        "strategy": ["pas", "as"] * 3,
        "M1": [0.002, 0.001, 0.003, 0.002, 0.01, 0.012],
        "M2": [0.01, -0.03, 0.02, -0.04, 0.05, -0.2],
        "M3": [0.02, -0.05, 0.01, -0.06, 0.1, -0.3],
    })
    fig, axes = plot_metrics(table)
    _save(fig, tmp_path, "metrics")
    assert len(axes) == 3
    for panel, metric in zip(axes, ("M1", "M2", "M3")):
        assert len(panel.patches) == 6
        heights = sorted(p.get_height() for p in panel.patches)
        assert heights == pytest.approx(sorted(100 * table[metric]))
    assert [t.get_text() for t in axes[-1].get_xticklabels()] == ["1a", "2a", "3a"]
    # one legend for the three panels, under the last one
    assert {t.get_text() for t in axes[-1].get_legend().get_texts()} == {"PAS", "AS"}
    assert axes[0].get_legend() is None and axes[1].get_legend() is None

    fig, ax = plt.subplots()
    plot_metrics(table.drop(columns="strategy").iloc[::2], ax=ax)
    _save(fig, tmp_path, "metrics_single")
    assert len(ax.patches) == 9  # 3 cases × 3 metrics

    with pytest.raises(ValueError, match="M3"):
        plot_metrics(table.drop(columns="M3"))


def _overlap(a, b):
    """True when the drawn areas of two Axes overlap (in figure pixels)."""
    a, b = a.get_window_extent(), b.get_window_extent()
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


@pytest.mark.parametrize("own_figure", [True, False])
def test_distribution_draws_the_lf_curve_in_its_own_panel(problem, result, own_figure):
    # the LF indicator (m) and the HF load (kN) are two quantities: never one plot area with
    # two value axes, and no LF curve drawn over the HF curve
    lf, _ = problem
    lfset = pas.LFSet(lf, n_waves=NW, p_exp=P)
    ax = None if own_figure else plt.subplots(figsize=(7, 6), layout="constrained")[1]
    fig, ax = plot_distribution(result, lf=lfset, unit="kN", lf_unit="m", ax=ax)
    fig.canvas.draw()
    assert not any(ln.get_label().startswith("LF indicator") for ln in ax.get_lines())
    assert ax.get_ylabel() == "HF load [kN]"
    others = [a for a in fig.axes if a is not ax] + list(ax.child_axes)
    assert len(others) == 1 and others[0].get_ylabel() == "LF indicator [m]"
    assert not _overlap(ax, others[0])
    np.testing.assert_allclose(others[0].get_lines()[0].get_ydata(), lfset.lf)
    assert others[0].get_xscale() == "log" and others[0].xaxis_inverted()
    texts = _legend_texts(ax)
    assert any(t.startswith("LF indicator") for t in texts)  # one legend for both panels
    assert not any("Eq." in t or "true-positive" in t for t in texts)
    # the same unit shares the value axis
    fig, ax = plot_distribution(result, lf=lfset, unit="m", lf_unit="m")
    assert any(ln.get_label() == "LF indicator" for ln in ax.get_lines()) and len(fig.axes) == 1


def test_distribution_leaves_out_clipped_zeros(result):
    # a mean of exactly 0 where no evaluated event gave 0: draws clipped at the HF
    # marginal's lower bound, not a prediction
    dist = result.distribution.copy()
    dist = dist[dist["h_mean"] > 0].reset_index(drop=True)  # no draw of "no impact" here
    dist.loc[dist.index[-25:], ["h_mean", "h_low", "h_high"]] = 0.0
    clipped = dataclasses.replace(result, distribution=dist, n_false_positive=0)
    d0 = dist["exceedance_probability"].iloc[-25]
    assert clipped.clipped_from == d0 and result.clipped_from is None
    assert clipped.to_dict()["clipped_from"] == d0
    fig, ax = plot_distribution(clipped)
    y = ax.get_lines()[0].get_ydata()
    assert np.isnan(y[-25:]).all() and np.isfinite(y[:-25]).all()
    assert any(f"not drawn for d ≥ {d0:.2g}" in t for t in _legend_texts(ax))
    # with evaluated false positives a zero is a value and is drawn
    fig, ax = plot_distribution(dataclasses.replace(clipped, n_false_positive=1))
    assert np.isfinite(ax.get_lines()[0].get_ydata()).all()


def test_scatter_reports_tail_dependence_only_from_enough_points(problem):
    lf, hf = problem
    fig, ax = plot_scatter(lf[:26], hf[:26])
    title = ax.get_title()
    assert "tail dependence not estimated: 2 of 26 pairs beyond the 90% quantile" in title
    assert "= 1.00" not in title and "= 0.00" not in title
    fig, ax = plot_scatter(lf[:100], hf[:100])
    assert "upper " in ax.get_title() and "lower " in ax.get_title()


def test_aic_says_why_the_lowest_aic_was_not_selected(result):
    hist = result.history.copy()
    fitted = hist["mpm"].notna()
    hist["ineligible"] = ""  # this test decides alone which fits were at a bound
    rows = hist.index[fitted][2:6]
    # rows 2-3: the lowest AIC is a family at its bound; rows 4-5: within the hysteresis
    for k, r in enumerate(rows):
        other = "student" if hist.at[r, "family"] != "student" else "gaussian"
        hist.at[r, f"aic_{other}"] = (
            hist.loc[r, [c for c in hist if c.startswith("aic_")]].min() - 1
        )
        hist.at[r, "ineligible"] = other if k < 2 else ""
    fig, (top, bottom) = plot_aic(dataclasses.replace(result, history=hist))
    texts = _legend_texts(bottom)  # one legend, under the lower panel
    assert "lowest AIC, not selected: parameter at its bound (not eligible) ×2" in texts
    hysteresis = [t for t in texts if "less than ΔAIC below the current family" in t]
    assert len(hysteresis) == 1 and int(hysteresis[0].rsplit("×", 1)[1]) >= 2
    marks = [ln for ln in top.get_lines() if ln.get_label().startswith("lowest AIC, not selected: "
                                                                       "parameter")][0]
    np.testing.assert_allclose(marks.get_xdata(), hist.loc[rows[:2], "n_hf"])


def test_metrics_of_one_case_are_labelled_bars(tmp_path):
    table = pd.DataFrame({"case": ["1a", "1a"], "strategy": ["pas", "as"], "M1": [6e-4, 5e-4],
                          "M2": [0.0264, -0.0085], "M3": [0.0294, 0.0178]})
    fig, axes = plot_metrics(table)
    _save(fig, tmp_path, "metrics_one")
    for panel, metric in zip(axes, ("M1", "M2", "M3")):
        assert all(p.get_width() <= 0.3 for p in panel.patches)
        labels = [t.get_text() for t in panel.texts]
        assert labels == [f"{100 * v:.3g}%" for v in table[metric]]
