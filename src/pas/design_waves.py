"""Design waves beside PAS and AS: :func:`run_rcw` (Dermatis et al. 2025).

For each exceedance level ``p`` of a ladder (``P_exp`` always among them):

1. the *linear* target response at ``p`` from the LF statistics -- Rayleigh on
   the surrogate's linear response spectrum, or the LF Monte-Carlo peaks read
   at ``d = p`` (Eq. 3, 12);
2. the episode whose surrogate response reaches it at ``t0``: FORM-RCW on the
   linear + second-order surrogate (Eq. 6–7), or MLER;
3. **one** HF evaluation of that episode by an *episode oracle*
   ``oracle(episode) -> float`` (0 = no impact), taken as the HF value at
   level ``p`` (§5.1.3); the non-linear factor is ``f_NL = HF / target − 1``
   (Eq. 8) -- meaningful when HF and target are the same quantity.

The result is a :class:`~pas.study.result.ScreeningResult` like PAS and AS
give: ``mpm`` is the HF value of the ``P_exp`` episode, ``n_hf`` the
episodes evaluated, ``distribution`` the HF-vs-level points (with
``linear`` and ``f_nl`` columns), ``history`` one row per episode.  A design
wave has no uncertainty band of its own: the bands are NaN.
"""

from __future__ import annotations

import json
import os

import numpy as np
import pandas as pd

from .stats.exceedance import exceedance_probabilities, value_at_exceedance
from .strategies.stopping import range_grid
from .study.result import ScreeningResult, distribution_frame
from .study.oracles import call_oracle
from .waves.design import rayleigh_target
from .waves.surrogate import ResponseSurrogate
from .waves.episode import METHODS, Episode, design_episode

__all__ = ["run_rcw", "rcw_levels", "rcw_targets", "rcw_episodes", "TARGETS"]

TARGETS = ("rayleigh", "lf")


def rcw_levels(p_exp, levels=None) -> np.ndarray:
    """The ladder of exceedance levels, descending, with ``p_exp`` in it.

    Examples
    --------
    >>> rcw_levels(1e-3, [1e-2, 5e-4]).tolist()
    [0.01, 0.001, 0.0005]
    """
    p_exp = float(p_exp)
    if not 0.0 < p_exp < 1.0:
        raise ValueError(f"p_exp must lie in (0, 1), got {p_exp!r}")
    lv = np.atleast_1d(np.asarray([] if levels is None else levels, dtype=float))
    if lv.ndim != 1 or np.any(~((lv > 0) & (lv < 1))):
        raise ValueError("levels must be exceedance probabilities in (0, 1)")
    lv = np.unique(np.r_[lv, p_exp])
    return lv[::-1]


def rcw_targets(surrogate: ResponseSurrogate, levels, *, target="rayleigh", lf_peaks=None,
                n_waves=None, peaks_per_wave=1.0) -> np.ndarray:
    """Linear target response per level.

    Parameters
    ----------
    surrogate : ResponseSurrogate
    levels : array_like
        Exceedance probabilities per wave encounter.
    target : {"rayleigh", "lf"} or array_like, default "rayleigh"
        ``"rayleigh"``: :func:`~pas.waves.design.rayleigh_target` on the
        linear response variance ``surrogate.m0`` with ``peaks_per_wave``;
        ``"lf"``: the LF Monte-Carlo, ``lf_peaks`` sorted with ``d = k /
        n_waves`` and read at each level on ``ln d`` (the LF peaks must be
        peaks of the surrogate's linear response); or the targets themselves.
    lf_peaks, n_waves
        For ``target="lf"``.
    peaks_per_wave : float, default 1
        For ``target="rayleigh"``: response peaks per wave encounter.
    """
    levels = np.asarray(levels, dtype=float)
    if isinstance(target, str):
        if target not in TARGETS:
            raise ValueError(f"target must be one of {', '.join(TARGETS)} or the target values, "
                             f"got {target!r}")
        if target == "rayleigh":
            return rayleigh_target(surrogate.m0, levels, peaks_per_wave=peaks_per_wave)
        if lf_peaks is None or n_waves is None:
            raise ValueError("target='lf' needs lf_peaks and n_waves (the LF Monte-Carlo)")
        d, v = exceedance_probabilities(lf_peaks, n_waves)
        if levels.min() < d[0] or levels.max() > d[-1]:
            raise ValueError(f"levels must lie within the LF Monte-Carlo's range "
                             f"[{d[0]:.3g}, {d[-1]:.3g}]; give more LF peaks or other levels")
        return value_at_exceedance(d, v, levels)
    t = np.asarray(target, dtype=float)
    if t.shape != levels.shape or np.any(~np.isfinite(t)) or np.any(t == 0):
        raise ValueError("target values must be finite, non-zero and one per level")
    return t


