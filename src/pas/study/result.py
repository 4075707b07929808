"""The result of a screening study: MPM, bands, distribution and full history."""

from __future__ import annotations

import json
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from .._support.strict_json import json_data
from ..stats.exceedance import quantile_exceedance, value_at_exceedance
from . import precision, stop_text

__all__ = ["ScreeningResult", "OUTPUT_FILES"]

OUTPUT_FILES = ("history.csv", "distribution.csv", "pairs.csv", "range_curves.csv",
                "lf_curve.csv", "summary.json")
"""Files :meth:`ScreeningResult.save` writes and :meth:`ScreeningResult.load` reads."""


@dataclass
class ScreeningResult:
    """What :func:`pas.run_pas` and :func:`pas.run_as` return.

    Attributes
    ----------
    mpm : float
        Most probable maximum at ``p_exp`` from the mean distribution (Eq. 12).
    mpm_band : tuple of float
        The U95 of the MPM, the one band pas reports (summary, ``summary.json``,
        ``pas study status``, the MPM error bar of the distribution figure):
        the union of its two parts below.
    mpm_band_sampling : tuple of float
        Sampling part: the paper's band from the z conditional draws,
        ``h* ± 1.96 σ_b`` read at ``p_exp`` (Eq. 10).  The progress lines and
        the history's ``mpm_low``/``mpm_high`` give this part per iteration.
    mpm_band_model : tuple of float or None
        Model part: the strategy's model-uncertainty band (PAS: refits on
        resampled pairs, :meth:`pas.strategies.base.Strategy.model_band`);
        None when the strategy has none (then U95 is the sampling part).
    n_hf : int
        HF evaluations made, false positives included, failures excluded
        (kept for compatibility; :attr:`n_evaluated` counts the failures too).
    n_false_positive, n_failed : int
        False positives (HF = 0) and failed oracle calls.  A failed event is
        left out of the fit: :attr:`n_evaluated`, :attr:`n_loads` and
        :attr:`n_no_impact` (also in ``summary.json``) split the evaluations.
    converged : bool
        Whether the stopping criterion was met.
    history : pandas.DataFrame
        One row per HF evaluation (the evaluation sequence), with the fit of
        that iteration where one was made.
    distribution : pandas.DataFrame
        ``exceedance_probability``, ``h_mean``, ``h_low``, ``h_high`` (and PAS's ``lf``,
        ``p_impact``).  From a study its columns may be the study's read-only arrays
        (not copied; writing into them raises, ``.copy()`` the table first).
    pairs : pandas.DataFrame
        The true-positive LF–HF pairs.
    range_curves : pandas.DataFrame
        Mean distribution of every fitted iteration on the stopping range
        ``[P_exp/2, 2 P_exp]`` (columns are the probabilities), indexed by
        history row; used by the metrics M2/M3.
    refit : dict or None
        For the result of another load on a study's events
        (:func:`pas.study.refit.refit`): ``target`` (the load analysed),
        ``chosen_for`` (the load the events were chosen for) and ``n_missing``
        (events lacking ``target``, counted failed); None for a study's own result.
    forecast : dict or None
        With a precision target: the further HF evaluations expected to reach it
        (``forecast_hf``, ``forecast_hf_low``, ``forecast_hf_high``; NaN before
        enough bands were measured), :attr:`forecast_hf`.
    """

    strategy: str
    mpm: float
    mpm_band: tuple
    mpm_band_sampling: tuple
    mpm_band_model: tuple | None
    n_hf: int
    n_false_positive: int
    n_failed: int
    converged: bool
    history: pd.DataFrame
    distribution: pd.DataFrame
    pairs: pd.DataFrame
    range_curves: pd.DataFrame
    p_exp: float
    n_waves: int
    seed: int
    family: str | None = None
    settings: dict = field(default_factory=dict)
    refit: dict | None = None
    forecast: dict | None = None

    @classmethod
    def from_study(cls, study, *, model_band: bool = True) -> ScreeningResult:
        """The result of ``study`` so far (:meth:`pas.study.study.Study.result`)."""
        pairs, pred = study.pairs(), study.last
        nan = float("nan")
        mpm, band, sampling, model, family = nan, (nan, nan), (nan, nan), None, None
        forecast, converged = None, study.converged
        distribution = distribution_frame([], [], [], [])
        pair_frame = pd.DataFrame({"lf": pairs.lf, "hf": pairs.hf})
        if pred is not None:
            if study.range_short(pred):
                warnings.warn(
                    f"the predicted distribution ends at d = {pred.d[-1]:.3g}, short of "
                    f"2·P_exp = {study.grid[-1]:.3g}: the lowest true positive lies above the LF "
                    "level of P_exp, so the MPM is read off the end of the distribution and the "
                    "study cannot converge; lower the threshold or check the false positives",
                    stacklevel=2)
            mpm, band = pred.mpm, pred.mpm_band
            sampling, family = pred.mpm_band, pred.record.get("family")
            if model_band:
                model = precision.model_band(study, pairs)
                band = precision.union(band, model)
            forecast = precision.final_forecast(study, pairs, pred, model if model_band else None)
            distribution = distribution_frame(pred.d, pred.h_mean, pred.h_low, pred.h_high,
                                              **pred.columns)
            clip = clipped_from(distribution, study.n_false_positive)
            if clip is not None and clip <= study.grid[-1]:
                warnings.warn(
                    f"the predicted distribution is exactly 0 from d = {clip:.3g} on, inside the "
                    f"stopping range [P_exp/2, 2·P_exp]: every conditional draw there fell below "
                    "the fitted HF marginal's lower bound and was clipped at 0, although no "
                    "evaluated event gave 0; the MPM and the stopping rule read clipped values",
                    stacklevel=2)
            ids = [study.lfset.event(p).id for p in pairs.position]
            pair_frame = pd.DataFrame({"event_id": ids, "lf": pairs.lf, "hf": pairs.hf,
                                       "d": pairs.d})
        result = cls(
            strategy=study.strategy.name, mpm=mpm, mpm_band=band, mpm_band_sampling=sampling,
            mpm_band_model=model, n_hf=study.n_hf, n_false_positive=study.n_false_positive,
            n_failed=study.n_failed,
            converged=converged and precision.holds(study, mpm, band, model_band),
            history=study.history(), distribution=distribution, pairs=pair_frame,
            range_curves=pd.DataFrame.from_dict(study.curves, orient="index", columns=study.grid),
            p_exp=study.lfset.p_exp, n_waves=study.lfset.n_waves, seed=study.seed, family=family,
            settings=study.settings(), forecast=forecast)
        if model_band and pred is not None and study.store is not None and not study.replaying:
            from .stored_results import save_result
            save_result(study.store, study, result)
        return result

    @property
    def clipped_from(self) -> float | None:
        """Smallest ``d`` from which the mean distribution is 0 by clipping, else None.

        The conditional draws are clipped at 0 (loads are not negative); where
        the fitted HF marginal's lower bound lies below 0, the draws of the
        smallest LF peaks can all land there.  With no evaluated false
        positive a mean of exactly 0 is then an artefact of the model, not a
        prediction: :func:`pas.plotting.plot_distribution` does not draw it.
        """
        return clipped_from(self.distribution, self.n_false_positive)

    @property
    def fitted(self) -> pd.DataFrame:
        """History rows where a model was fitted (true-positive iterations)."""
        return self.history[self.history["mpm"].notna()]

    def value_at(self, p):
        """Mean predicted HF value at exceedance probability ``p`` (per encounter)."""
        d = self.distribution["exceedance_probability"].to_numpy()
        if not len(d):
            raise ValueError("the result has no predicted distribution yet")
        return value_at_exceedance(d, self.distribution["h_mean"].to_numpy(), p)

    def quantile(self, q: float) -> float:
        """The ``q``-quantile of the maximum over the exposure duration.

        With ``n_exp = 1 / P_exp`` encounters in the exposure, ``P(max ≤ h) =
        (1 − d(h))^{n_exp} = q`` gives ``d = 1 − q^{P_exp}``
        (:func:`pas.stats.exceedance.quantile_exceedance` with ``m/n = P_exp``).
        ``q = e^{-1}`` is the MPM level; ``q = 0.9`` a common design quantile.
        """
        return float(self.value_at(quantile_exceedance(q, self.p_exp, 1.0)))

    def band_text(self, unit: str | None = None) -> str:
        """The U95 of the MPM with its parts labelled.

        Examples
        --------
        >>> r = ScreeningResult("pas", 600.0, (561.0, 668.0), (582.0, 612.0), (561.0, 668.0),
        ...                     20, 0, 0, True, *[pd.DataFrame()] * 4, 1e-3, 1000, 1)
        >>> r.band_text("kN")
        'U95 561–668 kN (sampling part 582–612, model part 561–668)'
        """
        u = f" {unit}" if unit else ""
        lo, hi = self.mpm_band
        parts = f"sampling part {_range(self.mpm_band_sampling)}"
        parts += (", no model part" if self.mpm_band_model is None
                  else f", model part {_range(self.mpm_band_model)}")
        return f"U95 {lo:.4g}–{hi:.4g}{u} ({parts})"

    def summary(self, unit: str | None = None) -> str:
        """One human-readable line: MPM with its U95 and parts, counts, convergence.

        ``unit`` (e.g. ``"kN"``) is appended to the MPM and its band.
        """
        fam = f", copula {self.family}" if self.family else ""
        state = stop_text.state(self)
        counts = f"{self.counts_text()}; {state}"
        counts += self._refit_note()
        if not np.isfinite(self.mpm):
            return f"{self.strategy.upper()}: no model fitted yet; {counts}"
        u = f" {unit}" if unit else ""
        return (f"{self.strategy.upper()}: MPM {self.mpm:.4g}{u}, {self.band_text(unit)}{fam}; "
                f"{counts}")

    def _refit_note(self) -> str:
        """For a refit: which load, and that its events were chosen for another."""
        if not self.refit:
            return ""
        name, chosen = self.refit["target"], self.refit.get("chosen_for")
        if name == chosen:
            return f"; refit of load {name!r}, the one its events were chosen for"
        chosen = repr(chosen) if chosen else "the study's load"
        missing = self.refit.get("n_missing", 0)
        return (f"; refit of load {name!r} on events chosen for {chosen}, so the sample is not "
                f"adapted to {name!r}" + (f" ({missing} event(s) lack {name!r}, counted failed)"
                                         if missing else ""))

    @property
    def n_evaluated(self) -> int:
        """HF evaluations asked for and answered: loads, no-impact results and failures."""
        return self.n_hf + self.n_failed

    @property
    def n_loads(self) -> int:
        """HF evaluations that gave a load (HF > 0): the true positives the fit uses."""
        return self.n_hf - self.n_false_positive

    @property
    def n_no_impact(self) -> int:
        """HF evaluations that gave no impact (HF = 0, false positives)."""
        return self.n_false_positive

    def counts_text(self) -> str:
        """What the HF evaluations gave, failures named as left out of the fit.

        Examples
        --------
        >>> r = ScreeningResult("pas", 600.0, (561.0, 668.0), (582.0, 612.0), None,
        ...                     8, 1, 5, True, *[pd.DataFrame()] * 4, 1e-3, 1000, 1)
        >>> r.counts_text()
        '13 evaluated: 7 loads, 1 no impact, 5 failed (left out of the fit)'
        """
        failed = (f"{self.n_failed} failed (left out of the fit)" if self.n_failed
                  else "0 failed")
        return (f"{self.n_evaluated} evaluated: {self.n_loads} loads, {self.n_no_impact} "
                f"no impact, {failed}")

    @property
    def forecast_hf(self) -> stop_text.HFForecast | None:
        """Further HF evaluations expected to reach the precision target: ``(expected, low,
        high)``, 0 once reached, ``inf`` out of reach; None without a target or a forecast yet.

        From a power law fitted to how the model band narrowed with the pairs
        (:mod:`pas.strategies.forecast`); ``low``–``high`` is its 95 % interval.
        """
        return stop_text.hf_forecast(self.forecast)

    def __repr__(self) -> str:
        return f"<ScreeningResult {self.summary()}>"

    def to_dict(self) -> dict:
        """JSON-friendly scalar summary."""
        return {
            "strategy": self.strategy, "mpm": self.mpm, "mpm_band": list(self.mpm_band),
            "mpm_band_sampling": list(self.mpm_band_sampling),
            "mpm_band_model": None if self.mpm_band_model is None else list(self.mpm_band_model),
            "n_hf": self.n_hf, "n_false_positive": self.n_false_positive,
            "n_failed": self.n_failed, "n_evaluated": self.n_evaluated, "n_loads": self.n_loads,
            "n_no_impact": self.n_no_impact, "converged": self.converged, "family": self.family,
            "p_exp": self.p_exp, "n_waves": self.n_waves, "seed": self.seed,
            "clipped_from": self.clipped_from, "settings": self.settings,
            **({} if self.refit is None else {"refit": self.refit}),
            **({} if self.forecast is None else {"forecast": self.forecast}),
        }

    def save(self, out, *, inputs=None, lfset=None) -> dict:
        """Write the result to folder ``out`` (created when missing).

        Writes :data:`OUTPUT_FILES`: the history, the final distribution, the
        true-positive pairs, the per-iteration curves on the stopping range, the
        LF exceedance curve (when ``lfset`` is given) and ``summary.json``
        (:meth:`to_dict` plus the one-line summary and ``inputs``), everything
        ``pas plot`` draws from.

        Returns
        -------
        dict
            The summary written to ``summary.json``.
        """
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        self.history.to_csv(out / "history.csv", index=False)
        self.distribution.to_csv(out / "distribution.csv", index=False)
        self.pairs.to_csv(out / "pairs.csv", index=False)
        self.range_curves.to_csv(out / "range_curves.csv", index_label="row")
        if lfset is not None:
            pd.DataFrame({"d": lfset.d, "lf": lfset.lf}).to_csv(out / "lf_curve.csv", index=False)
        inputs = dict(inputs or {})
        summary = json_data({**self.to_dict(), "summary": self.summary(unit=inputs.get("unit")),
                             "inputs": inputs})
        (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n", encoding="utf-8")
        return summary

    @classmethod
    def load(cls, path) -> ScreeningResult:
        """Read back a result written by :meth:`save` (the ``--out`` folder of ``pas run``)."""
        path = Path(path)
        summary = read_summary(path)
        curves_file = path / "range_curves.csv"
        if curves_file.exists():
            curves = pd.read_csv(curves_file, index_col="row")
            curves.columns = curves.columns.astype(float)
        else:
            curves = pd.DataFrame()
        s = summary
        band = tuple(_float_or_nan(x) for x in s["mpm_band"])
        return cls(
            strategy=s["strategy"], mpm=_float_or_nan(s["mpm"]), mpm_band=band,
            mpm_band_sampling=tuple(_float_or_nan(x) for x in s.get("mpm_band_sampling") or band),
            mpm_band_model=(None if s.get("mpm_band_model") is None
                            else tuple(_float_or_nan(x) for x in s["mpm_band_model"])),
            n_hf=int(s["n_hf"]), n_false_positive=int(s.get("n_false_positive", 0)),
            n_failed=int(s.get("n_failed", 0)), converged=bool(s.get("converged", False)),
            history=pd.read_csv(path / "history.csv"),
            distribution=pd.read_csv(path / "distribution.csv"),
            pairs=pd.read_csv(path / "pairs.csv"), range_curves=curves, p_exp=float(s["p_exp"]),
            n_waves=int(s["n_waves"]), seed=s.get("seed"), family=s.get("family"),
            settings=s.get("settings"), refit=s.get("refit"),
            forecast=_forecast_read(s.get("forecast")),
        )


def read_summary(path) -> dict:
    """``summary.json`` of a folder written by :meth:`ScreeningResult.save`, checked."""
    path = Path(path)
    if not path.is_dir():
        raise FileNotFoundError(f"{path} is not a folder")
    need = ("summary.json", "history.csv", "distribution.csv", "pairs.csv")
    missing = [f for f in need if not (path / f).exists()]
    if missing:
        raise FileNotFoundError(f"{path} lacks {', '.join(missing)} "
                                "(is it the --out folder of 'pas run'?)")
    try:
        s = json.loads((path / "summary.json").read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path / 'summary.json'}: not valid JSON ({exc})") from None
    for key in ("strategy", "mpm", "mpm_band", "n_hf", "p_exp", "n_waves"):
        if key not in s:
            raise ValueError(f"{path / 'summary.json'}: field {key!r} is missing")
    return s


def _range(band) -> str:
    return f"{band[0]:.4g}–{band[1]:.4g}"


def _forecast_read(stored: dict | None) -> dict | None:
    """A stored forecast, its nulls back as inf where it was out of reach, else NaN."""
    if stored is None:
        return None
    gone = float("inf") if stored.get("out_of_reach") else float("nan")
    return {**{k: gone if v is None else float(v) for k, v in stored.items()
               if k.startswith("forecast_")}, "out_of_reach": bool(stored.get("out_of_reach")),
            "sampling_halfwidth": _float_or_nan(stored.get("sampling_halfwidth"))}


def _float_or_nan(x):
    return float("nan") if x is None else float(x)


def clipped_from(distribution: pd.DataFrame, n_false_positive: int):
    """:attr:`ScreeningResult.clipped_from` of a distribution table."""
    h = distribution["h_mean"].to_numpy(dtype=float)
    if n_false_positive or not np.any(h == 0.0):
        return None
    return float(distribution["exceedance_probability"].to_numpy(dtype=float)[h == 0.0].min())


def distribution_frame(d, mean, low, high, **columns) -> pd.DataFrame:
    """The predicted distribution as a table (``columns``: more per-rank arrays).

    A read-only array (the prediction's, :class:`pas.strategies.tail_draws.TailPrediction`;
    12 MB a column at 1.5 M LF peaks) becomes the column itself, so writing into it raises
    instead of changing the study's prediction (``.copy()`` the table first); any other
    array is copied.
    """
    data = {"exceedance_probability": d, "h_mean": mean, "h_low": low, "h_high": high,
            **columns}
    shared = {k: v if isinstance(v, np.ndarray) and not v.flags.writeable else np.array(v)
              for k, v in data.items()}
    return pd.DataFrame(shared, copy=False)
