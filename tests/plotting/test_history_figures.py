"""The MPM history and the scatter say what happened: copula families, replaced results."""

import dataclasses

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from conftest import no_band  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

import pas  # noqa: E402
from pas.cli import main  # noqa: E402
from pas.plotting import plot_mpm_convergence  # noqa: E402

N = 400
LF = np.random.default_rng(0).rayleigh(1.0, N)
TYPO, RIGHT = 999.0, 12.5


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def replaced():
    """Eight events told, the last one with a typo, then corrected with ``replace=True``."""
    study = pas.make_study(no_band(), LF, n_waves=N, p_exp=1e-2, eps1=1e-3, seed=5, max_hf=30)
    told = 0
    while told < 8:
        for ev in study.ask():
            told += 1
            study.tell(ev, TYPO if told == 8 else 2.0 * ev.lf ** 1.2)
    study.tell(ev, RIGHT, replace=True)
    return study.result()


def test_mpm_history_has_one_point_per_evaluation_after_a_replacement(replaced):
    assert (replaced.history["n_hf"] == 8).sum() == 2  # the told row and its replacement
    fig, ax = plot_mpm_convergence(replaced)
    line = next(ln for ln in ax.get_lines() if "MPM" in ln.get_label())
    x = list(line.get_xdata())
    assert x == sorted(set(x)) and x[-1] == 8
    assert line.get_ydata()[-1] == pytest.approx(replaced.mpm)  # the refit, not the typo's fit


def test_scatter_does_not_draw_the_replaced_value(replaced, tmp_path, monkeypatch):
    replaced.save(tmp_path / "run")
    labels, points, save = [], [], Figure.savefig

    def record(fig, *args, **kwargs):
        ax = fig.axes[0]
        labels.extend(ax.get_legend_handles_labels()[1])
        points.append(np.concatenate([np.asarray(c.get_offsets())[:, 1] for c in ax.collections
                                    if len(c.get_offsets())]))
        return save(fig, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", record)
    assert main(["plot", str(tmp_path / "run"), "--kind", "scatter",
                 "--out", str(tmp_path / "s.png")]) == 0
    assert "evaluated events (n = 8)" in labels
    assert TYPO not in points[-1] and RIGHT in points[-1]


def test_mpm_history_shows_each_copula_family():
    rng = np.random.default_rng(3)
    lf = rng.rayleigh(2.0, 3000)
    hf = np.where(lf < 1.0, 0.0, 1.2 * lf ** 1.1 * rng.lognormal(0.0, 0.08, 3000))
    study = pas.make_study(pas.PAS(band=pas.ModelBand(n_bootstrap=0)), lf, n_waves=3200,
                           p_exp=3e-3, seed=2, max_hf=20,
                           stopping=pas.Stopping(eps1=0.2, k1=9, k2=9), stop_on_convergence=False)
    result = study.optimize(lambda ev: hf[ev.index])
    hist = result.history.copy()
    fitted = hist.index[hist["mpm"].notna()]
    thirds = np.array_split(fitted, 3)
    for rows, family in zip(thirds, ("gaussian", "clayton", "gumbel")):
        hist.loc[rows, "family"] = family
    fig, ax = plot_mpm_convergence(dataclasses.replace(result, history=hist, family="gumbel"))
    labels = ax.get_legend_handles_labels()[1]
    assert not any(t.startswith("PAS (gumbel)") for t in labels)  # not named after the last
    for rows, family in zip(thirds, ("gaussian", "clayton", "gumbel")):
        marks = [ln for ln in ax.get_lines() if ln.get_label().startswith(f"{family} copula")]
        assert len(marks) == 1
        assert list(marks[0].get_xdata()) == hist.loc[rows, "n_hf"].tolist()
    shapes = {ln.get_marker() for ln in ax.get_lines() if "copula" in ln.get_label()}
    assert len(shapes) == 3
    assert not any("Eq." in t for t in labels)