def rcw_episodes(surrogate, levels, targets, *, method="form", tol=1e-6,
                 max_iter=50) -> list[Episode]:
    """One episode per (level, target): :func:`~pas.waves.episode.design_episode`."""
    return [design_episode(surrogate, t, method=method, level=p, index=i, tol=tol,
                           max_iter=max_iter)
            for i, (p, t) in enumerate(zip(levels, targets))]


def _read_record(path):
    done = {}
    if path is not None and os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            for line in f:
                line = line.strip()
                if line:
                    rec = json.loads(line)
                    if rec.get("error") is None:
                        done[rec["episode_id"]] = rec["hf"]
    return done


def _append_record(path, row):
    if path is None:
        return
    rec = {k: row[k] for k in ("episode_id", "level", "target", "hf", "error")}
    with open(path, "a", encoding="utf-8") as f:
        f.write(json.dumps(rec) + "\n")
        f.flush()
        os.fsync(f.fileno())


def run_rcw(surrogate, oracle, *, p_exp, levels=None, target="rayleigh", lf_peaks=None,
            n_waves=None, peaks_per_wave=1.0, method="form", tol=1e-6, max_iter=50,
            record=None, callback=None) -> ScreeningResult:
    """Predict the HF load at ``p_exp`` (and a ladder of levels) with design waves.

    Parameters
    ----------
    surrogate : ResponseSurrogate
        From :func:`pas.waves.response_surrogate`: the sea, the linear
        transfer function of the conditioned response and the wave model
        (linear, or linear + second order).
    oracle : callable
        ``oracle(episode) -> float``: the HF peak load of an
        :class:`~pas.waves.episode.Episode` (0 = no impact).  An exception,
        NaN, inf or a negative value is a failure, never 0.
        :class:`pas.CommandOracle` runs a program per episode and gives it the
        files ``{episode}`` and ``{components}``.
    p_exp : float
        Target exceedance probability per wave encounter.
    levels : array_like, optional
        More exceedance levels (the HF-vs-level curve); ``p_exp`` is added.
    target : {"rayleigh", "lf"} or array_like, default "rayleigh"
        Where the linear targets come from (:func:`rcw_targets`).
    lf_peaks, n_waves : optional
        LF Monte-Carlo peaks and wave encounters (``target="lf"``);
        ``n_waves`` is also stored on the result (M1).
    peaks_per_wave : float, default 1
        Rayleigh only: response peaks per wave encounter.
    method : {"form", "mler"}, default "form"
    tol, max_iter
        FORM tolerance and iteration limit.
    record : str or os.PathLike, optional
        JSON-lines file: every HF result is appended (and synced) as it
        arrives, and a rerun takes the recorded value of an identical
        episode instead of evaluating it again.
    callback : callable, optional
        ``callback(episode, row)`` after every episode.

    Returns
    -------
    ScreeningResult
        ``strategy`` is ``"rcw"`` (``"mler"`` with ``method="mler"``).

    Examples
    --------
    >>> import pas
    >>> from pas.waves import jonswap
    >>> from pas.waves import response_surrogate
    >>> s = response_surrogate(lambda w: jonswap(w, 10.0, 11.0), lambda w: 1.0 + 0 * w,
    ...                        depth=30.0, omega_max=2.0, second_order=False)
    >>> res = pas.run_rcw(s, lambda ep: 1.1 * ep.target, p_exp=1e-3)
    >>> res.n_hf, round(float(res.mpm / res.distribution["linear"].iloc[0]), 3)
    (1, 1.1)
    """
    if not isinstance(surrogate, ResponseSurrogate):
        raise ValueError("surrogate must be a ResponseSurrogate "
                         "(pas.waves.response_surrogate)")
    if not callable(oracle):
        raise ValueError("oracle must be a callable oracle(episode) -> float")
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    lv = rcw_levels(p_exp, levels)
    targets = rcw_targets(surrogate, lv, target=target, lf_peaks=lf_peaks, n_waves=n_waves,
                          peaks_per_wave=peaks_per_wave)
    done = _read_record(record)
    rows, n_hf, n_fp, n_failed = [], 0, 0, 0
    for ep in rcw_episodes(surrogate, lv, targets, method=method, tol=tol, max_iter=max_iter):
        if ep.id in done:
            value, error = float(done[ep.id]), None
        else:
            value, error = call_oracle(oracle, ep)
        status = "failed" if error else ("true_positive" if value > 0 else "false_positive")
        n_failed += error is not None
        n_hf += error is None
        n_fp += status == "false_positive"
        row = {"row": len(rows), "n_hf": n_hf, "episode_id": ep.id, "level": ep.level,
               "d": ep.level, "target": ep.target, "lf": ep.target, "hf": value,
               "f_nl": value / ep.target - 1.0 if error is None else np.nan, "status": status,
               "method": method, "beta": ep.beta, "iterations": ep.form.iterations,
               "form_converged": ep.form.converged, "residual": ep.form.residual,
               "error": error, "mpm": np.nan}
        if ep.id not in done:
            _append_record(record, row)
        rows.append(row)
        if callback is not None:
            callback(ep, row)
    return _result(rows, float(p_exp), n_waves, n_hf, n_fp, n_failed, method,
                   {"levels": lv.tolist(), "targets": np.asarray(targets).tolist(),
                    "target": target if isinstance(target, str) else "given",
                    "method": method, "t0": surrogate.t0, "duration": surrogate.template.duration,
                    "second_order": surrogate.second_order, "tol": tol, "max_iter": max_iter})


