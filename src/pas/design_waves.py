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
from .strategies.design_waves import DesignWaves, LevelLadder
from .strategies.stopping import range_grid
from .study.corrections import check_retry
from .study.oracles import check_oracle
from .study.result import ScreeningResult, distribution_frame
from .study.settings import Budget, Stopping
from .study.state import EventState
from .study.study import Study
from .waves.design import rayleigh_target
from .waves.episode import METHODS, Episode, design_episode
from .waves.surrogate import ResponseSurrogate

__all__ = ["run_rcw", "rcw_levels", "rcw_targets", "rcw_episodes", "TARGETS", "DesignWaveStudy",
           "EpisodeOracle", "read_record"]

TARGETS = ("rayleigh", "lf")
"""Names of the sources of the linear targets (:func:`rcw_targets`)."""

HISTORY_COLUMNS = ("row", "n_hf", "episode_id", "level", "d", "target", "lf", "hf", "f_nl",
                   "status", "method", "beta", "iterations", "form_converged", "residual",
                   "error", "mpm")
"""Columns of a design-wave result's ``history``, one row per episode."""


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


def rcw_targets(surrogate: ResponseSurrogate, levels, *, linear_target="rayleigh", lf_peaks=None,
                n_waves=None, peaks_per_wave=1.0) -> np.ndarray:
    """Linear target response per level.

    Parameters
    ----------
    surrogate : ResponseSurrogate
    levels : array_like
        Exceedance probabilities per wave encounter.
    linear_target : {"rayleigh", "lf"} or array_like, default "rayleigh"
        ``"rayleigh"``: :func:`~pas.waves.design.rayleigh_target` on the
        linear response variance ``surrogate.m0`` with ``peaks_per_wave``;
        ``"lf"``: the LF Monte-Carlo, ``lf_peaks`` sorted with ``d = k /
        n_waves`` and read at each level on ``ln d`` (the LF peaks must be
        peaks of the surrogate's linear response); or the targets themselves.
    lf_peaks, n_waves
        For ``linear_target="lf"``.
    peaks_per_wave : float, default 1
        For ``linear_target="rayleigh"``: response peaks per wave encounter.
    """
    levels = np.asarray(levels, dtype=float)
    if isinstance(linear_target, str):
        if linear_target not in TARGETS:
            raise ValueError(f"linear_target must be one of {', '.join(TARGETS)} or the target "
                             f"values, got {linear_target!r}")
        if linear_target == "rayleigh":
            return rayleigh_target(surrogate.m0, levels, peaks_per_wave=peaks_per_wave)
        if lf_peaks is None or n_waves is None:
            raise ValueError("linear_target='lf' needs lf_peaks and n_waves (the LF Monte-Carlo)")
        d, v = exceedance_probabilities(lf_peaks, n_waves)
        if levels.min() < d[0] or levels.max() > d[-1]:
            raise ValueError(f"levels must lie within the LF Monte-Carlo's range "
                             f"[{d[0]:.3g}, {d[-1]:.3g}]; give more LF peaks or other levels")
        return value_at_exceedance(d, v, levels)
    t = np.asarray(linear_target, dtype=float)
    if t.shape != levels.shape or np.any(~np.isfinite(t)) or np.any(t == 0):
        raise ValueError("linear_target values must be finite, non-zero and one per level")
    return t


def rcw_episodes(surrogate, levels, targets, *, method="form", tol=1e-6,
                 max_iter=50) -> list[Episode]:
    """One episode per (level, target): :func:`~pas.waves.episode.design_episode`."""
    return [design_episode(surrogate, t, method=method, level=p, index=i, tol=tol,
                           max_iter=max_iter)
            for i, (p, t) in enumerate(zip(levels, targets))]


DESIGN_WAVE_SETTINGS = ("strategy", "strategy_settings", "n_waves", "p_exp", "max_failures",
                        "target")
"""The settings a design-wave study stores (its episodes are its LF pool)."""


