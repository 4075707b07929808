"""Running the long-term analysis: one PAS study per sea state, one HF budget, one store.

Each sea state that can reach the design level gets an ordinary
:class:`~pas.study.study.Study`, driven through its ask/tell interface, so
its failures, budget and crash safety are a study's; the HF events go where
:mod:`pas.longterm.allocation` says.  With ``study=PATH`` every sea state's
study lives in the one store file, scoped by the sea-state name
(:mod:`pas.study.schema`, version 3), next to the analysis's own settings
(scope ``""``, key ``longterm``): a killed run resumes where it stopped,
asks nothing twice and loses no result.
"""

from __future__ import annotations

import copy
import time

import numpy as np

from .._support.checks import draw_seed
from ..strategies.screening import LFSet
from ..study import precision as study_precision
from ..study.corrections import check_retry
from ..study.factory import study_options
from ..study.loop import check_command, failure_limit, run_batch
from ..study.oracles import OracleFailureLimit, check_oracle
from ..study.schema import StoreError, dumps
from ..study.store import StudyStore
from ..study.study import Study
from .allocation import REACH_SHARE, curves_of, gains, lf_shares, proxy_ratios, with_record
from .combination import level_at, proxy_curve, value_and_band
from .inputs import design_exceedance, encounter_weights, read_sea_states
from .result import LongTermResult
from .target import BANDS_KEY, LongTermTarget

__all__ = ["run_long_term", "LONG_TERM_KEY", "DEFAULT_LONG_TERM_MAX_HF"]

LONG_TERM_KEY = "longterm"
DEFAULT_LONG_TERM_MAX_HF = 400
"""Default HF budget of the whole analysis (enough for a green-water load over a scatter
diagram, ``docs/guide/long-term.md``)."""


