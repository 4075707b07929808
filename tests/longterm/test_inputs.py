"""Bad long-term inputs give one line naming the argument and the fix; the level from a return
period."""

import numpy as np
import pandas as pd
import pytest

import pas
from pas.longterm.inputs import design_exceedance, encounters_per_year, read_sea_states


def _table(**changes):
    t = pd.DataFrame({"name": ["a", "b"], "probability": [0.6, 0.4], "n_waves": [100, 200],
                      "duration": [800.0, 2000.0]})
    for k, v in changes.items():
        t[k] = v
    return t


LF = {"a": np.linspace(0.1, 3.0, 100), "b": np.linspace(0.1, 4.0, 200)}


def _never(event):
    raise AssertionError("the oracle must not be called for bad input")


@pytest.mark.parametrize("table, lf, match", [
    (_table(probability=[0.6, 0.3]), LF, r"sea_states: the probabilities sum to 0\.9, not 1"),
    (_table(probability=[1.2, -0.2]), LF, r"probability of 'b' is negative"),
    (_table(), {**LF, "c": [1.0, 2.0]}, r"lf_peaks: sea state 'c' is not in sea_states"),
    (_table(), {"a": LF["a"]}, r"lf_peaks: no LF peaks for sea state 'b'"),
    (_table().drop(columns="duration"), LF, r"sea_states: column\(s\) duration missing"),
    (_table(name=["a", "a"]), LF, r"sea_states: name 'a' appears more than once"),
    (_table(n_waves=[50, 200]), LF, r"n_waves of 'a' is 50, below its 100 LF peaks"),
    (_table(n_waves=[100.5, 200]), LF, r"n_waves of 'a' must be a positive whole number"),
    (_table(duration=[0.0, 1.0]), LF, r"duration of 'a' must be > 0"),
    (_table(), {"a": LF["a"], "b": [1.0, np.nan]}, r"lf_peaks\['b'\] contains 1 NaN"),
    (_table().to_dict("list"), LF, r"sea_states must be a pandas DataFrame"),
    (_table(), [LF["a"], LF["b"]], r"lf_peaks must be a mapping"),
])
def test_bad_input_names_the_argument(table, lf, match):
    with pytest.raises(ValueError, match=match):
        pas.run_long_term(table, lf, _never, p_exceed=1e-3)


@pytest.mark.parametrize("kw, match", [
    ({}, "give exactly one of p_exceed"),
    ({"p_exceed": 1e-3, "return_period": 20}, "give exactly one of p_exceed"),
    ({"p_exceed": 1.5}, "p_exceed must lie strictly between 0 and 1"),
    ({"return_period": -1}, "return_period must be > 0"),
    ({"p_exceed": 1e-3, "batch_size": 0}, "batch_size must be a positive integer"),
])
def test_bad_level_or_setting(kw, match):
    with pytest.raises(ValueError, match=match):
        pas.run_long_term(_table(), LF, _never, **kw)


def test_oracle_must_be_callable():
    with pytest.raises(TypeError, match="oracle must be a callable"):
        pas.run_long_term(_table(), LF, 3.0, p_exceed=1e-3)


def test_return_period_gives_one_exceedance_in_that_many_years():
    states = read_sea_states(_table(), LF)
    # encounter rates 100/800 and 200/2000 per s, weighted 0.6 / 0.4, by hand
    per_second = 0.6 * 0.125 + 0.4 * 0.1
    assert encounters_per_year(states, 8766) == pytest.approx(per_second * 8766 * 3600, rel=1e-12)
    p = design_exceedance(states, None, 25, 8766)
    assert p == pytest.approx(1 / (25 * per_second * 8766 * 3600), rel=1e-12)


def test_a_table_of_peaks_gives_ids_and_meta():
    frame = pd.DataFrame({"lf": LF["a"], "id": [f"e{i}" for i in range(100)],
                          "seed": np.arange(100)})
    states = read_sea_states(_table(), {"a": frame, "b": LF["b"]})
    assert states[0].ids[3] == "e3" and states[0].meta[3] == {"seed": 3}
    assert states[1].ids is None and states[1].meta is None


def test_one_table_of_peaks_with_a_sea_state_column():
    frame = pd.DataFrame({"sea_state": ["b"] * 200 + ["a"] * 100,
                          "lf": np.concatenate([LF["b"], LF["a"]]),
                          "id": [f"b{i}" for i in range(200)] + [f"a{i}" for i in range(100)]})
    states = read_sea_states(_table(), frame)
    assert [s.name for s in states] == ["a", "b"]
    assert states[0].lf == pytest.approx(LF["a"], rel=1e-12) and states[0].ids[0] == "a0"
    assert states[1].ids[199] == "b199" and states[1].meta is None