def _result(rows, p_exp, n_waves, n_hf, n_fp, n_failed, method, settings) -> ScreeningResult:
    hist = pd.DataFrame(rows)
    at_p = np.flatnonzero(np.isclose(hist["level"].to_numpy(), p_exp, rtol=1e-12, atol=0))[0]
    mpm = hist.at[at_p, "hf"]
    mpm = float("nan") if mpm is None else float(mpm)
    hist.loc[at_p, "mpm"] = mpm
    ok = hist[hist["status"] != "failed"].sort_values("level")
    d = ok["level"].to_numpy(dtype=float)
    h = ok["hf"].to_numpy(dtype=float)
    nan = np.full(d.size, np.nan)
    dist = distribution_frame(d, h, nan, nan).assign(linear=ok["target"].to_numpy(dtype=float),
                                                      f_nl=ok["f_nl"].to_numpy(dtype=float))
    grid = range_grid(p_exp)
    covered = d.size >= 2 and d[0] <= grid[0] * (1 + 1e-12) and d[-1] >= grid[-1] * (1 - 1e-12)
    curve = value_at_exceedance(d, h, grid) if covered else np.full(grid.size, np.nan)
    curves = pd.DataFrame([curve], index=[int(hist.at[at_p, "row"])], columns=grid)
    pairs = ok[["episode_id", "target", "hf", "level"]].rename(
        columns={"target": "lf", "level": "d"}).reset_index(drop=True)
    nan2 = (float("nan"), float("nan"))
    converged = bool(np.isfinite(mpm) and hist["form_converged"].all() and n_failed == 0)
    return ScreeningResult(
        strategy="rcw" if method == "form" else "mler", mpm=mpm, mpm_band=nan2,
        mpm_band_sampling=nan2, mpm_band_model=None, n_hf=n_hf, n_false_positive=n_fp,
        n_failed=n_failed, converged=converged, history=hist, distribution=dist, pairs=pairs,
        range_curves=curves, p_exp=p_exp, n_waves=int(n_waves) if n_waves else 0, seed=0,
        settings=settings)
