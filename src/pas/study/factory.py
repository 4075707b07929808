"""What a study is built from: the strategy registry and the names of the study settings.

:meth:`Study.from_settings <pas.study.study.Study.from_settings>` builds a
study from a settings dict (the one :meth:`~pas.study.study.Study.settings`
returns and the store keeps); :func:`pas.make_study`, ``pas study create`` and
the replay of a store all go through it.  A settings dict has the keys

``strategy``
    A name of :data:`STRATEGIES`, a :class:`~pas.strategies.base.Strategy`
    subclass or instance.
``strategy_settings``
    The strategy's settings by their flat names: PAS's of
    :mod:`pas.strategies.flat` (the fields of its settings objects), another
    strategy's constructor arguments.
:data:`LF_SETTINGS`
    Of the :class:`~pas.strategies.screening.LFSet`.
:data:`STUDY_SETTINGS`
    Keyword arguments of :class:`~pas.study.study.Study` (the flat names of
    :class:`~pas.study.settings.Stopping` and :class:`~pas.study.settings.Budget`
    among them).
"""

from __future__ import annotations

import inspect

from ..strategies.as_ import AS
from ..strategies.base import Strategy
from ..strategies.pas import PAS
from .settings import (
    BUDGET_NAMES,
    DEFAULT_MAX_HF,
    OTHER_STUDY_SETTINGS,
    STOPPING_NAMES,
    Budget,
    Stopping,
)

__all__ = ["study_settings", "study_options", "STRATEGIES", "LF_SETTINGS", "STUDY_SETTINGS",
           "DEFAULT_MAX_HF",
           "make_strategy"]

STRATEGIES = {"pas": PAS, "as": AS}
"""Strategies by the name a study stores (``Strategy.name``)."""

LF_SETTINGS = ("n_waves", "p_exp", "threshold")
"""Settings of the LF screening set."""

STUDY_SETTINGS = (*STOPPING_NAMES.values(), *BUDGET_NAMES.values(), *OTHER_STUDY_SETTINGS)
"""Keyword settings of :class:`~pas.study.study.Study` (its constructor takes them all): the
flat names of :class:`~pas.study.settings.Stopping` and :class:`~pas.study.settings.Budget`
and the others (:mod:`pas.study.settings`)."""


def strategy_parameters(cls) -> list[str]:
    """The keyword settings of strategy class ``cls``: its constructor's named parameters."""
    return [name for name, p in inspect.signature(cls).parameters.items()
            if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD)]


def make_strategy(strategy, settings=None) -> Strategy:
    """A strategy instance from a name, class or instance and its (flat) settings.

    Setting names are checked, so a misspelt one is an error naming the known
    ones and a ``TypeError`` raised inside a constructor is not mistaken for
    one; PAS reads the flat names of :mod:`pas.strategies.flat` (an option of
    the estimator not chosen is an error).

    Examples
    --------
    >>> make_strategy("pas", {"z": 20, "n_bootstrap": 0}).band.n_bootstrap
    0
    >>> make_strategy("as", {"zz": 1})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: unknown setting 'zz' for AS; its settings are fidelity, range_factor, ...
    """
    settings = dict(settings or {})
    if isinstance(strategy, str):
        if strategy not in STRATEGIES:
            raise ValueError(f"strategy must be one of {', '.join(STRATEGIES)}, got {strategy!r}")
        strategy = STRATEGIES[strategy]
    if isinstance(strategy, Strategy):
        if settings:
            raise ValueError(f"unknown settings {sorted(settings)}: give them to the "
                             f"{type(strategy).__name__} constructor")
        return strategy
    if not (isinstance(strategy, type) and issubclass(strategy, Strategy)):
        raise ValueError(f"strategy must be a name, a Strategy subclass or instance, "
                         f"got {strategy!r}")
    if issubclass(strategy, PAS):
        return strategy.from_flat(settings)
    known = strategy_parameters(strategy)
    for name in settings:
        if name not in known:
            raise ValueError(f"unknown setting {name!r} for {strategy.__name__}; its settings are "
                             f"{', '.join(known) or 'none'}")
    return strategy(**settings)


def strategy_flat_settings(strategy) -> dict:
    """The stored settings of a strategy instance: PAS's flat names, another strategy's
    constructor arguments (kept as attributes of the same names)."""
    if isinstance(strategy, PAS):
        return strategy.settings()
    params = {}
    for name in strategy_parameters(type(strategy)):
        if not hasattr(strategy, name):
            raise AttributeError(f"strategy setting {name} is not kept on "
                                 f"{type(strategy).__name__} as an attribute")
        params[name] = getattr(strategy, name)
    return params


def study_settings(study) -> dict:
    """Everything that defines ``study`` by flat names (what its store keeps): its strategy
    settings and study settings."""
    lfset, options = study.lfset, study.options()
    return {"strategy": study.strategy.name,
            "strategy_settings": strategy_flat_settings(study.strategy),
            "n_waves": lfset.n_waves, "p_exp": lfset.p_exp, "threshold": lfset.threshold,
            **options.pop("stopping").flat(), **options.pop("budget").flat(), **options}


def study_options(flat: dict) -> dict:
    """The :class:`~pas.study.study.Study` keywords from flat study settings (a store's,
    :data:`STUDY_SETTINGS`): the :class:`Stopping` and :class:`Budget` objects and the other
    settings given.  An unknown name is a ``ValueError`` naming the known ones."""
    unknown = sorted(set(flat) - set(STUDY_SETTINGS))
    if unknown:
        raise ValueError(f"unknown study settings {unknown}; known: "
                         f"{', '.join(sorted(STUDY_SETTINGS))}")
    return {"stopping": Stopping.from_flat(flat), "budget": Budget.from_flat(flat),
            **{name: flat[name] for name in OTHER_STUDY_SETTINGS if name in flat}}
