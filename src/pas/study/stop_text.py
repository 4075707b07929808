"""How far a result is from stopping, in words: the ``converged`` part of its summary.

With ``eps1`` (the paper's rule) the last ``Ē`` and COV against their limits;
with a precision target the U95's half-width in % of the MPM against the
target, and the forecast of the further HF evaluations it needs beside what
the budget allows (:mod:`pas.study.precision`).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import pandas as pd

from ..strategies.forecast import relative_half_width

__all__ = ["HFForecast", "hf_forecast", "state", "precision_state", "forecast_text", "percent",
           "HIGHEST_SHOWN", "FLOOR_NAME"]


class HFForecast(NamedTuple):
    """Further HF evaluations expected to reach the precision target, with a 95 % interval."""

    expected: float
    low: float
    high: float


def hf_forecast(forecast: dict | None) -> HFForecast | None:
    """The :class:`HFForecast` of a result's ``forecast`` dict, None when there is none."""
    if not forecast or not np.isfinite(forecast.get("forecast_hf", math.nan)) and \
            not forecast.get("out_of_reach"):
        return None
    return HFForecast(*(float(forecast[k]) for k in
                        ("forecast_hf", "forecast_hf_low", "forecast_hf_high")))


def percent(x: float) -> str:
    """A fraction as a percentage for a summary line: ``0.1`` → ``'±10 %'``."""
    return f"±{100 * x:.3g} %"


HIGHEST_SHOWN = 100_000
"""A forecast interval's upper end above this many HF is shown as "over" it (the value itself
stays in the result's ``forecast``): no campaign plans by a larger number."""


FURTHER_HF = ("further HF still correct the MPM and its band, and the forecast is revised with "
              "each band")
"""What a study that goes on after its forecast said "out of reach" spends its budget on: on
known-truth problems the MPM's error and the U95's coverage improved after that point, and
some studies reached their target after all (``docs/results/precision.md``)."""


FLOOR_NAME = "the sampling part alone (the z-draw band)"
"""What :func:`forecast_text` calls the part of the band more HF events do not narrow."""


def forecast_text(forecast: HFForecast | None, target: float, budget_left=None,
                  floor: float | None = None, floor_name: str = FLOOR_NAME) -> str:
    """``"about 60 more HF for ±10 % (40–95); the budget allows 40"`` and its variants.

    ``floor``: the relative half-width of the part that does not narrow, named
    ``floor_name`` when it alone is wider than the target.

    Examples
    --------
    >>> forecast_text(HFForecast(58.6, 40.2, 95.0), 0.1, 40)
    'about 59 more HF for ±10 % (40–95); the budget allows 40'
    >>> forecast_text(HFForecast(15.2, 12.0, 1.15e11), 0.1)
    'about 15 more HF for ±10 % (12–over 100,000)'
    >>> forecast_text(None, 0.1, 5)
    'too few model bands yet to forecast the HF needed for ±10 %; the budget allows 5'
    """
    goal = percent(target)
    if forecast is None:
        text = f"too few model bands yet to forecast the HF needed for {goal}"
    elif not math.isfinite(forecast.expected) and floor is not None and floor >= target:
        text = (f"more HF will not reach {goal}: {floor_name} is {percent(floor)}, and more "
                "HF events do not narrow it")
    elif not math.isfinite(forecast.expected):
        text = f"more HF are not expected to reach {goal}: the band has not narrowed with the pairs"
    else:
        high = ("∞" if not math.isfinite(forecast.high) else
                f"over {HIGHEST_SHOWN:,}" if forecast.high > HIGHEST_SHOWN else
                f"{forecast.high:.0f}")
        text = (f"about {forecast.expected:.0f} more HF for {goal} "
                f"({forecast.low:.0f}–{high})")
    if budget_left is not None:
        text += f"; the budget allows {max(int(budget_left), 0)}"
        if forecast is not None and not math.isfinite(forecast.expected) and budget_left > 0:
            text += f": {FURTHER_HF}"
    return text


