"""Flat settings (a study file, ``--set NAME=VALUE``, a store of pas 0.1) to and from objects.

:func:`from_flat` reads the flat dict of a study file or the command line (a
store's is :func:`pas.study.factory.study_options`'s, with the same
:meth:`Stopping.from_flat <pas.study.settings.Stopping.from_flat>`); :data:`MOVED`
says where each keyword :func:`pas.run_pas` took in pas 0.1 lives now, for
the error an old keyword raises and for ``docs/reference/settings.md``
(:func:`moved_table`, a test checks the page against it).
"""

from __future__ import annotations

from ..strategies.as_ import AS
from ..strategies.flat import BAND_NAMES, FLAT_NAMES, OWN_NAMES, SETTINGS_PAGE
from ..strategies.flat import MOVED as STRATEGY_MOVED
from ..strategies.pas import PAS
from .factory import make_strategy, strategy_parameters
from .settings import BUDGET_NAMES, OTHER_STUDY_SETTINGS, STOPPING_NAMES, Budget, Stopping

__all__ = ["MOVED", "SETTINGS_PAGE", "from_flat", "moved_table"]

_ADVANCED = "pas.make_study(..., {name}=...), then .optimize(oracle)"
MOVED = {
    **STRATEGY_MOVED,
    **{name: f"PAS({name}=...)" for name in FLAT_NAMES if name not in STRATEGY_MOVED},
    **{flat: f"stopping=Stopping({field}=...)" for field, flat in STOPPING_NAMES.items()
       if field not in ("eps1", "eps2", "precision")},
    "max_failures": "budget=Budget(max_failures=...)",
    **{name: _ADVANCED.format(name=name)
       for name in OTHER_STUDY_SETTINGS[1:]},
    "ids": "lf_peaks=pandas.DataFrame({'lf': ...}, index=ids) (the index is the event id)",
    "meta": "lf_peaks=pandas.DataFrame({'lf': ..., 'name': ...}) (the other columns are "
            "event.meta)",
    "pending": "pas.make_study(...).optimize(oracle, pending=...)",
    "n_workers": "executor=N (an int: N local processes)",
    "preset": "strategy=PAS.paper() (strategy='paper' in pas.make_study)",
    **{name: f"strategy=AS({name}=...)" for name in strategy_parameters(AS)},
}
"""Where each keyword of :func:`pas.run_pas` in pas 0.1 that is no argument now lives."""


def from_flat(flat: dict, *, strategy: str = "pas", preset: str | None = None,
              strict: bool = True) -> dict:
    """Settings objects from one flat dict of names (``--set NAME=VALUE``, a study file, pas 0.1).

    Parameters
    ----------
    flat : dict
        Strategy settings (:mod:`pas.strategies.flat` for PAS, the
        constructor's arguments for AS) and study settings
        (:data:`pas.study.factory.STUDY_SETTINGS`), by their flat names.
    strategy : {"pas", "as"}
        The strategy they configure.
    preset : {None, "default", "paper"}
        ``"paper"``: names not in ``flat`` take :meth:`PAS.paper()
        <pas.strategies.pas.PAS.paper>`'s, :meth:`Stopping.paper`'s and
        :meth:`Budget.paper`'s values (an ``estimator`` given replaces the
        paper's with its own options).
    strict : bool, default True
        An option of the estimator not chosen is an error; False drops it (stores).

    Returns
    -------
    dict
        ``{"strategy": PAS or AS, "stopping": Stopping, "budget": Budget,
        **other study settings}``.

    Examples
    --------
    >>> s = from_flat({"n_bootstrap": 0, "k1": 10, "stop_measure": "step", "max_hf": None})
    >>> s["strategy"].band.n_bootstrap, s["stopping"], s["budget"].max_hf
    (0, Stopping(eps1=None, eps2=0.1, precision=None, fit_check=0.01, k1=10, k2=20, measure='step'), None)
    >>> from_flat({"eps1": 2.0}, preset="paper")["stopping"].measure
    'step'
    """  # noqa: E501 (doctest output line)
    if preset not in (None, "default", "paper"):
        raise ValueError(f"preset must be one of default, paper, got {preset!r}")
    paper = preset == "paper"
    if paper and strategy != "pas":
        raise ValueError(f"preset 'paper' is a set of PAS settings; it does not apply to "
                         f"{strategy!r}")
    taken = {*STOPPING_NAMES.values(), *BUDGET_NAMES.values(), *OTHER_STUDY_SETTINGS}
    rest = {k: v for k, v in flat.items() if k not in taken}
    study = {name: flat[name] for name in OTHER_STUDY_SETTINGS if name in flat}
    if paper:
        base = PAS.paper().settings()
        if rest.get("estimator", base["estimator"]) != base["estimator"]:
            base = {k: v for k, v in base.items() if k in OWN_NAMES or k in BAND_NAMES.values()}
        rest = {**base, **rest}
    built = PAS.from_flat(rest, strict=strict) if strategy == "pas" else make_strategy(strategy,
                                                                                       rest)
    built.paper_study = paper
    return {"strategy": built, "stopping": Stopping.from_flat(flat, paper=paper),
            "budget": Budget.from_flat(flat, paper=paper), **study}


def moved_table() -> str:
    """The Markdown table "old name -> new place" of :data:`MOVED` (for
    ``docs/reference/settings.md``)."""
    rows = ["| pas 0.1 keyword | now |", "|---|---|"]
    rows += [f"| `{name}` | `{place}` |" for name, place in sorted(MOVED.items())]
    return "\n".join(rows)
