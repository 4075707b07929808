"""What a study is built from: the strategy registry and the names of the study settings.

:meth:`Study.from_settings <pas.study.study.Study.from_settings>` builds a
study from a settings dict (the one :meth:`~pas.study.study.Study.settings`
returns and the store keeps); :func:`pas.make_study`, ``pas study create`` and
the replay of a store all go through it.  A settings dict has the keys

``strategy``
    A name of :data:`STRATEGIES`, a :class:`~pas.strategies.base.Strategy`
    subclass or instance.
``strategy_settings``
    Keyword arguments of the strategy's constructor.
:data:`LF_SETTINGS`
    Of the :class:`~pas.screening.LFSet`.
:data:`STUDY_SETTINGS`
    Keyword arguments of :class:`~pas.study.study.Study`.
"""

from __future__ import annotations

import inspect

from ..strategies.as_ import AS
from ..strategies.base import Strategy
from ..strategies.pas import PAS

__all__ = ["STRATEGIES", "LF_SETTINGS", "STUDY_SETTINGS", "make_strategy", "split_settings"]

STRATEGIES = {"pas": PAS, "as": AS}
"""Strategies by the name a study stores (``Strategy.name``)."""

LF_SETTINGS = ("n_waves", "p_exp", "threshold")
"""Settings of the LF screening set."""

STUDY_SETTINGS = ("eps1", "eps2", "k1", "k2", "seed", "max_hf", "max_failures",
                  "stop_on_convergence", "adaptive_threshold", "threshold_step", "fp_run")
"""Keyword settings of :class:`~pas.study.study.Study` (its constructor takes them all)."""


def strategy_parameters(cls) -> list[str]:
    """The keyword settings of strategy class ``cls``: its constructor's named parameters."""
    return [name for name, p in inspect.signature(cls).parameters.items()
            if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD)]


def make_strategy(strategy, settings=None) -> Strategy:
    """A strategy instance from a name, class or instance and its settings.

    Setting names are checked against the constructor's signature, so a
    misspelt one is an error naming the known ones and a ``TypeError`` raised
    inside a constructor is not mistaken for one.

    Examples
    --------
    >>> make_strategy("pas", {"z": 20}).z
    20
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
    known = strategy_parameters(strategy)
    for name in settings:
        if name not in known:
            raise ValueError(f"unknown setting {name!r} for {strategy.__name__}; its settings are "
                             f"{', '.join(known) or 'none'}")
    return strategy(**settings)


def split_settings(settings: dict) -> tuple[dict, dict]:
    """Split flat keyword settings into ``(study settings, strategy settings)``."""
    study = {k: v for k, v in settings.items() if k in STUDY_SETTINGS}
    return study, {k: v for k, v in settings.items() if k not in STUDY_SETTINGS}
