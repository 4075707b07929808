"""PAS settings as one flat dict of names: the study file's, the store's and pas 0.1's keywords.

The names come from the fields of the settings objects — :class:`PAS`'s own
arguments, ``estimator`` (the estimator's ``name``) and the fields of the
estimator and of :class:`~pas.strategies.band.ModelBand` (the band's with the
prefixes of :data:`BAND_NAMES`) — so there is one source of names.
:func:`pas_kwargs` reads such a dict back into :class:`PAS` keyword
arguments; :data:`MOVED` says where each flat name lives now, for the error
an old keyword raises.
"""

from __future__ import annotations

from dataclasses import asdict, fields

from .._support import docs_page
from .._support.checks import check_option
from .band import ModelBand
from .estimators import ESTIMATORS

__all__ = ["OWN_NAMES", "BAND_NAMES", "FLAT_NAMES", "MOVED", "pas_to_flat", "pas_kwargs",
           "moved_setting"]

OWN_NAMES = ("families", "z", "delta_aic", "exclude_at_bound", "skip_unsplittable",
             "impact_model", "impact_trend", "common_random_numbers")
"""Settings that are :class:`~pas.strategies.pas.PAS` arguments themselves."""

BAND_NAMES = {"n_bootstrap": "n_bootstrap", "marginals": "band_marginals",
              "lf_ranks": "band_lf_ranks", "model_form": "band_model_form"}
"""Flat name of each :class:`~pas.strategies.band.ModelBand` field."""

_ESTIMATOR_FIELDS = {name: tuple(f.name for f in fields(cls)) for name, cls in ESTIMATORS.items()}

FLAT_NAMES = (*OWN_NAMES, "estimator", *(f for names in _ESTIMATOR_FIELDS.values() for f in names),
              *BAND_NAMES.values())
"""Every flat PAS setting name."""

SETTINGS_PAGE = docs_page("reference/settings.md")

MOVED = {
    **{name: f"PAS(estimator={cls.__name__}({name}=...))"
       for cls in ESTIMATORS.values() for name in _ESTIMATOR_FIELDS[cls.name]},
    "estimator": "PAS(estimator=ConditionalLikelihood(...) or SelectedSample(...))",
    **{flat: f"PAS(band=ModelBand({field}=...))" for field, flat in BAND_NAMES.items()},
}
"""Where each flat PAS setting that is no argument of :class:`PAS` lives now."""


def moved_setting(where: str, name: str, moved: dict | None = None) -> str:
    """The one-line error for the old keyword ``name`` given to ``where``."""
    place = (moved or MOVED).get(name)
    if place is None:
        return f"{where}: unknown keyword argument {name!r}; see {SETTINGS_PAGE}"
    return f"{where}: {name} is now {place}; see {SETTINGS_PAGE}"


def pas_to_flat(strategy) -> dict:
    """The flat settings of a :class:`~pas.strategies.pas.PAS` instance."""
    own = {name: getattr(strategy, name) for name in OWN_NAMES}
    band = {BAND_NAMES[k]: v for k, v in asdict(strategy.band).items()}
    return {**own, "estimator": strategy.estimator.name, **asdict(strategy.estimator), **band}


def pas_kwargs(flat: dict, *, strict: bool = True) -> dict:
    """:class:`~pas.strategies.pas.PAS` keyword arguments from flat settings.

    Missing names take the objects' defaults.  With ``strict`` an option of
    the estimator not chosen, or an unknown name, is a ``ValueError``;
    without (reading a store written by pas 0.1 or 0.1.x, which kept every
    option whichever estimator ran) such options are dropped: they did not
    act.

    Examples
    --------
    >>> kw = pas_kwargs({"estimator": "selected", "copula_fit": "itau", "n_bootstrap": 0})
    >>> kw["estimator"], kw["band"].n_bootstrap
    (SelectedSample(copula_fit='itau', marginals_from='all', outlier_k=3.0, upper_tail=None), 0)
    >>> pas_kwargs({"copula_fit": "itau"})
    Traceback (most recent call last):
    ...
    ValueError: copula_fit is an option of estimator 'selected', not of 'conditional'
    """
    rest = dict(flat)
    name = check_option(rest.pop("estimator", "conditional"), "estimator", set(ESTIMATORS))
    own_fields = {k: rest.pop(k) for k in _ESTIMATOR_FIELDS[name] if k in rest}
    for other, names in _ESTIMATOR_FIELDS.items():
        for k in names:
            if k in rest and other != name:
                rest.pop(k)
                if strict:
                    raise ValueError(f"{k} is an option of estimator {other!r}, not of {name!r}")
    band = {field: rest.pop(flat_name) for field, flat_name in BAND_NAMES.items()
            if flat_name in rest}
    unknown = [k for k in rest if k not in OWN_NAMES]
    if unknown:
        raise ValueError(f"unknown setting {unknown[0]!r} for PAS; its settings are "
                         f"{', '.join(FLAT_NAMES)}")
    return {**rest, "estimator": ESTIMATORS[name](**own_fields), "band": ModelBand(**band)}
