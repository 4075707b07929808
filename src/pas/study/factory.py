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
    Of the :class:`~pas.strategies.screening.LFSet`.
:data:`STUDY_SETTINGS`
    Keyword arguments of :class:`~pas.study.study.Study`.
"""

from __future__ import annotations

import inspect

from ..strategies.as_ import AS
from ..strategies.base import Strategy
from ..strategies.pas import PAS
from .schema import DEFAULT_MAX_HF

__all__ = ["study_settings", "STRATEGIES", "LF_SETTINGS", "STUDY_SETTINGS", "PRESETS", "DEFAULT_MAX_HF",
           "make_strategy", "split_settings", "apply_preset"]

STRATEGIES = {"pas": PAS, "as": AS}
"""Strategies by the name a study stores (``Strategy.name``)."""

LF_SETTINGS = ("n_waves", "p_exp", "threshold")
"""Settings of the LF screening set."""

STUDY_SETTINGS = ("eps1", "precision", "eps2", "k1", "k2", "stop_measure", "seed", "max_hf", "max_failures",
                  "stop_on_convergence", "adaptive_threshold", "threshold_step", "fp_run",
                  "legacy_md", "target")
"""Keyword settings of :class:`~pas.study.study.Study` (its constructor takes them all)."""


PRESETS = {
    "default": {},
    "paper": {
        "copula_fit": "itau",              # §2.8: Clayton, Gumbel, Frank by τ inversion
        "exclude_at_bound": False,         # §2.2: AIC with hysteresis over all five
        "skip_unsplittable": False,        # Eq. 16–17 verbatim
        "common_random_numbers": False,    # Eq. 7: new uniforms every iteration
        "z": 10,
        "estimator": "selected",           # §5.4: copula and marginals in selected-sample space
        "impact_model": False,             # Step 6: a positive draw for every conditioning peak
        "marginals_from": "kept",          # Step 7: outliers out of the iteration's fits
        "n_bootstrap": 0,                  # Eq. 10: the sampling band only
        "hf_marginal": "weibull",          # Eq. 15: a Weibull HF marginal
        "band_marginals": "fitted",        # (no model band in the paper; set for completeness)
        "band_lf_ranks": "fixed",          # (likewise)
        "lf_tail": "ranks",                # (the selected-space fit has no LF population ranks)
        "stop_measure": "step",            # App. C, Eq. 28: the per-iteration change
        "max_hf": None,                    # no budget (unless max_hf is given)
    },
}
"""Named bundles of PAS settings.  ``"paper"`` reproduces van Essen & Seyffert
(2026) as their scripts ran (``docs/departures.md`` lists every difference
from ``"default"``, with its reason and measured effect); settings given
explicitly beside a preset win."""


def apply_preset(preset: str | None, strategy, settings: dict) -> dict:
    """``settings`` (strategy and study settings) on top of the named preset's (PAS only)."""
    if preset in (None, "default"):
        return dict(settings)
    if preset not in PRESETS:
        raise ValueError(f"preset must be one of {', '.join(PRESETS)}, got {preset!r}")
    name = strategy if isinstance(strategy, str) else getattr(strategy, "name", None)
    if name != "pas":
        raise ValueError(f"preset {preset!r} is a set of PAS settings; it does not apply to "
                         f"{name or strategy!r}")
    return {**PRESETS[preset], **settings}


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


def study_settings(study) -> dict:
    """Everything that defines ``study``: its strategy settings and study settings (stored)."""
    strategy = study.strategy
    params = {}
    for name in strategy_parameters(type(strategy)):
        if not hasattr(strategy, name):
            raise AttributeError(f"strategy setting {name} is not kept on "
                                 f"{type(strategy).__name__} as an attribute")
        params[name] = getattr(strategy, name)
    lfset, stop = study.lfset, study.stopping
    return {"strategy": strategy.name, "strategy_settings": params,
            "n_waves": lfset.n_waves, "p_exp": lfset.p_exp, "threshold": lfset.threshold,
            "eps1": stop.eps1, "precision": stop.precision, "eps2": stop.eps2, "k1": stop.k1, "k2": stop.k2,
            "stop_measure": stop.measure, "legacy_md": study.legacy_md,
            "seed": study.seed, "max_hf": study.max_hf, "max_failures": study.max_failures,
            "stop_on_convergence": study.stop_on_convergence,
            "adaptive_threshold": study.adaptive_threshold,
            "threshold_step": study.threshold_step, "fp_run": study.fp_run,
            "target": study.target}