class DesignWaveStudy(Study):
    """A :class:`~pas.study.study.Study` whose events are the episodes of a ladder of levels.

    The strategy is :class:`~pas.strategies.design_waves.DesignWaves` and the
    pool a :class:`~pas.strategies.design_waves.LevelLadder`; ``episodes``
    (position order) give the result its FORM diagnostics and
    ``run_settings`` the rest of its ``settings`` (surrogate, FORM options).
    No stopping rule, threshold or budget applies; failures never stop the
    study (``max_failures`` is the number of episodes) but leave it
    unconverged.
    """

    def __init__(self, lfset, strategy, *, episodes=(), run_settings=None, store=None,
                 **options):
        self.episodes = list(episodes)
        self.run_settings = dict(run_settings or {})
        options = {"stopping": Stopping(eps1=1.0), "seed": 0, "adaptive_threshold": False,
                   "budget": Budget(max_hf=None, max_failures=lfset.n), **options}
        super().__init__(lfset, strategy, store=store, **options)

    def settings(self) -> dict:
        """What defines a design-wave study (the stopping settings do not apply)."""
        return {k: v for k, v in super().settings().items() if k in DESIGN_WAVE_SETTINGS}

    def retry_failed(self, ids=None) -> dict:
        """:meth:`Study.retry_failed <pas.study.study.Study.retry_failed>`, keeping the episodes."""
        kept = self.episodes, self.run_settings
        report = super().retry_failed(ids)
        self.episodes, self.run_settings = kept
        return report

    def episode_row(self, row: dict) -> dict:
        """The design-wave history row of the study's history ``row``."""
        ep = self.episodes[row["position"]]
        value, error = row["hf"], row["error"]
        return {"row": row["row"], "n_hf": row["n_hf"], "episode_id": ep.id, "level": ep.level,
                "d": ep.level, "target": ep.target, "lf": ep.target, "hf": value,
                "f_nl": value / ep.target - 1.0 if error is None else np.nan,
                "status": row["status"], "method": ep.method, "beta": ep.beta,
                "iterations": ep.form.iterations, "form_converged": ep.form.converged,
                "residual": ep.form.residual, "error": error, "mpm": np.nan}

    def result(self, *, model_band: bool = True) -> ScreeningResult:
        """The HF value at ``p_exp`` and the HF-vs-level points, from the latest result per episode.

        ``model_band`` is accepted for the study loop; a design wave has no band.
        """
        latest = {r["position"]: r for r in self.rows}
        rows, n_hf = [], 0
        for pos in sorted(latest):
            n_hf += EventState(latest[pos]["status"]).is_evaluated()
            rows.append({**self.episode_row(latest[pos]), "row": len(rows), "n_hf": n_hf})
        settings = {"levels": self.lfset.d.tolist(), "targets": self.lfset.lf.tolist(),
                    **self.run_settings}
        return _result(rows, self.lfset.p_exp, self.lfset.n_waves, self.strategy.name, settings,
                       complete=len(rows) == self.lfset.n)


class EpisodeOracle:
    """The oracle a design-wave study calls: the HF oracle on the episode of each event.

    ``recorded`` maps episode ids to HF values imported from a pas 0.1 record
    file; those episodes are not evaluated again.
    """

    def __init__(self, oracle, episodes, recorded=None):
        self.oracle, self.episodes, self.recorded = oracle, list(episodes), dict(recorded or {})

    def __call__(self, event):
        episode = self.episodes[event.index]
        if episode.id in self.recorded:
            return self.recorded[episode.id]
        return self.oracle(episode)


def read_record(path) -> dict:
    """``{episode_id: hf}`` of the successful results in a pas 0.1 record file (JSON lines)."""
    if not os.path.exists(path):
        raise ValueError(f"record: no file {os.fspath(path)!r}; record= only imports the results "
                         "of a pas 0.1 record file, new results go to study=")
    done = {}
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if not line.strip():
                continue
            try:
                rec = json.loads(line)
                if rec.get("error") is None:
                    done[str(rec["episode_id"])] = float(rec["hf"])
            except (ValueError, KeyError, TypeError, AttributeError) as exc:
                raise ValueError(f"record: line {n} of {os.fspath(path)!r} is not a pas 0.1 "
                                 f"record ({type(exc).__name__}: {exc})") from None
    return done


