"""Figures read right: legends readable and off the curves, the stop of a study
visible, ΔAIC to the selected family, samples and design waves labelled for what they are."""

import dataclasses
from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

import pas  # noqa: E402
from pas.plotting import (  # noqa: E402
    plot_aic,
    plot_design_points,
    plot_distribution,
    plot_metrics,
    plot_mpm_convergence,
    plot_scatter,
)
from pas.stats.exceedance import exceedance_probabilities  # noqa: E402
from pas.study.oracles import OracleFailureLimit  # noqa: E402
from pas.study.result import ScreeningResult  # noqa: E402

N, NW, P = 1500, 1600, 4e-3


@pytest.fixture(scope="module")
def problem():
    """HF = 120 l^1.1 · lognormal noise [kN], no impact below l = 1 (false positives)."""
    rng = np.random.default_rng(11)
    lf = rng.rayleigh(2.0, N)
    hf = np.where(lf < 1.0, 0.0, 120.0 * lf**1.1 * rng.lognormal(0.0, 0.08, N))
    return lf, hf


def _run(problem, **kw):
    lf, hf = problem
    return pas.run_pas(lf, lambda ev: hf[ev.index], n_waves=NW, p_exp=P, seed=2,
                       strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)), **kw)


@pytest.fixture(scope="module")
def budget(problem):
    """A study its budget stopped: ε1 far below what 12 samples reach."""
    res = _run(problem, eps1=1e-6, max_hf=12)
    assert not res.converged and res.n_hf == 12
    return res


@pytest.fixture(scope="module")
def converged(problem):
    res = _run(problem, stopping=pas.Stopping(eps1=20.0, k1=3, k2=3), max_hf=40)
    assert res.converged
    return res


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def _legend_texts(ax):
    leg = ax.get_legend()
    assert leg is not None, "no legend"
    return [t.get_text() for t in leg.get_texts()]