def precision_state(width: float, target: float, reached: bool, forecast: dict | None,
                    left=None, *, of: str = "the MPM", words=("converged", "NOT converged"),
                    floor_name: str = FLOOR_NAME) -> str:
    """How far a band of relative half-width ``width`` is from the precision ``target``:
    reached, or its width, the target and the forecast (:func:`forecast_text`) of the
    further HF evaluations (``forecast``: a result's dict; ``left``: what the budget allows).

    Examples
    --------
    >>> precision_state(0.08, 0.1, True, None, of="the value", words=("reached", "NOT reached"))
    'reached: U95 within ±10 % of the value (±8 %)'
    """
    goal = percent(target)
    if reached:
        return f"{words[0]}: U95 within {goal} of {of} ({percent(width)})"
    if not math.isfinite(width):
        return f"{words[1]} (target {goal} of {of})"
    return (f"{words[1]}: U95 {percent(width)} of {of} against the target {goal}; "
            f"{forecast_text(hf_forecast(forecast), target, left, _floor(forecast), floor_name)}")


def state(result) -> str:
    """``converged`` / ``NOT converged (...)`` for :meth:`ScreeningResult.summary`."""
    settings = result.settings or {}
    target = settings.get("precision")
    max_hf = settings.get("max_hf")
    left = None if max_hf is None else max_hf - result.n_hf
    if target is None:
        if result.converged:
            return "converged"
        spent = f"; the budget of {max_hf} HF is spent" if left is not None and left <= 0 else ""
        return f"NOT converged{paper_gap(result)}{spent}"
    width = relative_half_width(result.mpm, result.mpm_band)
    paper = settings.get("eps1") is not None
    misfit = "" if result.converged else misfit_text(result.history)
    if misfit and width <= target:  # a band narrow enough, not taken for the precision
        return (f"NOT converged: U95 {percent(width)} of the MPM, within the target "
                f"{percent(target)}{misfit}")
    text = precision_state(width, target, result.converged, result.forecast, left)
    if result.converged:
        return text + (" and the eps1 rule" if paper else "")
    return text + (paper_gap(result) if paper and math.isfinite(width) else "") + misfit


def misfit_text(history: pd.DataFrame) -> str:
    """What the last fit check said when it kept the study from taking its band for the
    precision (:func:`pas.study.precision.fits_evaluated`), else ``""``.

    Examples
    --------
    >>> h = pd.DataFrame({"n_hf": [40, 41], "fit_check_p": [0.2, 0.003],
    ...                   "fit_misfit": [None, "the count above 0.9"]})
    >>> misfit_text(h)
    '; at 41 HF the fitted model failed the fit check on the evaluated loads (p 0.003, the count above 0.9), so its band was not taken for the precision: it may not hold the truth'
    """  # noqa: E501 (doctest output line)
    if "fit_check_p" not in history or "fit_misfit" not in history:
        return ""
    checked = history[history["fit_check_p"].notna()]
    if checked.empty or not isinstance(checked["fit_misfit"].iloc[-1], str):
        return ""
    last = checked.iloc[-1]
    return (f"; at {int(last['n_hf'])} HF the fitted model failed the fit check on the "
            f"evaluated loads (p {last['fit_check_p']:.2g}, {last['fit_misfit']}), so its "
            "band was not taken for the precision: it may not hold the truth")


def _floor(forecast: dict | None) -> float | None:
    value = (forecast or {}).get("sampling_halfwidth")
    return None if value is None or not math.isfinite(value) else float(value)


def paper_gap(result) -> str:
    """How far the last iteration was from stopping: its Ē and COV against ε1, ε2."""
    settings = result.settings or {}
    fitted = result.fitted if "mpm" in result.history else pd.DataFrame()
    if fitted.empty or settings.get("eps1") is None or "E_bar" not in fitted:
        return ""
    last = fitted.iloc[-1]
    if not np.isfinite(last["E_bar"]):
        return ""
    eps2 = settings.get("eps2", np.nan)
    over = ([f"last Ē {last['E_bar']:.3g} against ε1 {settings['eps1']:.3g}"]
            if not last["E_bar"] < settings["eps1"] else [])
    over += [f"COV {last['COV']:.2g} against ε2 {eps2:.2g}"] if not last["COV"] < eps2 else []
    if not over:
        return (" (Ē and COV within ε1 and ε2: too few fitted iterations, or a "
                "predicted range short of 2·P_exp)")
    return f" ({', '.join(over)})"
