"""The screening study: an ask/tell loop that runs any strategy against an HF oracle.

The loop (:meth:`Study.optimize`, :mod:`pas.study.loop`) is a client of
:meth:`Study.ask` and :meth:`Study.tell`, so slow external campaigns (CLI,
basin results that arrive days later) and a Python oracle run the same code.  The study owns
everything that is about *running* a campaign: the pool of events, false
positives (paper Step 6), failed oracle calls, the adaptive threshold
(§2.4), the stopping criterion (App. C) and the iteration history.
"""

from __future__ import annotations

import warnings
from dataclasses import asdict

import numpy as np
import pandas as pd

from .._support.checks import check_int, check_setting, draw_seed
from .._support.moved import keywords_moved
from ..strategies.base import Pairs, Prediction, Strategy
from ..strategies.flat import SETTINGS_PAGE
from ..strategies.screening import Event, LFSet
from ..strategies.stopping import StoppingRule, range_grid
from . import loop, precision
from .answers import check_hf_answer, check_target, lacks_target
from .corrections import Corrections
from .replay import attach
from .result import ScreeningResult
from .settings import (
    BUDGET_NAMES,
    STOPPING_NAMES,
    Budget,
    Stopping,
    lacks_a_limit,
)
from .state import EventState
from .study_settings import StudySettings

__all__ = ["Study"]

_MOVED = {**{flat: f"stopping=Stopping({field}=...)" for field, flat in STOPPING_NAMES.items()},
          **{flat: f"budget=Budget({field}=...)" for field, flat in BUDGET_NAMES.items()}}
"""Where each flat study setting the constructor took before its settings objects lives."""