def run_long_term(sea_states, lf_peaks, oracle, *, p_exceed=None, return_period=None,
                  hours_per_year=8766.0, max_hf=DEFAULT_LONG_TERM_MAX_HF, seed=None, study=None,
                  strategy=None, eps1=None, precision=None, study_settings=None, batch_size=1,
                  executor=None, callback=None, model_band=True,
                  retry_failed=False) -> LongTermResult:
    """The long-term design value of an HF load over a scatter diagram, one HF budget shared.

    Parameters
    ----------
    sea_states : pandas.DataFrame
        One row per sea state: ``name``, ``probability`` (share of time,
        summing to 1), ``n_waves`` (wave encounters of its LF run),
        ``duration`` (s, of its LF run), optionally ``threshold`` (its LF
        threshold) and any descriptive columns (``hs``, ``tp`` ...).
    lf_peaks : mapping
        ``name -> array`` of the LF indicator peaks of that sea state's run,
        one per wave event, or ``name -> DataFrame`` with ``lf``, ``id`` and
        metadata columns (handed to the oracle on ``event.meta``).
    oracle : callable
        ``oracle(event) -> float``, one for all sea states; ``event.sea_state``
        names the row, ``event.index`` the position in its array.
    p_exceed : float, optional
        Long-term exceedance probability per wave encounter of the design value.
    return_period : float, optional
        Instead of ``p_exceed``: years; ``p_exceed = 1 / (return_period ×
        encounters per year)``.
    hours_per_year : float, default 8766
        Hours at sea per year (with ``return_period``).
    max_hf : int, default 400
        HF evaluations of all sea states together.
    seed : int, optional
        Seeds every sea state's study; drawn and stored when None.
    study : str or os.PathLike, optional
        The one store file of the analysis: created when missing, else
        checked against this call and continued.
    strategy : Strategy, optional
        Each sea state's strategy, copied per sea state (default
        :class:`~pas.strategies.pas.PAS` with its defaults).
    eps1 : float, optional
        Stopping limit of each sea state's study (load units, as for
        :func:`pas.run_pas`): a study that converged gets no more events.
        None: the studies do not stop by themselves; the budget and the
        allocation decide.
    precision : float, optional
        A precision target for the long-term value (e.g. 0.10): the analysis
        stops once the U95 of the value lies within ``±precision × value``
        of it and the values of the last 20 allocation rounds inside that
        band (the rule of one sea state's ``precision``,
        :mod:`pas.longterm.target`); ``result.converged`` is True exactly
        then, and ``result.forecast_hf`` says how many more HF evaluations
        the target is expected to need.  None: the budget decides.  It may
        change when a stored analysis is continued.
    study_settings : dict, optional
        Further settings of every :class:`~pas.study.study.Study` (``eps2``,
        ``k1``, ``max_failures``, ``adaptive_threshold`` ...).
    batch_size : int, default 1
        Sea states served per round; their HF runs go to ``executor`` together.
    executor : concurrent.futures.Executor, optional
        Runs the oracle calls of a round concurrently (e.g. a Dask
        ``distributed.Client(...).get_executor()``): sea states in parallel.
    callback : callable, optional
        ``callback(name, study, row)`` after every told HF result.
    model_band : bool, default True
        Add each fitted study's model band to the result's band.
    retry_failed : bool, default False
        With ``study``: run the failed events of every sea state's stored
        study again (:meth:`Study.retry_failed
        <pas.study.study.Study.retry_failed>`): each study continues as if they
        had not failed; the events already given to other sea states stay
        theirs.

    Returns
    -------
    LongTermResult

    Raises
    ------
    OracleFailureLimit
        A sea state's study saw more than ``max_failures`` failed calls; the
        message names the sea state, every result is stored.
    """
    t_start = time.perf_counter()
    check_oracle(oracle)
    check_retry(retry_failed, study)
    if taken := sorted(set(study_settings or ()) & set(_OWN_STUDY_SETTINGS)):
        raise ValueError(f"study_settings: run_long_term sets {', '.join(taken)} itself (give "
                         "its own eps1, max_hf and seed); leave them out of study_settings")
    states = read_sea_states(sea_states, lf_peaks)
    p = design_exceedance(states, p_exceed, return_period, hours_per_year)
    weights = encounter_weights(states)
    batch_size = int(batch_size)
    if batch_size < 1:
        raise ValueError(f"batch_size must be a positive integer, got {batch_size}")
    top = max(float(s.lf.max()) for s in states)
    lf_value = level_at([proxy_curve(s, 1.0) for s in states], weights, p, top)
    target = LongTermTarget(precision, max_hf=max_hf)
    settings = {"p_exceed": p, "max_hf": max_hf, "eps1": eps1, "precision": target.precision,
                "sea_states": [[s.name, s.probability, s.n_waves, s.duration] for s in states]}
    root, seed = _open_root(study, settings, seed)
    strategy = _default_strategy() if strategy is None else strategy
    share_lf, q_lf = lf_shares(states, weights, lf_value) if np.isfinite(lf_value) else \
        (np.zeros(len(states)), np.zeros(len(states)))
    studies = [None if share_lf[i] < REACH_SHARE else _make_study(
        s, i, q_lf[i], strategy, seed, max_hf, eps1, study_settings or {}, study)
        for i, s in enumerate(states)]
    for st in studies if retry_failed else ():
        if st is not None and st.n_failed:
            st.retry_failed()
    if root is not None:
        target.restore(root.get(BANDS_KEY))
    run = _Run(states, weights, studies, oracle, executor, callback, max_hf, target=target,
               model_band=model_band, root=root)
    try:
        check_command(oracle, studies)
        run.left_over()
        run.allocate(p, batch_size, top)
    finally:
        if root is not None:
            root.close()
    result = LongTermResult.build(states, weights, studies, p, lf_value, seed, model_band, top,
                                  target=target, table=sea_states, seconds=run.seconds)
    result.seconds = time.perf_counter() - t_start
    return result


def _default_strategy():
    from ..strategies.pas import PAS

    return PAS()