def run_rcw(surrogate, oracle, *, p_exp, levels=None, linear_target="rayleigh", lf_peaks=None,
            n_waves=None, peaks_per_wave=1.0, method="form", tol=1e-6, max_iter=50,
            study=None, retry_failed=False, target=None, executor=None, callback=None,
            record=None) -> ScreeningResult:
    """Predict the HF load at ``p_exp`` (and a ladder of levels) with design waves.

    The episodes run as the events of a study (:class:`DesignWaveStudy`), on
    the loop and store of PAS (:mod:`pas.study.loop`, :mod:`pas.study.store`).

    Parameters
    ----------
    surrogate : ResponseSurrogate
        From :func:`pas.waves.response_surrogate`: the sea, the linear
        transfer function of the conditioned response and the wave model
        (linear, or linear + second order).
    oracle : callable
        ``oracle(episode) -> float``: the HF peak load of an
        :class:`~pas.waves.episode.Episode` (0 = no impact), or named loads
        ``{name: load}`` with ``target``.  An exception, NaN, inf or a
        negative value is a failure, never 0.  :class:`pas.CommandOracle`
        runs a program per episode and gives it the files ``{episode}`` and
        ``{components}``.
    p_exp : float
        Target exceedance probability per wave encounter.
    levels : array_like, optional
        More exceedance levels (the HF-vs-level curve); ``p_exp`` is added.
    linear_target : {"rayleigh", "lf"} or array_like, default "rayleigh"
        Where the linear targets come from (:func:`rcw_targets`).
    lf_peaks, n_waves : optional
        LF Monte-Carlo peaks and wave encounters (``linear_target="lf"``);
        ``n_waves`` is also stored on the result (M1).
    peaks_per_wave : float, default 1
        Rayleigh only: response peaks per wave encounter.
    method : {"form", "mler"}, default "form"
    tol, max_iter
        FORM tolerance and iteration limit.
    study : str, os.PathLike or StudyStore, optional
        SQLite study store (:mod:`pas.study.store`): every HF result is
        stored the moment it arrives; a rerun with the same episodes takes
        the stored results and evaluates only the episodes without one
        (different episodes are refused).
    retry_failed : bool, default False
        With ``study``: evaluate the episodes that failed in it again.
    target : str, optional
        With an oracle answering several named loads: the one to use (as in
        :func:`pas.run_pas`; the store keeps all).
    executor : concurrent.futures.Executor, optional
        Run the episodes concurrently there (default: one after another here).
    callback : callable, optional
        ``callback(episode, row)`` after every episode evaluated in this call.
    record : str or os.PathLike, optional
        A record file of pas 0.1 (JSON lines), with ``study``: its results
        are imported for the episodes it holds.

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
    check_oracle(oracle)
    _check_renamed(target, record, study, retry_failed)
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    lv = rcw_levels(p_exp, levels)
    targets = rcw_targets(surrogate, lv, linear_target=linear_target, lf_peaks=lf_peaks,
                          n_waves=n_waves, peaks_per_wave=peaks_per_wave)
    episodes = rcw_episodes(surrogate, lv, targets, method=method, tol=tol, max_iter=max_iter)
    ladder = LevelLadder(lv, targets, ids=[ep.id for ep in episodes], p_exp=p_exp,
                         n_waves=n_waves)
    run_settings = {"target": linear_target if isinstance(linear_target, str) else "given",
                    "method": method, "t0": surrogate.t0,
                    "duration": surrogate.template.duration,
                    "second_order": surrogate.second_order, "tol": tol, "max_iter": max_iter}
    built = DesignWaveStudy(ladder, DesignWaves(method), episodes=episodes,
                            run_settings=run_settings, target=target, store=study)
    if retry_failed:
        built.retry_failed()
    recorded = {} if record is None else read_record(record)
    tell = None if callback is None else \
        (lambda s, row: callback(s.episodes[row["position"]], s.episode_row(row)))
    return built.optimize(EpisodeOracle(oracle, episodes, recorded), executor=executor,
                          callback=tell)


def _check_renamed(target, record, study, retry_failed) -> None:
    """One-line errors for the options of pas 0.1 that changed meaning or place."""
    if target is not None and (not isinstance(target, str) or target in TARGETS):
        raise ValueError(f"target names the load of a multi-load oracle since pas 0.2 (as in "
                         f"run_pas); give the linear target as linear_target={target!r:.40}")
    if record is not None and study is None:
        raise ValueError("record: results are stored in a study store since pas 0.2: give "
                         "study='rcw.sqlite' (with it, record= imports a 0.1 record file)")
    check_retry(retry_failed, study)


def _result(rows, p_exp, n_waves, name, settings, complete) -> ScreeningResult:
    """The result of the design-wave history ``rows`` (``complete``: every episode told)."""
    hist = pd.DataFrame(rows, columns=HISTORY_COLUMNS)
    at_p = np.flatnonzero(np.isclose(hist["level"].to_numpy(dtype=float), p_exp, rtol=1e-12,
                                     atol=0))
    mpm = hist.at[at_p[0], "hf"] if at_p.size else None
    mpm = float("nan") if mpm is None else float(mpm)
    hist.loc[at_p, "mpm"] = mpm
    status = hist["status"]
    n_failed = int((status == EventState.FAILED).sum())
    ok = hist[status != EventState.FAILED].sort_values("level")
    d = ok["level"].to_numpy(dtype=float)
    h = ok["hf"].to_numpy(dtype=float)
    nan = np.full(d.size, np.nan)
    dist = distribution_frame(d, h, nan, nan).assign(linear=ok["target"].to_numpy(dtype=float),
                                                      f_nl=ok["f_nl"].to_numpy(dtype=float))
    grid = range_grid(p_exp)
    covered = d.size >= 2 and d[0] <= grid[0] * (1 + 1e-12) and d[-1] >= grid[-1] * (1 - 1e-12)
    curve = value_at_exceedance(d, h, grid) if covered else np.full(grid.size, np.nan)
    curves = pd.DataFrame([curve], index=[int(hist.at[at_p[0], "row"]) if at_p.size else 0],
                          columns=grid)
    pairs = ok[["episode_id", "target", "hf", "level"]].rename(
        columns={"target": "lf", "level": "d"}).reset_index(drop=True)
    nan2 = (float("nan"), float("nan"))
    converged = bool(complete and np.isfinite(mpm) and hist["form_converged"].all()
                     and n_failed == 0)
    return ScreeningResult(
        strategy=name, mpm=mpm, mpm_band=nan2, mpm_band_sampling=nan2, mpm_band_model=None,
        n_hf=int(status.isin([EventState.TRUE_POSITIVE, EventState.FALSE_POSITIVE]).sum()),
        n_false_positive=int((status == EventState.FALSE_POSITIVE).sum()), n_failed=n_failed,
        converged=converged, history=hist, distribution=dist, pairs=pairs, range_curves=curves,
        p_exp=p_exp, n_waves=int(n_waves) if n_waves else 0, seed=0, settings=settings)
