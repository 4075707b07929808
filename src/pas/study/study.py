"""The screening study: an ask/tell loop that runs any strategy against an HF oracle.

The in-process loop (:meth:`Study.optimize`) is a client of :meth:`Study.ask`
and :meth:`Study.tell`, so slow external campaigns (CLI, basin results that
arrive days later) and a Python oracle run the same code.  The study owns
everything that is about *running* a campaign: the pool of events, false
positives (paper Step 6), failed oracle calls, the adaptive threshold
(§2.4), the stopping criterion (App. C) and the iteration history.
"""

from __future__ import annotations

import inspect
import math
import warnings

import numpy as np
import pandas as pd

from .._validation import check_positive
from ..screening import Event, LFSet
from ..strategies.base import Pairs, Prediction, Strategy
from ..strategies.stopping import StoppingRule, range_grid
from .result import ScreeningResult, distribution_frame

__all__ = ["Study", "OracleFailureLimit", "check_hf_value"]

PENDING, TRUE_POSITIVE, FALSE_POSITIVE, FAILED = "pending", "true_positive", "false_positive", "failed"


class OracleFailureLimit(RuntimeError):
    """Raised when the oracle failed more often than ``max_failures``.

    ``result`` holds the study's result so far (nothing evaluated is lost).
    """

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


def check_hf_value(value):
    """Validate an oracle's answer: ``(float, None)`` or ``(None, error message)``.

    0 is a valid answer (no impact, a false positive); NaN, inf, negative and
    non-numeric answers are failures, never taken as 0.
    """
    if isinstance(value, bool):
        return None, f"oracle returned a bool ({value!r}), expected a load"
    try:
        v = float(value)
    except (TypeError, ValueError):
        return None, f"oracle returned {value!r}, not a number"
    if not math.isfinite(v):
        return None, f"oracle returned {v!r}"
    if v < 0:
        return None, f"oracle returned a negative load {v!r}"
    return v, None


def call_oracle(oracle, event: Event):
    """Call ``oracle(event)`` and validate the answer: ``(value, error)``."""
    try:
        raw = oracle(event)
    except Exception as exc:  # the oracle is user code: any failure is recorded
        return None, f"{type(exc).__name__}: {exc}"
    return check_hf_value(raw)


