"""``pas impacts EVENTS.csv``: the printed summary, the written tables and figures, errors."""

import numpy as np
import pandas as pd

from pas.cli import main


def _events(tmp_path):
    # per-encounter table: 3 seeds x 2000 encounters, 3 % impacts, some in pairs 8 s apart
    rng = np.random.default_rng(0)
    rows = []
    for s in range(3):
        t = np.arange(2000) * 8.0
        hit = rng.random(2000) < 0.02
        hit[1:] |= hit[:-1] & (rng.random(1999) < 0.5)      # clustered followers
        load = np.where(hit, 100.0 + rng.weibull(1.2, 2000) * 500.0, 0.0)
        rows.append(pd.DataFrame({"t": t, "seed": s, "load": load}))
    ev = pd.concat(rows, ignore_index=True)
    path = tmp_path / "events.csv"
    ev.to_csv(path, index=False)
    return path, ev


def test_pas_impacts_prints_and_writes(tmp_path, capsys):
    path, ev = _events(tmp_path)
    out = tmp_path / "report"
    code = main(["impacts", str(path), "--t-min", "10", "--levels", "500",
                 "--exposure-hours", "3", "--encounter-period", "8", "--limit", "2000",
                 "--out", str(out)])
    text = capsys.readouterr().out
    assert code == 0
    n_imp = int((ev["load"] > 0).sum())
    assert f"{n_imp} impacts in 6000 encounters" in text
    assert "zero-inflation" in text and "declustered (t_min 10 s)" in text
    assert "ranked by AIC" in text and "P(maximum > 2000)" in text
    rates = pd.read_csv(out / "rates.csv", index_col="event")
    assert rates.loc["impact", "n_events"] == n_imp
    assert rates.loc["load > 500", "probability"] == (ev["load"] > 500).sum() / 6000
    fits = pd.read_csv(out / "fits.csv", index_col="candidate")
    assert fits["aic"].is_monotonic_increasing
    for name in ("inter_arrival.png", "qq.png", "exposure.png", "exposure.csv"):
        assert (out / name).stat().st_size > 1000


def test_pas_impacts_errors_are_one_line(tmp_path, capsys):
    path, _ = _events(tmp_path)
    assert main(["impacts", str(tmp_path / "missing.csv")]) == 2
    assert main(["impacts", str(path), "--load", "force"]) == 2
    assert main(["impacts", str(path), "--exposure-hours", "3"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 3 and all(e.startswith("pas impacts: error:") for e in err)
    assert "'force' not found" in err[1] and "--encounter-period" in err[2]
