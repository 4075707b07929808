"""``pas.lf_events``: from an LF time series to the events table, against known answers.

The known-answer record is built wave by wave: wave ``k`` is one full sine
cycle ``a_k sin(2 pi (t - s_k) / T_k)`` starting at ``s_k`` (a sample), so its
up-crossing is ``s_k``, its end ``s_k + T_k``, its crest ``a_k`` at
``s_k + T_k / 4`` (a sample too), with nothing computed by the code under test.
"""

import numpy as np
import pandas as pd
import pytest

import pas
from pas.study.inputs import split_lf_table

DT = 0.05


def cycles(amplitudes, periods, *, lead=20, tail=True):
    """Samples of a half trough (``lead`` samples), then one sine cycle per wave, then
    the first half of one more cycle (not a complete wave); and each wave's truth."""
    steps = np.round(np.asarray(periods) / DT).astype(int)
    assert np.all(steps % 4 == 0)
    parts = [-np.sin(np.pi * np.arange(1, lead) / lead)]          # negative, no up-crossing
    start = lead - 1
    starts = []
    for a, n in zip(amplitudes, steps):
        starts.append(start)
        parts.append(a * np.sin(2 * np.pi * np.arange(n) / n))
        start += n
    if tail:
        parts.append(0.5 * np.sin(np.pi * np.arange(20) / 20))    # up-crossing, no full wave
    x = np.concatenate(parts)
    s = np.asarray(starts) * DT
    truth = pd.DataFrame({"lf": amplitudes, "t_start": s, "t_end": s + steps * DT,
                          "t_peak": s + steps * DT / 4})
    return x, truth


@pytest.fixture
def record():
    rng = np.random.default_rng(3)
    amplitudes = rng.uniform(0.2, 3.0, 25)
    periods = rng.choice([4.0, 6.0, 8.0, 10.0, 12.0], 25)
    return cycles(amplitudes, periods) + (periods,)


def test_one_event_per_wave_with_its_crest_and_window(record):
    x, truth, periods = record
    ev = pas.lf_events(x, dt=DT, exposure=3 * 3600)
    assert ev.n_waves == 25
    assert list(ev.table.columns) == ["id", "lf", "record", "wave", "t_start", "t_peak", "t_end"]
    np.testing.assert_allclose(ev.table["lf"], truth["lf"], rtol=1e-12)
    for col in ("t_start", "t_end", "t_peak"):
        np.testing.assert_allclose(ev.table[col], truth[col], atol=1e-9)
    assert ev.mean_period == pytest.approx(periods.mean(), rel=1e-12)
    assert ev.p_exp == pytest.approx(periods.mean() / 10_800.0, rel=1e-12)
    assert ev.duration == pytest.approx(x.size * DT)
    assert ev.table["id"].is_unique and ev.table["record"].eq(0).all()
    assert ev.table["wave"].tolist() == list(range(25))


def test_up_crossings_between_samples_are_interpolated():
    # -cos(2 pi t / 10) crosses zero upwards at 2.5 + 10 k s, between the samples 0.3 s apart;
    # the curvature is zero there, so linear interpolation is exact to ~1e-4 s
    t = 0.3 * np.arange(400)
    ev = pas.lf_events(-np.cos(2 * np.pi * t / 10.0), dt=0.3)
    assert ev.n_waves == 11
    np.testing.assert_allclose(ev.table["t_start"], 2.5 + 10.0 * np.arange(11), atol=1e-3)
    np.testing.assert_allclose(ev.table["t_end"], 12.5 + 10.0 * np.arange(11), atol=1e-3)
    assert ev.mean_period == pytest.approx(10.0, abs=1e-4)


def test_time_index_of_a_series_is_kept(record):
    x, truth, _ = record
    t = 100.0 + DT * np.arange(x.size)
    ev = pas.lf_events(pd.Series(x, index=t))
    np.testing.assert_allclose(ev.table["t_start"], truth["t_start"] + 100.0, atol=1e-9)
    td = pd.to_timedelta(DT * np.arange(x.size), unit="s")
    ev2 = pas.lf_events(pd.Series(x, index=pd.Timestamp("2026-01-01") + td))
    np.testing.assert_allclose(ev2.table["t_peak"], truth["t_peak"], atol=1e-6)