class Study(StudySettings, Corrections):
    """One screening campaign.

    Parameters
    ----------
    lfset : LFSet
        LF peaks over threshold (steps 1–4).
    strategy : Strategy
        :class:`~pas.strategies.pas.PAS` or :class:`~pas.strategies.as_.AS`.
    stopping : Stopping, optional
        The stopping rule (App. C, and the precision target); it needs
        ``eps1`` or ``precision``.  Default ``Stopping()``
        (``Stopping.paper()`` for :meth:`PAS.paper() <pas.strategies.pas.PAS.paper>`).
    budget : Budget, optional
        HF evaluations and failed oracle calls the study may spend; default
        ``Budget()`` (``Budget.paper()``, no budget, for ``PAS.paper()``).
    seed : int, optional
        Seed of every random draw; drawn from the OS when None and reported.
    target : str, optional
        With an oracle answering several named loads ``{name: load}``: the
        one to screen on (:func:`~pas.study.answers.check_hf_answer`).
    stop_on_convergence : bool, default True
        False keeps sampling until ``budget.max_hf`` or the pool is empty.
    adaptive_threshold : bool, default True
        Raise the acquisition threshold by ``threshold_step`` × max LF after
        ``fp_run`` (5) consecutive false positives (§2.4; see
        :meth:`_maybe_raise_threshold` for the reading of the paper's rule).
    threshold_step : float, default 0.02
        The step of ``adaptive_threshold``, a share of the largest LF peak.
    fp_run : int, default 5
        False positives in a row that raise the threshold.
    legacy_md : bool, default False
        MD gaps between true positives only and the earlier reading of the
        threshold rule (pas 0.1): set for study stores written then, so they
        replay as they ran (:data:`~pas.study.schema.LEGACY_SETTINGS`).
    store : str, os.PathLike or StudyStore, optional
        Crash-safe SQLite store (:mod:`pas.study.store`): a new one records
        this study's settings, LF pool, every ask and every result as it
        happens; an existing one is checked against these settings and
        replayed, so the study continues where it stopped.  Without a store
        the study lives in memory only.

    Attributes
    ----------
    rule : StoppingRule
        The running stopping rule made from ``stopping``
        (:class:`~pas.strategies.stopping.StoppingRule`): its limits and the
        measures of every fit so far.
    """

    @keywords_moved(_MOVED, SETTINGS_PAGE, "Study")
    def __init__(self, lfset: LFSet, strategy: Strategy, *, stopping: Stopping | None = None,
                 budget: Budget | None = None, seed=None, target=None, stop_on_convergence=True,
                 adaptive_threshold=True, threshold_step=0.02, fp_run=5, legacy_md=False,
                 store=None):
        self.lfset = lfset
        self.strategy = strategy
        paper = getattr(strategy, "paper_study", False)  # PAS.paper(): the paper's defaults
        budget = (Budget.paper if paper else Budget)() if budget is None else budget
        stopping = (Stopping.paper if paper else Stopping)() if stopping is None else stopping
        for name, value, cls in (("stopping", stopping, Stopping), ("budget", budget, Budget)):
            if not isinstance(value, cls):
                raise TypeError(f"Study: {name} must be {cls.__name__}(...), got {value!r}")
        # its least value is the strategy's, stricter than the budget's own rule
        self.max_hf = (None if budget.max_hf is None
                       else check_int(budget.max_hf, "max_hf", strategy.n_initial))
        self.max_failures = budget.max_failures
        missing = lacks_a_limit(stopping.flat(), spell=lambda n: f"stopping=Stopping({n}=...)")
        if missing is not None:
            raise ValueError(f"Study: {missing}")
        self.rule = StoppingRule(**asdict(stopping))
        self.seed = draw_seed(check_setting("seed", seed))
        strategy.reset(self.seed)
        self.stop_on_convergence = check_setting("stop_on_convergence", stop_on_convergence)
        self.adaptive_threshold = check_setting("adaptive_threshold", adaptive_threshold)
        self.threshold_step = check_setting("threshold_step", threshold_step)
        self.fp_run = check_setting("fp_run", fp_run)
        self.legacy_md = check_setting("legacy_md", legacy_md)
        self.target = check_target(target)
        self.grid = range_grid(lfset.p_exp)
        self.state: dict[int, EventState] = {}
        self.value: dict[int, float] = {}
        self.rows: list[dict] = []
        self.curves: dict[int, np.ndarray] = {}
        self.l0 = lfset.threshold
        self.consecutive_fp = 0
        self.last: Prediction | None = None
        self.converged = False
        self._initial = None
        self._warned_tau = False
        self._before_fit = None  # (row, model state before the fit it made) of the last fit
        self.replaying = False  # True while pas.study.replay.attach replays a store's log
        self.kept_band = None  # (what it depends on, (low, high)): pas.study.precision
        self.stored_bands = {}  # a replayed store's model bands by history row
        self.store = None
        if store is not None:
            attach(self, store)

    # -- bookkeeping -------------------------------------------------------
    def _positions(self, status) -> list[int]:
        return [p for p, s in self.state.items() if s == status]

    def _told(self, *states) -> list[int]:
        """Positions now in one of ``states``, in the order they were first told."""
        return [
            p for p in dict.fromkeys(r["position"] for r in self.rows) if self.state[p] in states
        ]

    @property
    def n_pending(self) -> int:
        """Events asked for and not yet told."""
        return len(self._positions(EventState.PENDING))

    @property
    def started(self) -> bool:
        """True once the strategy's initial events have been asked for."""
        return self._initial is not None

    def start_with(self, positions) -> None:
        """Take ``positions`` as the initial events if none are yet (a stored log's first ask)."""
        if self._initial is None:
            self._initial = list(positions)

    @property
    def n_hf(self) -> int:
        return sum(s.is_evaluated() for s in self.state.values())

    @property
    def n_false_positive(self) -> int:
        return sum(s == EventState.FALSE_POSITIVE for s in self.state.values())

    @property
    def n_failed(self) -> int:
        return sum(s == EventState.FAILED for s in self.state.values())

    @property
    def pending(self) -> list[Event]:
        return [self.lfset.event(p) for p in self._positions(EventState.PENDING)]

    def pairs(self) -> Pairs:
        """True-positive pairs in evaluation order."""
        pos = np.array(self._told(EventState.TRUE_POSITIVE), dtype=int)
        fp = np.array(self._told(EventState.FALSE_POSITIVE), dtype=int)
        return Pairs(pos, self.lfset.lf[pos], np.array([self.value[p] for p in pos], dtype=float),
                     self.lfset.d[pos], self.lfset.lf[fp], fp)

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
        if self.max_hf is not None and self.n_hf + self.n_pending >= self.max_hf:
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
        elif self.finished and not self.replaying:
            return []
        else:
            # a replay repeats the stored asks whatever the (possibly changed) stopping
            # settings and budget say now: they decided when to stop, not what to ask
            room = n if self.max_hf is None or self.replaying else \
                min(n, self.max_hf - self.n_hf - self.n_pending)
            # MD's gaps run over every evaluated event, false positives included, and the
            # pending ones: only then can MD sample below the lowest true positive and
            # "oversample zero HF values" as §2.4 describes
            sel_d = self.lfset.d[self._told(EventState.TRUE_POSITIVE, EventState.FALSE_POSITIVE)
                                 + self._positions(EventState.PENDING)]
            if self.legacy_md and len(self.pairs()) >= 2:
                sel_d = self.pairs().d  # pas 0.1: gaps between true positives only
            if len(sel_d) >= 2:
                new = self.strategy.propose(sel_d, self.lfset, self.available(), self.last,
                                            q=max(room, 0))
            else:  # initial samples failed: try the next peaks nearest the initial targets
                new = self.strategy.initial_positions(self.lfset, self.available())[:max(room, 0)]
        for p in new:
            self.state[p] = EventState.PENDING
        events = [self.lfset.event(p) for p in new]
        if self.store is not None and events:
            self.store.record_ask(events)
        return events

    def tell(self, event, value=None, *, error: str | None = None, replace: bool = False) -> dict:
        """Record the HF result of an asked event and update the model.

        ``event`` is the :class:`Event` (or its index in ``lf_peaks``);
        ``value`` the HF peak (0 = no impact) or named loads ``{name: load}``
        (the store keeps all), or ``error`` a failure message.
        Returns the history row written.  ``tell`` only records: the limit
        on failed calls (``max_failures``) is the loop's to enforce
        (:mod:`pas.study.loop`).

        ``replace=True`` corrects a told result (a typo, a re-run basin test,
        a value for a failure): :class:`~pas.study.corrections.Corrections`
        says what changes and what stays; for a pending event it is a plain tell.
        Named loads replace the stored ones they name (the old ones are kept,
        ``store.load_replacements()``); when the screened load is unchanged
        nothing is refitted and the event's last history row is returned.
        """
        idx = event.index if isinstance(event, Event) else int(event)
        pos = self.lfset.position_of(idx)
        state = self.state.get(pos)
        if state != EventState.PENDING and not (replace and state is not None):
            raise ValueError(f"event {idx} was not asked for or is already told "
                             f"(state: {state or 'never asked'}); correct a told result "
                             "with replace=True")
        loads = None
        if error is None:
            value, error, loads = check_hf_answer(value, self.target)
            if lacks_target(loads, self.target):
                raise ValueError(error)
        ev = self.lfset.event(pos)
        replacing = state != EventState.PENDING
        if replacing and loads and (old := self._loads_alone(pos, ev, value, error, loads)):
            return old
        if self.store is not None:  # on disk before the fit; record_tell only marks it used
            self.store.record_result(ev, value, error, loads=loads, replace=replacing)
        if replacing:
            return self._replace(pos, ev, value, error)
        row = self._row(pos, ev, value, error)
        state = self.state[pos]
        if state == EventState.TRUE_POSITIVE:
            self.consecutive_fp = 0
        elif state == EventState.FALSE_POSITIVE:
            self.consecutive_fp += 1
            self._maybe_raise_threshold(ev)
        row["n_hf"] = self.n_hf
        self.rows.append(row)
        if state == EventState.TRUE_POSITIVE:
            self._iterate(row)
        row["threshold"] = self.l0
        if self.store is not None:
            self.store.record_tell(ev, row)
        return row

    def _maybe_raise_threshold(self, ev: Event) -> None:
        """§2.4: after ``fp_run`` consecutive false positives, raise ``l0``.

        As the paper writes it: the ``fp_run``-th consecutive false positive
        raises the acquisition threshold by ``threshold_step`` × the largest LF
        peak "when the exceedance probability of [the] new sample exceeds that
        of any existing sample" of the selected (true-positive) set — the new
        false positive lies below every true positive.  MD reaches there
        because its gaps include the false positives (:meth:`ask`).  With no
        true positive yet the condition is void.  The count starts again after
        a raise.
        """
        tp = self.pairs()
        below = len(tp) == 0 or (ev.d > tp.d.min() if self.legacy_md else ev.d > tp.d.max())
        if self.adaptive_threshold and self.consecutive_fp >= self.fp_run and below:
            base = self.lfset.lf.min() if self.l0 is None else self.l0
            self.l0 = float(base + self.threshold_step * self.lfset.lf.max())
            if not self.legacy_md:
                self.consecutive_fp = 0

    def _iterate(self, row: dict, replacing: bool = False) -> None:
        pairs = self.pairs()
        if len(pairs) < self.strategy.min_pairs or any(
                self.state[p] == EventState.PENDING for p in self._initial):
            return
        rng = np.random.default_rng([self.seed, self.n_told])
        self._remember_model_state(row)
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
        e, e_bar, cov, stop = self.rule.update(h_range, pred.mpm)
        if self.range_short(pred):
            stop = False
            row["range_short"] = True
        if self.rule.precision is not None:  # may compute the model band
            stop = precision.judge(self, pred, pairs, row, stop)
        self.curves[row["row"]] = h_range
        row.update(pred.record)
        row.update(mpm=pred.mpm, mpm_low=pred.mpm_band[0], mpm_high=pred.mpm_band[1],
                   n_pairs=len(pairs), E=e, E_bar=e_bar, COV=cov, stop=stop)
        self.converged = stop if replacing else self.converged or stop
        tau = pred.record.get("tau", np.nan)
        if (self.strategy.spreads_samples and len(pairs) >= 8 and tau <= 0
                and not self._warned_tau):
            self._warned_tau = True
            warnings.warn(
                f"Kendall's tau of the {len(pairs)} LF-HF pairs is {tau:.2f} <= 0: the LF "
                "indicator does not rank the HF loads, so the screening assumption fails; "
                "check the indicator, its threshold and the event matching", stacklevel=2)

    def range_short(self, pred: Prediction) -> bool:
        """True when the predicted distribution ends short of 2·P_exp.

        The MPM and the stopping range are then read off a clamped end of the
        distribution, so the study must not converge on them.
        """
        return pred.d[-1] < self.grid[-1]

    # -- running -----------------------------------------------------------
    def optimize(self, oracle, *, batch_size: int = 1, callback=None, executor=None,
                 n_workers=None, pending="resubmit") -> ScreeningResult:
        """Run the loop with a Python oracle until the study is finished.

        The loop is :func:`pas.study.loop.optimize` (its parameters):
        ``callback(study, row)`` is called after every told result (progress
        output, checkpoints); oracle calls run in this process, on an
        ``executor`` (any :class:`concurrent.futures.Executor`, e.g. a Dask
        client's ``get_executor()``) or in ``n_workers`` local processes; with
        a store each result is stored as it arrives and events left pending by
        a killed run are resubmitted (``pending="resubmit"``) or waited for
        (``"wait"``).  Raises :class:`~pas.study.oracles.OracleFailureLimit`
        after more than ``max_failures`` failed calls.
        """
        return loop.optimize(self, oracle, batch_size=batch_size, callback=callback,
                             executor=executor, n_workers=n_workers, pending=pending)

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
        """The current result (final after :meth:`optimize`).

        ``model_band`` adds the strategy's model-uncertainty band
        (:meth:`~pas.strategies.base.Strategy.model_band`) to the MPM's band.
        """
        return ScreeningResult.from_study(self, model_band=model_band)
