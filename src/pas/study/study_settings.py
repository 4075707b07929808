"""A study's settings: a study built from them, and read back from a study.

:meth:`StudySettings.from_peaks` builds a :class:`~pas.study.study.Study` on
LF peaks from settings objects (what :func:`pas.make_study` calls);
:meth:`StudySettings.from_settings` from the flat settings a store keeps.
:meth:`StudySettings.settings` gives those flat settings back,
:meth:`StudySettings.options` the constructor's keywords.
"""

from __future__ import annotations

from dataclasses import fields

from ..strategies.base import Strategy
from ..strategies.screening import LFSet
from .factory import LF_SETTINGS, STUDY_SETTINGS, make_strategy, study_options, study_settings
from .settings import OTHER_STUDY_SETTINGS, Budget, Stopping
from .store import read_settings

__all__ = ["StudySettings"]


class StudySettings:
    """The settings side of :class:`~pas.study.study.Study` (a mixin)."""

    @classmethod
    def from_peaks(cls, strategy: Strategy, lf_peaks, *, n_waves, p_exp, threshold=None,
                   ids=None, meta=None, store=None, seed=None, **options):
        """A study of ``strategy`` on the LF peaks ``lf_peaks`` (its :class:`LFSet` built here).

        ``options`` are the constructor's keywords; with ``seed=None`` an
        existing store's seed is used.
        """
        lfset = LFSet(lf_peaks, n_waves=n_waves, p_exp=p_exp, threshold=threshold, ids=ids,
                      meta=meta, min_peaks=max(4, strategy.n_initial),
                      sea_state=getattr(store, "scope", None) or None)
        if store is not None and seed is None:
            seed = read_settings(store).get("seed")
        return cls(lfset, strategy, store=store, seed=seed, **options)

    @classmethod
    def from_settings(cls, settings: dict, lf_peaks, *, ids=None, meta=None,
                      store=None):
        """Build a study from its flat settings, the dict :meth:`settings` returns (a store's).

        Parameters
        ----------
        settings : dict
            ``strategy`` (a name, class or instance), ``strategy_settings``,
            ``n_waves``, ``p_exp``, ``threshold`` and the study settings by
            their flat names (:mod:`pas.study.factory`); unknown keys raise
            ``ValueError``.
        lf_peaks : array-like
            LF peak of every wave event.
        ids, meta : sequence, optional
            User ids / metadata per event.
        store : str, os.PathLike or StudyStore, optional
            As for the constructor; with no ``seed`` in ``settings`` an
            existing store's seed is used.
        """
        known = {"strategy", "strategy_settings", *LF_SETTINGS, *STUDY_SETTINGS}
        unknown = sorted(set(settings) - known)
        if unknown:
            raise ValueError(f"unknown study settings {unknown}; known: {', '.join(sorted(known))}")
        strategy = make_strategy(settings["strategy"], settings.get("strategy_settings"))
        return cls.from_peaks(strategy, lf_peaks, n_waves=settings["n_waves"],
                              p_exp=settings["p_exp"], threshold=settings.get("threshold"),
                              ids=ids, meta=meta, store=store,
                              **study_options({k: v for k, v in settings.items()
                                               if k in STUDY_SETTINGS}))

    def settings(self) -> dict:
        """Everything that defines this study, by flat names (what its store keeps)."""
        return study_settings(self)

    def options(self) -> dict:
        """The constructor's keywords that rebuild this study's settings (``stopping`` and
        ``budget`` as objects)."""
        rule = self.rule
        return {"stopping": Stopping(**{f.name: getattr(rule, f.name) for f in fields(Stopping)}),
                "budget": Budget(max_hf=self.max_hf, max_failures=self.max_failures),
                **{name: getattr(self, name) for name in OTHER_STUDY_SETTINGS}}