def test_threshold_cuts_the_table_not_n_waves(record):
    x, truth, periods = record
    ev = pas.lf_events(x, dt=DT, threshold=1.5)
    over = truth["lf"] > 1.5
    assert 0 < over.sum() < 25
    assert ev.n_waves == 25 and ev.threshold == 1.5
    assert ev.mean_period == pytest.approx(periods.mean(), rel=1e-12)
    np.testing.assert_allclose(ev.table["lf"], truth["lf"][over], rtol=1e-12)
    assert ev.table["wave"].tolist() == list(np.flatnonzero(over))   # ids kept, not renumbered


def test_several_records_keep_their_names_and_own_times():
    x1, t1 = cycles([1.0, 2.0, 3.0], [4.0, 8.0, 12.0])
    x2, t2 = cycles([0.5, 0.7], [6.0, 10.0], lead=40)
    ev = pas.lf_events({"seed7": x1, "seed8": x2}, dt=DT, exposure=3600.0)
    assert ev.n_waves == 5
    assert ev.table["record"].tolist() == ["seed7"] * 3 + ["seed8"] * 2
    assert ev.table["id"].is_unique
    np.testing.assert_allclose(ev.table["t_start"], [*t1["t_start"], *t2["t_start"]], atol=1e-9)
    assert ev.mean_period == pytest.approx((4 + 8 + 12 + 6 + 10) / 5)
    assert ev.records["n_waves"].tolist() == [3, 2]
    assert ev.records["mean_period"].tolist() == pytest.approx([8.0, 8.0])
    listed = pas.lf_events([x1, x2], dt=DT)
    assert listed.table["record"].tolist() == [0, 0, 0, 1, 1]


def test_random_record_windows_hold_their_peak():
    rng = np.random.default_rng(11)
    t = np.arange(0, 600, 0.5)
    w = rng.uniform(0.4, 1.2, 30)
    x = (rng.rayleigh(0.2, 30) * np.cos(np.outer(t, w) + rng.uniform(0, 2 * np.pi, 30))).sum(1)
    ev = pas.lf_events(x, dt=0.5)
    ups = [i for i in range(1, x.size) if x[i - 1] < 0 <= x[i]]
    assert ev.n_waves == len(ups) - 1
    for row in ev.table.itertuples():
        inside = (t >= row.t_start) & (t < row.t_end)
        assert row.t_start <= row.t_peak < row.t_end
        assert row.lf == x[inside].max()


def test_table_feeds_run_pas_meta_and_command_placeholders(record):
    x, _, _ = record
    ev = pas.lf_events({"s1": x}, dt=DT, threshold=0.5)
    lf, ids, meta = split_lf_table(ev.table)
    assert ids == ev.table["id"].tolist()
    assert set(meta[0]) == {"record", "wave", "t_start", "t_peak", "t_end"}
    text = "--record {record} --t0 {t_start} --t1 {t_end}".format_map(meta[0])
    assert text == f"--record s1 --t0 {meta[0]['t_start']} --t1 {meta[0]['t_end']}"


@pytest.mark.parametrize("call, words", [
    (lambda x: pas.lf_events(x), "dt"),
    (lambda x: pas.lf_events(x, dt=0.0), "dt must be > 0"),
    (lambda x: pas.lf_events(np.vstack([x, x]), dt=DT), "list or a dict"),
    (lambda x: pas.lf_events(np.r_[x, np.nan], dt=DT), "NaN"),
    (lambda x: pas.lf_events(pd.Series(x), dt=DT), "time index"),
    (lambda x: pas.lf_events(pd.Series(x, index=-np.arange(x.size) * DT)), "increasing"),
    (lambda x: pas.lf_events(np.abs(x) + 1.0, dt=DT), "no complete zero-up-crossing wave"),
    (lambda x: pas.lf_events({"a": x, "b": x[:2]}, dt=DT), "series['b']"),
    (lambda x: pas.lf_events(x, dt=DT, threshold="2"), "threshold must be a number"),
    (lambda x: pas.lf_events(x, dt=DT, exposure=-1), "exposure must be > 0"),
    (lambda x: pas.lf_events({}, dt=DT), "series is an empty dict"),
    (lambda x: pas.lf_events(["a", "b", "c"], dt=DT), "must hold numbers"),
])
def test_bad_input_is_one_line_naming_the_argument(record, call, words):
    with pytest.raises(ValueError) as info:
        call(record[0])
    message = str(info.value)
    assert words in message and "\n" not in message
