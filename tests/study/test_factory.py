"""Building studies: the strategy registry, setting names, Study.from_settings."""

import inspect

import numpy as np
import pytest

import pas
from pas.strategies.base import Strategy
from pas.study.factory import (
    LF_SETTINGS,
    STRATEGIES,
    STUDY_SETTINGS,
    make_strategy,
    study_options,
)
from pas.study.settings import BUDGET_NAMES, STOPPING_NAMES
from pas.study.study import Study

LF = np.random.default_rng(0).rayleigh(1.0, 400)


def test_registry_names_are_the_strategies_own():
    assert {name: cls.name for name, cls in STRATEGIES.items()} == {"pas": "pas", "as": "as"}


def test_study_settings_are_the_study_constructor_keywords():
    """Every flat study setting is a field of the Stopping or Budget the constructor takes,
    or a constructor keyword of its own."""
    params = inspect.signature(Study).parameters
    keywords = {n for n, p in params.items() if p.kind == p.KEYWORD_ONLY and n != "store"}
    objects = {*STOPPING_NAMES.values(), *BUDGET_NAMES.values()}
    assert keywords - {"stopping", "budget"} == set(STUDY_SETTINGS) - objects
    assert {"stopping", "budget"} <= keywords


def test_study_options_refuse_an_unknown_name():
    with pytest.raises(ValueError, match=r"unknown study settings \['k3'\]; known: "):
        study_options({"k1": 5, "k3": 1})
    assert study_options({"k1": 5, "max_failures": 2, "fp_run": 3}) == {
        "stopping": pas.Stopping(k1=5), "budget": pas.Budget(max_failures=2), "fp_run": 3}


def test_settings_round_trip_through_from_settings():
    study = pas.make_study(pas.AS(n_grid=51), LF, n_waves=400, p_exp=0.01, eps1=0.1, seed=3,
                           max_hf=9, fp_run=7)
    again = Study.from_settings(study.settings(), LF)
    assert again.settings() == study.settings()
    # precision is stored only when set (stores of 0.1 have none)
    assert set(study.settings()) == {"strategy", "strategy_settings", *LF_SETTINGS,
                                     *STUDY_SETTINGS} - {"precision", "fit_check"}


def test_unknown_names_are_errors_that_list_the_known_ones():
    with pytest.raises(ValueError, match="unknown setting 'zz' for PAS; its settings are families"):
        make_strategy("pas", {"zz": 1})
    with pytest.raises(ValueError, match="strategy must be one of pas, as"):
        make_strategy("gpr")
    with pytest.raises(ValueError, match="unknown study settings"):
        Study.from_settings({"strategy": "pas", "n_waves": 400, "p_exp": 0.01, "eps1": 0.1,
                             "k3": 1}, LF)
    with pytest.raises(ValueError, match="give them to the PAS constructor"):
        make_strategy(pas.PAS(), {"z": 5})


def test_a_type_error_inside_a_constructor_is_not_taken_for_a_bad_setting():
    class Broken(Strategy):
        def __init__(self, *, width=1.0):
            self.width = width + "1"  # a bug: TypeError

        def predict(self, pairs, lfset, rng):
            raise NotImplementedError

    with pytest.raises(TypeError, match="unsupported operand"):
        make_strategy(Broken, {"width": 2.0})
