"""A study's settings as small frozen objects: :class:`Stopping` and :class:`Budget`.

The store and the study file keep them as flat names (``eps1``,
``stop_measure``, ``max_hf`` …), which come from the objects' fields
(:meth:`Stopping.flat`, :data:`STOPPING_NAMES`); :mod:`pas.study.flat` reads
a flat dict back into the objects.  This module imports no strategy, so the
command line starts fast.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields

from .._support.checks import check_setting

__all__ = ["Stopping", "Budget", "DEFAULT_MAX_HF", "STOPPING_NAMES", "BUDGET_NAMES",
           "STOP_LIMITS", "lacks_a_limit",
           "OTHER_STUDY_SETTINGS", "RESUMABLE", "UNSET", "resolve"]

DEFAULT_MAX_HF = 160
"""Default budget of HF evaluations: the most the paper needed (case 4b, Table 4).

A study stops there, converged or not, so a typo cannot start thousands of
CFD runs; ``Budget(max_hf=None)`` lifts it."""


@dataclass(frozen=True)
class Stopping:
    """The stopping rule of App. C (van Essen & Seyffert 2026), checked after every fit.

    Parameters
    ----------
    eps1 : float, optional
        Limit on the mean change of the predicted distribution, in load units
        (paper: about 1–2 % of the expected maximum).
    eps2 : float, default 0.1
        Limit on the COV of the last ``k2`` MPMs.
    precision : float, optional
        A study setting of that name, passed on when given.
    fit_check : float or None, default 0.01
        With ``precision``: the level of the check the fitted model must pass on the
        evaluated loads (:func:`pas.stats.fit_check.uniform_check` of their
        transforms) before the study takes its band for the precision; None: the
        band alone decides.
    k1, k2 : int, default 20
        The windows of the two measures.
    measure : {"window", "step"}, default "window"
        ``Ē``: the change of the distribution across the last ``k1``
        iterations, or the mean per-iteration change of Eq. 28 (the paper,
        :meth:`paper`; :class:`~pas.strategies.stopping.StoppingRule`).
    """

    eps1: float | None = None
    eps2: float = 0.1
    precision: float | None = None
    fit_check: float | None = 0.01
    k1: int = 20
    k2: int = 20
    measure: str = "window"

    def __post_init__(self):
        _check_fields(self, STOPPING_NAMES)

    @classmethod
    def paper(cls, **given) -> Stopping:
        """The paper's rule: Eq. 28's per-iteration change (``measure="step"``)."""
        return cls(**{"measure": "step", **given})

    @classmethod
    def from_flat(cls, flat: dict, *, paper: bool = False) -> Stopping:
        """The rule from flat study settings (a store, a study file); other names are ignored
        and missing ones take the defaults (the paper's with ``paper``)."""
        given = {field: flat[name] for field, name in STOPPING_NAMES.items() if name in flat}
        return (cls.paper if paper else cls)(**given)

    def flat(self) -> dict:
        """The flat study settings (``stop_measure`` for ``measure``; ``precision`` and
        ``fit_check``, which acts with it, only when ``precision`` is set)."""
        out = {STOPPING_NAMES[k]: v for k, v in asdict(self).items()}
        if self.precision is None:
            del out["precision"], out["fit_check"]
        return out


@dataclass(frozen=True)
class Budget:
    """What a study may spend: HF evaluations and failed oracle calls.

    Parameters
    ----------
    max_hf : int or None, default 160
        The study stops after this many HF evaluations, converged or not
        (:data:`DEFAULT_MAX_HF`); None: no budget (:meth:`paper`).
    max_failures : int, default 10
        More failed oracle calls raise :class:`~pas.study.oracles.OracleFailureLimit`.
    """

    max_hf: int | None = DEFAULT_MAX_HF
    max_failures: int = 10

    def __post_init__(self):
        _check_fields(self, BUDGET_NAMES)

    @classmethod
    def paper(cls, **given) -> Budget:
        """No budget, as the paper's scripts ran."""
        return cls(**{"max_hf": None, **given})

    @classmethod
    def from_flat(cls, flat: dict, *, paper: bool = False) -> Budget:
        """The budget from flat study settings (a store, a study file), as
        :meth:`Stopping.from_flat`."""
        given = {field: flat[name] for field, name in BUDGET_NAMES.items() if name in flat}
        return (cls.paper if paper else cls)(**given)

    def flat(self) -> dict:
        """The flat study settings."""
        return asdict(self)


def _check_fields(settings, names: dict) -> None:
    """Check every field of a frozen settings object by the rule of its flat name
    (:data:`pas._support.checks.SETTING_CHECKS`), so an object refuses what a study file
    refuses, and keep the checked value (``3.0`` becomes ``3``)."""
    for field, name in names.items():
        object.__setattr__(settings, field, check_setting(name, getattr(settings, field)))


STOPPING_NAMES = {f.name: ("stop_measure" if f.name == "measure" else f.name)
                  for f in fields(Stopping)}
"""Flat name of each :class:`Stopping` field."""
BUDGET_NAMES = {f.name: f.name for f in fields(Budget)}
"""Flat name of each :class:`Budget` field."""
OTHER_STUDY_SETTINGS = ("seed", "stop_on_convergence", "adaptive_threshold", "threshold_step",
                        "fp_run", "legacy_md", "target")
"""Study settings that are keywords of :func:`pas.make_study` and of
:class:`~pas.study.study.Study` (no object of their own)."""
STOP_LIMITS = {"eps1": "a limit in load units, the paper's rule",
               "precision": "e.g. 0.10: stop once the U95 of the MPM is within ±10 % of it"}
"""The :class:`Stopping` settings that can each end a study by itself: a study needs one at
least (:func:`lacks_a_limit`)."""


def lacks_a_limit(flat: dict, spell=str) -> str | None:
    """The one-line error for flat settings that set none of :data:`STOP_LIMITS`, else None;
    ``spell(name)`` writes a name as the caller's user types it (``--eps1``).

    >>> lacks_a_limit({"eps1": 0.5}) is None
    True
    >>> lacks_a_limit({"eps2": 0.1}, spell=lambda n: "--" + n)[:17]
    'give --eps1 (a li'
    """
    if any(flat.get(name) is not None for name in STOP_LIMITS):
        return None
    return "give " + " or ".join(f"{spell(name)} ({why})" for name, why in STOP_LIMITS.items())


RESUMABLE = (*STOPPING_NAMES.values(), *BUDGET_NAMES.values())
"""Settings that may change when a study is resumed: the stopping rule and the
budget.  They decide when a study stops, never which event it asks for next."""


class _Unset:
    """The default of an argument that, when not given, takes the settings object's value."""

    def __repr__(self) -> str:
        return "<the budget's: 160, none with PAS.paper()>"


UNSET = _Unset()


def given_names(stopping, budget, *, eps1=None, eps2=None, precision=None,
                max_hf=UNSET) -> set:
    """The flat names of the stopping and budget settings a call to :func:`resolve` names."""
    given = {STOPPING_NAMES[k] for k, v in (("eps1", eps1), ("eps2", eps2),
                                            ("precision", precision)) if v is not None}
    if max_hf is not UNSET:
        given.add(BUDGET_NAMES["max_hf"])
    if stopping is not None:
        given.update(STOPPING_NAMES.values())
    if budget is not None:
        given.update(BUDGET_NAMES.values())
    return given


def keep_stored(stopping: Stopping, budget: Budget, stored: dict,
                given) -> tuple[Stopping, Budget]:
    """``stopping`` and ``budget`` with each :data:`RESUMABLE` setting not in ``given`` as
    ``stored`` (a store's flat settings) has it.

    A resumed study keeps the stopping rule and budget in its store (set by
    ``pas study set``, or by the call that created it) unless the call names
    them: a default never overwrites a stored value.
    """
    if not stored:
        return stopping, budget
    flat = {**stopping.flat(), **budget.flat()}
    for k in set(RESUMABLE) - set(given):
        if k in stored:
            flat[k] = stored[k]
        elif k in (STOPPING_NAMES["precision"], STOPPING_NAMES["fit_check"]):  # only when set
            flat.pop(k, None)
    return Stopping.from_flat(flat), Budget.from_flat(flat)


def resolve(where: str, strategy, stopping, budget, *, eps1=None, eps2=None, precision=None,
            max_hf=UNSET) -> tuple[Stopping, Budget]:
    """The :class:`Stopping` and :class:`Budget` of a call to :func:`pas.run_pas` (``where``).

    ``eps1``, ``eps2``, ``precision`` and ``max_hf`` fill the objects; given
    beside ``stopping=`` / ``budget=`` they are an error (the two would
    disagree).  Without objects the defaults are the paper's when
    ``strategy`` is :meth:`PAS.paper() <pas.strategies.pas.PAS.paper>`.
    """
    paper = getattr(strategy, "paper_study", False)
    given = {k: v for k, v in (("eps1", eps1), ("eps2", eps2), ("precision", precision))
             if v is not None}
    if stopping is None:
        stopping = (Stopping.paper if paper else Stopping)(**given)
    elif not isinstance(stopping, Stopping):
        raise TypeError(f"{where}: stopping must be Stopping(...), got {stopping!r}")
    elif given:
        raise ValueError(f"{where}: give {', '.join(given)} inside stopping=Stopping(...) or as "
                         "arguments, not both")
    if budget is None:
        budget = (Budget.paper if paper else Budget)(
            **({} if max_hf is UNSET else {"max_hf": max_hf}))
    elif not isinstance(budget, Budget):
        raise TypeError(f"{where}: budget must be Budget(...), got {budget!r}")
    elif max_hf is not UNSET:
        raise ValueError(f"{where}: give max_hf inside budget=Budget(...) or as an argument, "
                         "not both")
    return stopping, budget
