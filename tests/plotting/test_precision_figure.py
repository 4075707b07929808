"""The convergence figure of a precision study: target, U95 where computed, forecast."""

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pandas as pd

from pas.plotting import plot_mpm_convergence
from pas.plotting.convergence import stop_text
from pas.study.result import ScreeningResult


def precision_result(converged=False):
    n = np.arange(1, 31)
    mpm = 100.0 + 5.0 * np.exp(-n / 10.0)
    hist = pd.DataFrame({"n_hf": n, "status": "true_positive", "mpm": mpm,
                         "mpm_low": mpm - 2.0, "mpm_high": mpm + 2.0,
                         "model_low": np.where(n % 10 == 0, mpm - 14.0, np.nan),
                         "model_high": np.where(n % 10 == 0, mpm + 12.0, np.nan),
                         "stop": converged & (n == 30)})
    forecast = {"forecast_hf": 42.0, "forecast_hf_low": 25.0, "forecast_hf_high": 80.0,
                "out_of_reach": False, "sampling_halfwidth": 0.02}
    return ScreeningResult("pas", mpm[-1], (mpm[-1] - 14.0, mpm[-1] + 12.0),
                           (mpm[-1] - 2.0, mpm[-1] + 2.0), (mpm[-1] - 14.0, mpm[-1] + 12.0),
                           30, 0, 0, converged, hist, pd.DataFrame(), pd.DataFrame(),
                           pd.DataFrame(), 1e-2, 2000, 1, family="gumbel",
                           settings={"precision": 0.1, "max_hf": 30, "max_failures": 10},
                           forecast=forecast)


def test_short_study_shows_target_bands_forecast_and_its_distance():
    res = precision_result()
    fig, ax = plot_mpm_convergence(res)
    labels = ax.get_legend_handles_labels()[1]
    assert "PAS (gumbel): target MPM ±10 %" in labels
    assert "PAS (gumbel): U95 where the loop computed it" in labels
    assert any(lab.startswith("PAS (gumbel): forecast, about 42 more HF for ±10 % (25–80)")
               for lab in labels)
    width = 14.0 / res.mpm
    assert stop_text(res) == (f"budget reached (max_hf = 30) — not converged: "
                              f"U95 ±{100 * width:.3g} % against ±10 %")
    assert ax.get_title() == stop_text(res)
    fig.clf()


def test_converged_study_draws_no_forecast():
    fig, ax = plot_mpm_convergence(precision_result(converged=True))
    labels = ax.get_legend_handles_labels()[1]
    assert not any("forecast" in lab for lab in labels)
    assert any("converged at 30 HF samples" in lab for lab in labels)
    fig.clf()