class Study:
    """One screening campaign.

    Parameters
    ----------
    lfset : LFSet
        LF peaks over threshold (steps 1–4).
    strategy : Strategy
        :class:`~pas.strategies.pas.PAS` or :class:`~pas.strategies.as_.AS`.
    eps1 : float
        Stopping limit on the mean distribution change, in load units.
    eps2 : float, default 0.1
        Stopping limit on the COV of the MPM.
    k1, k2 : int, default 20
        Stopping windows (App. C).
    seed : int, optional
        Seed of every random draw; drawn from the OS when None and reported.
    max_hf : int, optional
        Stop after this many HF evaluations (converged or not).
    max_failures : int, default 10
        Raise :class:`OracleFailureLimit` when more oracle calls fail.
    stop_on_convergence : bool, default True
        False keeps sampling until ``max_hf`` or the pool is empty.
    adaptive_threshold : bool, default True
        Raise the acquisition threshold by ``threshold_step`` × max LF after
        ``fp_run`` (5) consecutive false positives (§2.4; see
        :meth:`_maybe_raise_threshold` for the reading of the paper's rule).
    store : str, os.PathLike or StudyStore, optional
        Crash-safe SQLite store (:mod:`pas.study.store`): a new one records
        this study's settings, LF pool, every ask and every result as it
        happens; an existing one is checked against these settings and
        replayed, so the study continues where it stopped.  Without a store
        the study lives in memory only.
    """

    def __init__(self, lfset: LFSet, strategy: Strategy, *, eps1, eps2=0.1, k1=20, k2=20,
                 seed=None, max_hf=None, max_failures=10, stop_on_convergence=True,
                 adaptive_threshold=True, threshold_step=0.02, fp_run=5, store=None):
        self.lfset = lfset
        self.strategy = strategy
        strategy.reset()
        self.stopping = StoppingRule(eps1=check_positive(eps1, "eps1"),
                                     eps2=check_positive(eps2, "eps2"), k1=int(k1), k2=int(k2))
        if seed is None:
            seed = int(np.random.SeedSequence().entropy % (2**63))
        self.seed = int(seed)
        if max_hf is not None and (int(max_hf) != max_hf or max_hf < strategy.n_initial):
            raise ValueError(f"max_hf must be an integer ≥ {strategy.n_initial}, got {max_hf!r}")
        self.max_hf = None if max_hf is None else int(max_hf)
        self.max_failures = int(max_failures)
        self.stop_on_convergence = bool(stop_on_convergence)
        self.adaptive_threshold = bool(adaptive_threshold)
        self.threshold_step = float(threshold_step)
        self.fp_run = int(fp_run)
        self.grid = range_grid(lfset.p_exp)
        self.state: dict[int, str] = {}
        self.value: dict[int, float] = {}
        self.rows: list[dict] = []
        self.curves: dict[int, np.ndarray] = {}
        self.l0 = lfset.threshold
        self.consecutive_fp = 0
        self.last: Prediction | None = None
        self.converged = False
        self._initial = None
        self._warned_tau = False
        self.store = None
        if store is not None:
            from .store import attach
            attach(self, store)

    # -- bookkeeping -------------------------------------------------------
    def _positions(self, status) -> list[int]:
        return [p for p, s in self.state.items() if s == status]

    @property
    def n_hf(self) -> int:
        return sum(s in (TRUE_POSITIVE, FALSE_POSITIVE) for s in self.state.values())

    @property
    def n_false_positive(self) -> int:
        return sum(s == FALSE_POSITIVE for s in self.state.values())

    @property
    def n_failed(self) -> int:
        return sum(s == FAILED for s in self.state.values())

    @property
    def pending(self) -> list[Event]:
        return [self.lfset.event(p) for p in self._positions(PENDING)]

    def pairs(self) -> Pairs:
        """True-positive pairs in evaluation order."""
        pos = np.array([r["position"] for r in self.rows if r["status"] == TRUE_POSITIVE], dtype=int)
        fp = np.array([r["position"] for r in self.rows if r["status"] == FALSE_POSITIVE], dtype=int)
        return Pairs(pos, self.lfset.lf[pos], np.array([self.value[p] for p in pos], dtype=float),
                     self.lfset.d[pos], self.lfset.lf[fp])

    def available(self) -> np.ndarray:
        mask = np.ones(self.lfset.n, dtype=bool)
        if self.state:
            mask[list(self.state)] = False
        if self.l0 is not None:
            mask &= self.lfset.lf > self.l0
        return mask

    @property
    def finished(self) -> bool:
        """True when the study should ask for nothing more."""
        if self.converged and self.stop_on_convergence:
            return True
        if self.max_hf is not None and self.n_hf + len(self._positions(PENDING)) >= self.max_hf:
            return True
        return self._initial is not None and not self.available().any()

    # -- ask / tell --------------------------------------------------------
    def ask(self, n: int = 1) -> list[Event]:
        """Events to evaluate next, marked pending (empty when the study is finished).

        The first call returns the strategy's initial samples (4 for PAS);
        later calls propose up to ``n`` events (a batch when ``n > 1``).
        """
        if self._initial is None:
            self._initial = self.strategy.initial_positions(self.lfset)
            new = list(self._initial)
        elif self.finished:
            return []
        else:
            room = n if self.max_hf is None else min(n, self.max_hf - self.n_hf - len(self._positions(PENDING)))
            tp = self.pairs()
            if len(tp) >= 2:
                sel_d = tp.d
            else:
                sel_d = self.lfset.d[[r["position"] for r in self.rows if r["status"] != FAILED] +
                                     self._positions(PENDING)]
            if len(sel_d) >= 2:
                new = self.strategy.propose(sel_d, self.lfset, self.available(), self.last,
                                            q=max(room, 0))
            else:  # initial samples failed: try the next peaks nearest the initial targets
                new = self.strategy.initial_positions(self.lfset, self.available())[:max(room, 0)]
        for p in new:
            self.state[p] = PENDING
        events = [self.lfset.event(p) for p in new]
        if self.store is not None and events:
            self.store.record_ask(events)
        return events

    def tell(self, event, value=None, *, error: str | None = None) -> dict:
        """Record the HF result of an asked event and update the model.

        ``event`` is the :class:`Event` (or its index in ``lf_peaks``);
        ``value`` the HF peak (0 = no impact) or ``error`` a failure message.
        Returns the history row written.
        """
        idx = event.index if isinstance(event, Event) else int(event)
        pos = self.lfset.position_of(idx)
        if self.state.get(pos) != PENDING:
            raise ValueError(f"event {idx} was not asked for or is already told "
                             f"(state: {self.state.get(pos, 'never asked')})")
        if error is None:
            value, error = check_hf_value(value)
        ev = self.lfset.event(pos)
        if self.store is not None:
            self.store.record_result(ev, value, error)
        row = {"row": len(self.rows), "position": pos, "event_index": ev.index, "event_id": ev.id,
               "lf": ev.lf, "d": ev.d, "hf": value, "error": error}
        if error is not None:
            self.state[pos] = row["status"] = FAILED
        elif value > 0:
            self.state[pos] = row["status"] = TRUE_POSITIVE
            self.value[pos] = value
            self.consecutive_fp = 0
        else:
            self.state[pos] = row["status"] = FALSE_POSITIVE
            self.value[pos] = 0.0
            self.consecutive_fp += 1
            self._maybe_raise_threshold(ev)
        row["n_hf"] = self.n_hf
        self.rows.append(row)
        if row["status"] == TRUE_POSITIVE:
            self._iterate(row)
        row["threshold"] = self.l0
        if self.store is not None:
            self.store.record_tell(ev, row)
        if self.n_failed > self.max_failures:
            raise OracleFailureLimit(
                f"the HF oracle failed {self.n_failed} times (max_failures={self.max_failures}); "
                f"last error on event {ev.id}: {error}", result=self.result())
        return row

    def _maybe_raise_threshold(self, ev: Event) -> None:
        """§2.4: after ``fp_run`` consecutive false positives, raise ``l0``.

        The paper adds "and the exceedance probability of a new sample
        exceeds that of any existing sample".  Read as *every* selected
        sample, the rule can never fire under MD, whose proposals lie inside
        gaps between selected samples, and false positives could then eat the
        whole budget; it is read as *some* selected sample (the new sample is
        not the rarest one).  With no true positive yet the condition is void.
        """
        tp = self.pairs()
        if (self.adaptive_threshold and self.consecutive_fp >= self.fp_run
                and (len(tp) == 0 or ev.d > tp.d.min())):
            base = self.lfset.lf.min() if self.l0 is None else self.l0
            self.l0 = float(base + self.threshold_step * self.lfset.lf.max())

    def _iterate(self, row: dict) -> None:
        pairs = self.pairs()
        if len(pairs) < self.strategy.min_pairs or any(
                self.state[p] == PENDING for p in self._initial):
            return
        rng = np.random.default_rng([self.seed, len(self.rows)])
        try:
            pred = self.strategy.predict(pairs, self.lfset, rng)
        except (ValueError, np.linalg.LinAlgError, RuntimeError) as exc:
            # degenerate pairs (e.g. all HF values equal) must not stop a campaign:
            # the result stays recorded, the model waits for more data
            row["fit_error"] = f"{type(exc).__name__}: {exc}"
            warnings.warn(f"no model fit after event {row['event_id']}: {exc}", stacklevel=2)
            return
        self.last = pred
        h_range = pred.at(self.grid)
        e, e_bar, cov, stop = self.stopping.update(h_range, pred.mpm)
        if pred.d[-1] < self.grid[-1]:
            # the conditioning set does not reach 2·P_exp: the MPM and the stopping
            # range would be read off a clamped end of the distribution
            stop = False
            row["range_short"] = True
        self.curves[row["row"]] = h_range
        row.update(pred.record)
        row.update(mpm=pred.mpm, mpm_low=pred.mpm_band[0], mpm_high=pred.mpm_band[1],
                   n_pairs=len(pairs), E=e, E_bar=e_bar, COV=cov, stop=stop)
        self.converged = self.converged or stop
        tau = pred.record.get("tau", np.nan)
        if (self.strategy.spreads_samples and len(pairs) >= 8 and tau <= 0
                and not self._warned_tau):
            self._warned_tau = True
            warnings.warn(
                f"Kendall's tau of the {len(pairs)} LF-HF pairs is {tau:.2f} <= 0: the LF "
                "indicator does not rank the HF loads, so the screening assumption fails; "
                "check the indicator, its threshold and the event matching", stacklevel=2)

    # -- running -----------------------------------------------------------
    def optimize(self, oracle, *, batch_size: int = 1, callback=None, executor=None,
                 n_workers=None, pending="resubmit") -> ScreeningResult:
        """Run the loop with a Python oracle until the study is finished.

        ``callback(study, row)`` is called after every told result (progress
        output, checkpoints).  With a store, an ``executor`` (any
        :class:`concurrent.futures.Executor`, e.g. a Dask client's
        ``get_executor()``) or ``n_workers`` (a local process pool) the loop
        is :func:`pas.study.executor.optimize`, which stores each result as it
        arrives and handles events left pending by a killed run
        (``pending="resubmit"`` or ``"wait"``).
        """
        if self.store is not None or executor is not None or n_workers is not None:
            from .executor import optimize
            return optimize(self, oracle, batch_size=batch_size, callback=callback,
                            executor=executor, n_workers=n_workers, pending=pending)
        while True:
            events = self.ask(batch_size)
            if not events:
                break
            for ev in events:
                value, error = call_oracle(oracle, ev)
                row = self.tell(ev, value, error=error)
                if callback is not None:
                    callback(self, row)
        return self.result()

    def settings(self) -> dict:
        """Everything that defines this study: strategy settings and study settings."""
        strategy = self.strategy
        params = {}
        for name, p in inspect.signature(type(strategy).__init__).parameters.items():
            if name == "self" or p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
                continue
            if not hasattr(strategy, name):
                raise AttributeError(f"strategy setting {name} is not kept on "
                                     f"{type(strategy).__name__} as an attribute")
            params[name] = getattr(strategy, name)
        lfset, stop = self.lfset, self.stopping
        return {"strategy": strategy.name, "strategy_settings": params,
                "n_waves": lfset.n_waves, "p_exp": lfset.p_exp, "threshold": lfset.threshold,
                "eps1": stop.eps1, "eps2": stop.eps2, "k1": stop.k1, "k2": stop.k2,
                "seed": self.seed, "max_hf": self.max_hf, "max_failures": self.max_failures,
                "stop_on_convergence": self.stop_on_convergence,
                "adaptive_threshold": self.adaptive_threshold,
                "threshold_step": self.threshold_step, "fp_run": self.fp_run}

    # -- results -----------------------------------------------------------
    def history(self) -> pd.DataFrame:
        cols = ["row", "n_hf", "event_index", "event_id", "lf", "d", "hf", "status", "family",
                "mpm", "mpm_low", "mpm_high", "E", "E_bar", "COV", "threshold", "tau",
                "lambda_u", "lambda_l", "n_pairs", "n_outliers", "error", "fit_error"]
        df = pd.DataFrame(self.rows)
        for c in cols:
            if c not in df:
                df[c] = np.nan
        extra = [c for c in df.columns if c not in cols and c != "position"]
        return df[cols + extra]

    def result(self, *, model_band: bool = True) -> ScreeningResult:
        """The current result (final after :meth:`optimize`)."""
        hist = self.history()
        pairs = self.pairs()
        curves = pd.DataFrame.from_dict(self.curves, orient="index", columns=self.grid)
        if self.last is None:
            nan = float("nan")
            return ScreeningResult(
                strategy=self.strategy.name, mpm=nan, mpm_band=(nan, nan),
                mpm_band_sampling=(nan, nan), mpm_band_model=None, n_hf=self.n_hf,
                n_false_positive=self.n_false_positive, n_failed=self.n_failed,
                converged=False, history=hist,
                distribution=distribution_frame([], [], [], []),
                pairs=pd.DataFrame({"lf": pairs.lf, "hf": pairs.hf}), range_curves=curves,
                p_exp=self.lfset.p_exp, n_waves=self.lfset.n_waves, seed=self.seed,
                settings=self.settings())
        pred = self.last
        if pred.d[-1] < self.grid[-1]:
            warnings.warn(
                f"the predicted distribution ends at d = {pred.d[-1]:.3g}, short of "
                f"2·P_exp = {self.grid[-1]:.3g}: the lowest true positive lies above the LF "
                "level of P_exp, so the MPM is read off the end of the distribution and the "
                "study cannot converge; lower the threshold or check the false positives",
                stacklevel=2)
        band = pred.mpm_band
        model = None
        if model_band:
            rng = np.random.default_rng([self.seed, len(self.rows), 1])
            mb = self.strategy.model_band(pairs, self.lfset, rng)
            if mb is not None:
                model = (mb[0], mb[1])
                band = (min(band[0], mb[0]), max(band[1], mb[1]))
        ids = [self.lfset.event(p).id for p in pairs.position]
        return ScreeningResult(
            strategy=self.strategy.name, mpm=pred.mpm, mpm_band=band,
            mpm_band_sampling=pred.mpm_band, mpm_band_model=model, n_hf=self.n_hf,
            n_false_positive=self.n_false_positive, n_failed=self.n_failed,
            converged=self.converged, history=hist,
            distribution=distribution_frame(pred.d, pred.h_mean, pred.h_low, pred.h_high),
            pairs=pd.DataFrame({"event_id": ids, "lf": pairs.lf, "hf": pairs.hf, "d": pairs.d}),
            range_curves=curves, p_exp=self.lfset.p_exp, n_waves=self.lfset.n_waves,
            seed=self.seed, family=pred.record.get("family"), settings=self.settings(),
        )
