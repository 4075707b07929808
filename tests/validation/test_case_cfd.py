"""The CFD validation case from its table: the LF record, the table's provenance, the truth,
and ``pas reproduce cfd`` (seconds, no CFD)."""

import numpy as np
import pytest

from pas.validation.case_cfd import CFD_CASE, cfd_lf_record, cfd_table, cfd_truth


@pytest.fixture(scope="module")
def record():
    return cfd_lf_record()


def test_lf_record_is_twelve_hours_of_the_sea_state(record):
    events, n_waves, p_exp = record
    assert n_waves == len(events) and events["id"].is_unique
    tz = p_exp * CFD_CASE.exposure
    # a JONSWAP(3.3) sea's zero-crossing period is about Tp / 1.28; band-limited at 1.6 rad/s
    assert 0.70 * CFD_CASE.tp < tz < 0.85 * CFD_CASE.tp
    assert n_waves == pytest.approx(12 * 3600 / tz, rel=0.01)
    # crests of a narrow-band linear sea are Rayleigh: P(C > c) = exp(-8 c^2 / Hs^2)
    for c in (3.0, 4.0):
        share = (events["lf"] > c).mean()
        assert share == pytest.approx(np.exp(-8 * c ** 2 / CFD_CASE.hs ** 2), rel=0.35)
    assert (events["t_start"] < events["t_peak"]).all() and \
        (events["t_peak"] < events["t_end"]).all()


def test_table_has_its_provenance_and_every_event_above_the_cut(record):
    events, n_waves, p_exp = record
    table = cfd_table()
    ok = table[table["status"] == "ok"]
    assert len(ok) >= 0.95 * len(table)
    assert ok["openfoam"].str.startswith("OPENFOAM=1912").all()
    assert (ok["n_cells"] > 0).all() and (ok["wall_seconds"] > 0).all()
    assert (ok["cell"] == 0.5).all()
    ranked = events.sort_values("lf", ascending=False)["id"].tolist()
    # the events run are the largest LF events, then a sample: no gap among the top ones
    have = set(table["id"])
    n_top = next(i for i, e in enumerate(ranked) if e not in have)
    assert n_top >= 10 * p_exp * n_waves / 2
    # the LF column is the record's, not something else
    lf = events.set_index("id").loc[ok["id"], "lf"].to_numpy()
    np.testing.assert_allclose(ok["lf"].to_numpy(), lf, rtol=1e-5)


def test_truth_is_the_interpolated_rank_of_p_exp(record):
    events, n_waves, p_exp = record
    ok = cfd_table().query("status == 'ok'")
    h = np.sort(ok[CFD_CASE.load].to_numpy())[::-1]
    k = p_exp * n_waves                                  # about 12 exceedances
    lo = int(np.floor(k))                                # rank lo and lo + 1 (1-based)
    w = (np.log(k) - np.log(lo)) / (np.log(lo + 1) - np.log(lo))
    expected = h[lo - 1] + w * (h[lo] - h[lo - 1])
    assert cfd_truth(events, ok, n_waves, p_exp) == pytest.approx(expected, rel=1e-12)
    assert k >= 10


def test_reproduce_cfd_prints_every_strategy(capsys):
    from pas.cli import main

    assert main(["reproduce", "cfd", "--strategies", "pas,as"]) == 0
    out = capsys.readouterr().out
    for name in ("pas", "paper", "as", "LF events", "design wave (MLER)", "truth MPM"):
        assert name in out