def _open_root(path, settings, seed):
    """The store's own scope with the analysis's settings (checked when it exists), and the seed."""
    if path is None:
        return None, draw_seed(seed)
    root = StudyStore(path, scope="")
    stored = root.get(LONG_TERM_KEY)
    if stored is None and not root.is_new:
        root.close()
        raise StoreError(f"study store {path} holds a single study, not a long-term analysis: "
                         "give run_long_term another file")
    if stored is None:
        seed = draw_seed(seed)
        root.put(LONG_TERM_KEY, {**settings, "seed": seed})
        return root, seed
    for key in sorted(settings):
        old, new = stored.get(key), settings[key]
        if key in _MAY_CHANGE or dumps(old) == dumps(new):
            continue
        root.close()
        raise StoreError(f"{key} differs from the long-term store {path}: it was created with "
                         f"{key}={old!r}, this call has {key}={new!r}")
    if seed is not None and int(seed) != stored["seed"]:
        root.close()
        raise StoreError(f"seed differs from the long-term store {path}: it was created with "
                         f"seed={stored['seed']}, this call has seed={seed}")
    if any(stored.get(key) != settings[key] for key in _MAY_CHANGE):
        root.put(LONG_TERM_KEY, {**stored, **{key: settings[key] for key in _MAY_CHANGE}})
    return root, int(stored["seed"])


_MAY_CHANGE = ("max_hf", "precision")
"""Settings a continued analysis may change: its budget and its precision target."""


_OWN_STUDY_SETTINGS = ("eps1", "max_hf", "seed", "stop_on_convergence")
"""Settings of each sea state's study that :func:`run_long_term` sets itself."""


def _make_study(state, i, q_lf, strategy, seed, max_hf, eps1, settings, path) -> Study:
    """The sea state's study, at ``p_exp`` = its LF exceedance at the LF-only long-term level
    (within its record: ``1/n_w`` for a level above it)."""
    n_initial = strategy.n_initial
    mask = state.lf > state.threshold if state.threshold is not None else slice(None)
    p_exp = min(max(q_lf, 1.0 / state.n_waves), np.asarray(state.lf)[mask].size / state.n_waves)
    lfset = LFSet(state.lf, n_waves=state.n_waves, p_exp=p_exp, threshold=state.threshold,
                  ids=state.ids, meta=state.meta, min_peaks=max(4, n_initial),
                  sea_state=state.name)
    own_seed = int(np.random.SeedSequence([seed, i]).generate_state(1, dtype=np.uint64)[0]
                   % (2**63))
    store = None if path is None else StudyStore(path, scope=state.name)
    own = {"eps1": 1.0 if eps1 is None else eps1, "max_hf": max_hf,
           "stop_on_convergence": eps1 is not None, "seed": own_seed}
    options = study_options({**own, **settings})
    return Study(lfset, copy.deepcopy(strategy), store=store, **options)


