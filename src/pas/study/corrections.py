"""Correcting a study: replacing a told result and retrying failed events.

Mixed into :class:`~pas.study.study.Study`; the store's side (the audit
trail, the rewound log) is :mod:`pas.study.amend`.

Replacing (``study.tell(event, value, replace=True)``)
    The new result replaces the old one in the fits from then on, at the
    event's place in the evaluation order; the history row written says
    which result it replaces (``replaced_hf``, ``replaced_error``) and the
    store keeps the old one (:meth:`StudyStore.replacements
    <pas.study.store.StudyStore.replacements>`).  The asks made since stay as
    they are, and so do the adaptive threshold and the count of consecutive
    false positives: MD gaps and threshold raises after it may differ from
    what the new value would have caused.  The model is refitted (each fit
    draws from ``default_rng([seed, n_told])``, a replaced event counting
    once) and convergence is decided again on that fit.  When the replaced
    event is the last one told and made the last fit, the refit starts from
    the model state before that fit (the selected copula of §2.2, warm starts, stopping windows), so
    the result is the one the new value would have given had it been told in
    the first place.
"""

from __future__ import annotations

import copy

from ..strategies.screening import Event
from .state import EventState

__all__ = ["Corrections", "check_retry"]


class Corrections:
    """:meth:`retry_failed` and the ``replace=True`` of :meth:`Study.tell
    <pas.study.study.Study.tell>`."""

    @property
    def n_told(self) -> int:
        """Events told so far (a replaced result counts once); seeds each fit's draws."""
        return len({r["position"] for r in self.rows})

    def _row(self, pos, ev, value, error) -> dict:
        """The history row of a result for ``ev``, its state and value set on the study."""
        state = self.state[pos] = EventState.of_result(value, error)
        self.value.pop(pos, None)
        if state.is_evaluated():
            self.value[pos] = value
        return {"row": len(self.rows), "position": pos, "event_index": ev.index,
                "event_id": ev.id, "lf": ev.lf, "d": ev.d, "hf": value, "error": error,
                "status": state.value}

    def _remember_model_state(self, row) -> None:
        """Keep the strategy and stopping state before the fit ``row`` makes (for a replacement)."""
        self._before_fit = (row["row"], copy.deepcopy(
            (vars(self.strategy), self.rule, self.converged), {id(self.lfset): self.lfset}))

    def _loads_alone(self, pos, ev, value, error, loads) -> dict | None:
        """The event's last history row when a replacement changes only its other named
        loads (stored, audited; nothing to refit), else None."""
        old = next(r for r in reversed(self.rows) if r["position"] == pos)
        if (old["hf"], old["error"]) != (value, error):
            return None
        if self.store is not None:
            self.store.record_result(ev, value, error, loads=loads, replace=True)
        return old

    def _replace(self, pos, ev, value, error) -> dict:
        old = next(r for r in reversed(self.rows) if r["position"] == pos)
        if self._before_fit is not None and self._before_fit[0] == old["row"] == len(self.rows) - 1:
            # the last fit was this event's: refit from the model state before it, as if the
            # new value had been told in the first place
            strategy_vars, self.rule, self.converged = self._before_fit[1]
            vars(self.strategy).clear()
            vars(self.strategy).update(strategy_vars)
        row = self._row(pos, ev, value, error)
        row.update(replaced_hf=old["hf"], replaced_error=old["error"], n_hf=self.n_hf)
        self.rows.append(row)
        self.last = None  # the old fit used the old value
        self._iterate(row, replacing=True)
        row["threshold"] = self.l0
        if self.store is not None:
            self.store.record_tell(ev, row, replace=True)
        return row

    def retry_failed(self, ids=None) -> dict:
        """Run failed events again after their cause is fixed: rewind the store and replay.

        ``ids`` are the event ids (or :class:`Event` objects) to retry, all
        failed events when None.  The store's log is cut back to the first
        retried failure: the asks made after it (the substitutes the failures
        caused) leave the log, the retried events become pending and the
        study is replayed, so :meth:`optimize` asks what an uninterrupted run
        with the fixed oracle would have asked.  Results told after the cut are
        kept and reused when the study asks for those events again; those it no
        longer asks for stay in the store (``StudyStore.dropped()``) unused.
        The exact rules are in :mod:`pas.study.amend`.

        Returns
        -------
        dict
            ``retried`` (event ids), ``dropped`` (asks taken out of the log)
            and ``kept`` (their results kept for reuse).
        """
        if self.store is None:
            raise ValueError("retry_failed needs a study store: create the study with store=... "
                             "(a failed event of a study in memory cannot be rewound)")
        keys = None if ids is None else [str(i.id if isinstance(i, Event) else i) for i in ids]
        report = self.store.retry_failed(keys)
        if report["retried"]:
            self.__dict__.update(type(self)(self.lfset, self.strategy, store=self.store,
                                            **self.options()).__dict__)
        return report


def check_retry(retry_failed: bool, store) -> None:
    """A ``ValueError`` when ``retry_failed=True`` is given without ``study=`` (a store):
    a failed event of a study in memory cannot be rewound."""
    if retry_failed and store is None:
        raise ValueError("retry_failed=True needs study=... (a study store: the failed "
                         "events of a study in memory cannot be rewound)")