def _assert_legends_read_right(fig):
    """Every legend: text ≥ 8 pt, inside the figure, over no Axes and no other legend."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
    assert legends, "no legend"
    boxes = []
    for leg in legends:
        sizes = [t.get_fontsize() for t in leg.get_texts()]
        assert min(sizes) >= 8.0, f"legend text of {min(sizes)} pt"
        box = leg.get_window_extent(renderer)
        assert box.x0 >= -1 and box.y0 >= -1 and box.x1 <= fig.bbox.x1 + 1 \
            and box.y1 <= fig.bbox.y1 + 1, "legend cut off by the figure edge"
        for ax in fig.axes:
            assert not box.overlaps(ax.get_window_extent(renderer)), \
                f"legend {[t.get_text() for t in leg.get_texts()][:2]} covers an Axes"
        assert not any(box.overlaps(other) for other in boxes), "legends overlap"
        boxes.append(box)


# -- legends ------------------------------------------------------------------
def test_every_result_figure_has_readable_legends_off_the_curves(problem, converged):
    lf, hf = problem
    truth = exceedance_probabilities(hf[hf > 0], NW)
    lfset = pas.LFSet(lf, n_waves=NW, p_exp=P)
    figures = [plot_mpm_convergence(converged, truth=1000.0, unit="kN")[0],
               plot_distribution(converged, lf=lfset, truth=truth, unit="kN", lf_unit="m")[0],
               plot_scatter(lf, hf, result=converged, lf_unit="m", unit="kN")[0],
               plot_aic(converged)[0]]
    fig, ax = plt.subplots()
    plot_aic(converged, ax=ax)
    figures.append(fig)
    table = pd.DataFrame({"case": ["1a", "1a", "3a", "3a"], "strategy": ["pas", "as"] * 2,
                          "M1": [0.006, 0.005, 0.01, 0.012], "M2": [0.02, -0.01, 0.05, -0.2],
                          "M3": [0.03, 0.02, 0.1, -0.3]})
    figures.append(plot_metrics(table)[0])
    for fig in figures:
        _assert_legends_read_right(fig)


def test_legend_below_the_axes_leaves_the_x_label_readable(converged):
    fig, ax = plot_mpm_convergence(converged)
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    label = ax.xaxis.label.get_window_extent(r)
    assert ax.get_legend().get_window_extent(r).y1 < label.y0
    # the figure grew by the legend instead of squeezing the Axes
    assert fig.get_figheight() > 4.5


# -- the stop of a study --------------------------------------------------------
def test_convergence_figure_says_the_budget_stopped_a_study_that_did_not_converge(budget):
    fig, ax = plot_mpm_convergence(budget, label="run")
    text = "budget reached (max_hf = 12) — not converged"
    assert f"run: {text}" in _legend_texts(ax)
    assert ax.get_title() == text
    stop = [ln for ln in ax.get_lines() if ln.get_label() == f"run: {text}"][0]
    assert stop.get_xdata()[0] == 12
    assert not any("converged at" in t for t in _legend_texts(ax))


def test_convergence_figure_says_where_a_study_converged(converged):
    fig, ax = plot_mpm_convergence(converged)
    first = converged.history[converged.history["stop"] == True].iloc[0]  # noqa: E712
    texts = _legend_texts(ax)
    assert any(f"converged at {int(first['n_hf'])} HF samples" in t for t in texts)
    assert not any("not converged" in t for t in texts)
    assert ax.get_title() == f"converged at {int(first['n_hf'])} HF samples"


def test_convergence_figure_says_the_failure_limit_stopped_a_study(problem):
    lf, hf = problem
    calls = []

    def oracle(ev):  # the basin fails every test after the tenth
        calls.append(ev.index)
        if len(calls) > 10:
            raise RuntimeError("wave maker tripped")
        return hf[ev.index]

    with pytest.raises(OracleFailureLimit) as info:
        pas.run_pas(lf, oracle, n_waves=NW, p_exp=P, eps1=1e-6, seed=2,
                    strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)),
                    budget=pas.Budget(max_failures=2))
    res = info.value.result
    assert res.n_failed == 3
    fig, ax = plot_mpm_convergence(res)
    assert ax.get_title() == ("stopped by the failure limit (3 failed, max_failures = 2)"
                              " — not converged")
    assert any("failed HF call ×3" in t for t in _legend_texts(ax))


# -- copula selection -------------------------------------------------------------
def test_aic_panel_draws_delta_aic_to_the_family_selected_at_each_iteration(converged):
    # make the selection change, so the reference family changes between iterations
    hist = converged.history.copy()
    rows = hist.index[hist["mpm"].notna()]
    hist.loc[rows[3:6], "family"] = "student"
    res = dataclasses.replace(converged, history=hist,
                              settings={**converged.settings,
                                        "strategy_settings": {"delta_aic": 6.0}})
    fig, (top, bottom) = plot_aic(res)
    fitted = hist.loc[rows]
    for fam in pas.models.copulas.PAPER_FAMILIES:
        line = [ln for ln in top.get_lines() if ln.get_label() == fam][0]
        expected = [row[f"aic_{fam}"] - row[f"aic_{row['family']}"]
                    for _, row in fitted.iterrows()]
        np.testing.assert_allclose(line.get_ydata(), expected, rtol=1e-9, atol=1e-9)
        chosen = (fitted["family"] == fam).to_numpy()
        np.testing.assert_allclose(line.get_ydata()[chosen], 0.0, atol=1e-9)
    threshold = [ln for ln in top.get_lines() if ln.get_label().startswith("ΔAIC = −6")]
    assert len(threshold) == 1 and threshold[0].get_ydata()[0] == pytest.approx(-6.0)
    assert "ΔAIC" in top.get_ylabel()


def test_aic_panel_cuts_far_worse_fits_and_says_so(converged):
    hist = converged.history.copy()
    rows = hist.index[hist["mpm"].notna()]
    worse = "clayton" if converged.family != "clayton" else "frank"
    hist.loc[rows[-1], f"aic_{worse}"] += 500.0
    fig, (top, _) = plot_aic(dataclasses.replace(converged, history=hist))
    assert top.get_ylim()[1] == pytest.approx(32.0)
    assert top.get_ylim()[0] <= -4.0
    assert "ΔAIC above 32 cut off at the top (far worse fits)" in _legend_texts(fig.axes[1])


# -- samples and design waves -------------------------------------------------------
def test_distribution_says_the_samples_sit_at_their_lf_exceedance(converged):
    fig, ax = plot_distribution(converged)
    n = len(converged.pairs)
    label = f"PAS ({converged.family}): HF loads of the {n} evaluated events with a load, " \
            "each at its LF exceedance $d$"
    assert label in _legend_texts(ax)
    marks = [ln for ln in ax.get_lines() if ln.get_label() == label][0]
    np.testing.assert_allclose(marks.get_xdata(), converged.pairs["d"], rtol=1e-12)
    np.testing.assert_allclose(marks.get_ydata(), converged.pairs["hf"], rtol=1e-12)


def _design_result(p_exp=P):
    """A design-wave result as pas.run_rcw gives: one HF episode per level, no band."""
    levels = np.array([p_exp / 4, p_exp, 4 * p_exp])
    target = np.array([9.0, 8.0, 7.0])
    hf = 1.1 * target * 100.0
    nan = np.full(3, np.nan)
    hist = pd.DataFrame({"row": range(3), "n_hf": [1, 2, 3], "level": levels, "hf": hf,
                         "status": "true_positive", "mpm": [np.nan, hf[1], np.nan]})
    dist = pd.DataFrame({"exceedance_probability": levels, "h_mean": hf, "h_low": nan,
                         "h_high": nan, "linear": target, "f_nl": hf / target - 1})
    return ScreeningResult("rcw", float(hf[1]), (np.nan, np.nan), (np.nan, np.nan), None, 3, 0,
                           0, True, hist, dist, pd.DataFrame({"lf": target, "hf": hf,
                                                              "d": levels}),
                           pd.DataFrame(), p_exp, NW, 0)


def test_design_waves_claim_no_band(converged):
    rcw = _design_result()
    fig, ax = plot_mpm_convergence(converged)
    plot_mpm_convergence(rcw, ax=ax)
    texts = [t for t in _legend_texts(ax) if t.startswith("RCW")]
    assert texts == [f"RCW: MPM {rcw.mpm:.4g}, HF of the $P_{{exp}}$ design wave "
                     "(3 episodes, one per level; no band)"]
    fig, ax = plot_distribution(converged)
    plot_distribution(rcw, ax=ax)
    texts = [t for t in _legend_texts(ax) if t.startswith("RCW")]
    assert texts == ["RCW: one HF episode per level"]
    assert sum(t.startswith("$P_{exp}$") for t in _legend_texts(ax)) == 1
    # the same as drawing the points directly
    fig, ax2 = plot_design_points(rcw)
    np.testing.assert_allclose(ax2.get_lines()[0].get_ydata(), rcw.distribution["h_mean"])


@pytest.mark.slow
def test_reproduce_case_figure_reads_right(problem, converged, tmp_path):
    """``pas reproduce``'s case and design figures: legends ≥ 8 pt, off every curve,
    and no "sampling band" claimed for a design wave."""
    from pas.validation.figures import write_figures

    lf, hf = problem
    d_t, h_t = exceedance_probabilities(hf[hf > 0], NW)
    data = SimpleNamespace(lf=lf, hf=hf, n_waves=NW, truth_mpm=float(converged.mpm),
                           truth_d=d_t, truth_h=h_t, unit="m")
    as_res = pas.run_as(lf, lambda ev: hf[ev.index], n_waves=NW, p_exp=P, eps1=20.0, seed=2,
                        max_hf=10)
    results = {("1a", "pas"): converged, ("1a", "as"): as_res, ("1a", "rcw"): _design_result()}
    table = pd.DataFrame({"case": ["1a"] * 3, "strategy": ["PAS", "AS", "RCW"],
                          "M1": [0.01, 0.01, 0.002], "M2": [0.0, 0.01, -0.1],
                          "M3": [0.0, 0.02, -0.1]})
    shown = {}
    real_savefig = matplotlib.figure.Figure.savefig

    def keep(fig, path, **kw):
        shown[str(path).rsplit("/", 1)[-1]] = fig
        real_savefig(fig, path, **kw)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(matplotlib.figure.Figure, "savefig", keep)
        mp.setattr(plt, "close", lambda fig=None: None)
        files = write_figures(tmp_path, {"1a": data}, results, table)
    assert {f.name for f in files} == {"case_1a.png", "design_1a.png", "metrics.png"}
    for name, fig in shown.items():
        _assert_legends_read_right(fig)
        for ax in fig.axes:
            if ax.get_legend() is not None:
                rcw = [t for t in _legend_texts(ax) if t.startswith("RCW")]
                assert not any("band" in t and "no band" not in t for t in rcw), (name, rcw)
    assert all(f.stat().st_size > 20_000 for f in files)


# -- titles ---------------------------------------------------------------------
@pytest.mark.parametrize("n", [N, 26])  # tail dependence estimated, and not
def test_the_scatter_title_fits_in_its_figure(problem, n):
    lf, hf = problem
    fig, ax = plot_scatter(lf[:n], hf[:n], lf_unit="m", unit="kN")
    fig.canvas.draw()
    box = ax.title.get_window_extent()
    assert box.x0 >= 0 and box.x1 <= fig.bbox.x1 and box.y1 <= fig.bbox.y1, \
        f"title {ax.get_title()!r} cut by the figure edge"