class _Run:
    """The allocation loop over the sea states' studies."""

    def __init__(self, states, weights, studies, oracle, executor, callback, max_hf, target=None,
                 model_band=True, root=None):
        self.states, self.weights, self.studies = states, weights, studies
        self.oracle, self.executor, self.callback, self.max_hf = oracle, executor, callback, max_hf
        self.target = LongTermTarget(max_hf=max_hf) if target is None else target
        self.model_band, self.root = model_band, root
        self.seconds: dict[int, float] = {}  # wall time of each study's fits and bands
        self.closed: set[int] = set()
        self._curves: dict[int, tuple] = {}

    def spent(self) -> int:
        return sum(s.n_hf + s.n_pending for s in self.studies if s is not None)

    def left_over(self) -> None:
        """Events a killed run left asked but not told: told from the store or run again."""
        asks = []
        for i, st in enumerate(self.studies):
            if st is None:
                continue
            rows = st.store.outstanding() if st.store is not None else []
            events = [st.lfset.event(st.lfset.position_of(r.idx)) for r in rows] or st.pending
            if events:
                asks.append((i, events))
        if asks:
            self.round(asks)

    def curves(self, i, ratios) -> tuple:
        """Sea state ``i``'s curves for the gains, rebuilt only when its fit (or, for the
        LF-only proxy of an unfitted one, the HF/LF ratios) changed."""
        st = self.studies[i]
        pred = None if st is None else st.last
        cached = self._curves.get(i)
        if cached is None or cached[0] is not pred or (pred is None and cached[1] != ratios):
            cached = self._curves[i] = (pred, ratios,
                                        curves_of(self.states[i], st, ratios, record=False))
        return cached[2]

    def value_now(self, p, top):
        """``(triples, value, ratios)``: every sea state's curves for the gains, the long-term
        value they give and the HF/LF ratios of the proxies."""
        ratios = proxy_ratios(self.studies)
        triples = [self.curves(i, ratios) for i in range(len(self.states))]
        x = level_at([t[1] for t in triples], self.weights, p, top * ratios[1])
        return triples, x, ratios

    def reached(self, triples, x, ratios, p, top) -> bool:
        """Record the round in the target's history; whether the precision target is reached
        (the full band computed only when :meth:`LongTermTarget.band_due` asks for it)."""
        start = top * ratios[1]
        wide = [with_record(s, t) for s, t in zip(self.states, triples)]
        _, low, high = value_and_band(wide, self.weights, p, start)
        n_hf = sum(st.n_hf for st in self.studies if st is not None)
        lf_only = not any(st is not None and st.last is not None for st in self.studies)
        row = self.target.record(n_hf, x, (low, high), lf_only=lf_only)
        reached = False
        if self.target.band_due(row):
            if self.model_band:  # the bands the states' new results call for, one a core
                for i, wall in study_precision.model_bands(self.studies).items():
                    self.seconds[i] = self.seconds.get(i, 0.0) + wall
            full = [curves_of(s, st, ratios, model_band=self.model_of(i))
                    for i, (s, st) in enumerate(zip(self.states, self.studies))]
            _, low, high = value_and_band(full, self.weights, p, start)
            reached = self.target.judge(row, (low, high))
            if self.root is not None:
                self.root.put(BANDS_KEY, self.target.stored())
        self.target.forecast_into(row)
        return reached

    def model_of(self, i):
        """Study ``i``'s model band (kept until it is told more), None without a fit."""
        study = self.studies[i]
        if not self.model_band or study is None or study.last is None:
            return None
        t0 = time.perf_counter()
        band = study_precision.model_band(study, study.pairs())
        self.seconds[i] = self.seconds.get(i, 0.0) + time.perf_counter() - t0
        return band

    def allocate(self, p, batch_size, top) -> None:
        while True:
            triples, x, ratios = self.value_now(p, top)
            if (not np.isfinite(x) or self.reached(triples, x, ratios, p, top)
                    or self.spent() >= self.max_hf):
                return
            n_hf = [0 if st is None else st.n_hf for st in self.studies]
            fitted = [st is not None and st.last is not None for st in self.studies]
            gain = gains(triples, self.weights, x, n_hf, fitted)
            asks, room = [], self.max_hf - self.spent()
            for i in np.argsort(-gain, kind="stable"):
                st = self.studies[i]
                if len(asks) == batch_size or gain[i] <= 0:
                    break
                if st is None or i in self.closed or (not st.started
                                                      and st.strategy.n_initial > room):
                    continue
                events = st.ask(1)
                if not events:
                    self.closed.add(int(i))
                    continue
                room -= len(events)
                asks.append((int(i), events))
            if not asks:
                return
            self.round(asks)

    def round(self, asks) -> None:
        """Run the HF events of ``asks`` (``[(sea-state position, events)]``), store, then tell
        (:func:`pas.study.loop.run_batch`)."""
        position = {id(self.studies[i]): i for i, _ in asks}

        def tell(st, ev, value, error):
            i = position[id(st)]
            t0 = time.perf_counter()
            row = st.tell(ev, value, error=error)
            self.seconds[i] = self.seconds.get(i, 0.0) + time.perf_counter() - t0
            if self.callback is not None:
                self.callback(self.states[i].name, st, row)
            if (failure := failure_limit(st)) is not None:
                return OracleFailureLimit(f"sea state {self.states[i].name}: {failure}",
                                          result=failure.result)
            return None

        run_batch([(self.studies[i], events) for i, events in asks], self.oracle, self.executor,
                  tell)
