"""Retrying failed events and the failure-limit flow: a set-up mistake is mended, not
fatal.

The reference of every test is an uninterrupted run with the fixed oracle, run
by the same code: the point is that a failed-then-retried campaign makes the
same decisions, so its numbers must agree with that run, not with a constant.
"""

import json
import logging
import sqlite3
import textwrap

import numpy as np
import pandas as pd
import pytest

import pas
from pas import PAS, Budget, ModelBand
from pas.cli import main
from pas.study import open_study
from pas.study.store import StoreError, StudyStore, Tell

N = 400
LF = np.random.default_rng(0).rayleigh(1.0, N)
KW = dict(n_waves=N, p_exp=1e-2, eps1=1e-3, seed=5)
NO_BAND = PAS(band=ModelBand(n_bootstrap=0))
MAX_HF = 12
LENIENT = Budget(max_hf=MAX_HF, max_failures=50)  # failed events get substitutes
BROKEN_ABOVE = 2.2  # the wrong input deck fails for the largest events (48 of 400)


def good(ev):
    return 2.0 * ev.lf ** 1.2


class Flaky:
    """The oracle with a set-up mistake: fails for the largest events until ``fixed``."""

    def __init__(self):
        self.fixed, self.calls = False, []

    def __call__(self, ev):
        self.calls.append(ev.index)
        if not self.fixed and ev.lf > BROKEN_ABOVE:
            raise RuntimeError("input deck names a missing mesh")
        return good(ev)


def _asks(db):
    with StudyStore(db, create=False) as store:
        return list(store.events()["idx"])


def test_retry_after_substitutes_asks_what_an_uninterrupted_run_asks(tmp_path, caplog):
    """Reproduction: resumed with a larger max_failures the largest events stayed failed."""
    ref_db, db = str(tmp_path / "ref.db"), str(tmp_path / "s.db")
    ref = pas.run_pas(LF, good, study=ref_db, strategy=NO_BAND, max_hf=MAX_HF, **KW)
    oracle = Flaky()
    first = pas.run_pas(LF, oracle, study=db, strategy=NO_BAND, budget=LENIENT, **KW)
    assert first.n_failed >= 2 and _asks(db) != _asks(ref_db)   # substitutes were asked
    with StudyStore(db, create=False) as store:
        told_before = {r.idx: r.hf for r in store.events().itertuples() if r.state == "done"}
    oracle.fixed, oracle.calls = True, []
    with caplog.at_level(logging.INFO, logger="pas"):
        res = pas.run_pas(LF, oracle, study=db, strategy=NO_BAND, budget=LENIENT,
                          retry_failed=True, **KW)
    assert f"resuming {db}: {len(first.history)} results reused" in caplog.text
    assert res.n_failed == 0 and res.n_hf == ref.n_hf
    assert res.mpm == pytest.approx(ref.mpm, rel=1e-9)
    assert _asks(db) == _asks(ref_db)
    # told results were reused, not recomputed; the oracle ran only for what was new
    assert not set(oracle.calls) & set(told_before)
    assert len(oracle.calls) == ref.n_hf - len(set(_asks(db)) & set(told_before))
    with StudyStore(db, create=False) as store:
        dropped = store.dropped()
        final = set(store.events()["idx"])
    retried = [d for d in dropped if d["reason"] == "retried failure"]
    assert {d["error"] for d in retried} == {"RuntimeError: input deck names a missing mesh"}
    for d in dropped:   # nothing told is lost: a kept result is reused or waits unused
        if d["reusable"]:
            assert (d["reused_seq"] is not None) == (d["idx"] in final)
    again = open_study(db)      # the rewound log replays
    assert again.result().mpm == pytest.approx(ref.mpm, rel=1e-9)
    again.store.close()


def test_retry_of_chosen_events_and_its_errors(tmp_path):
    db = str(tmp_path / "s.db")
    oracle = Flaky()
    pas.run_pas(LF, oracle, study=db, strategy=NO_BAND, budget=Budget(max_hf=6, max_failures=50),
                **KW)
    with StudyStore(db, create=False) as store:
        ev = store.events()
        failed = [str(i) for i in ev.loc[ev["state"] == "failed", "event_id"]]
        done = str(ev.loc[ev["state"] == "done", "event_id"].iloc[0])
        with pytest.raises(StoreError, match=f"event {done} is done, not failed"):
            store.retry_failed([done])
        with pytest.raises(StoreError, match="event nope was never asked for"):
            store.retry_failed(["nope"])
        report = store.retry_failed(failed[-1:])
        assert report["retried"] == failed[-1:]
        states = dict(zip(store.events()["event_id"].astype(str), store.events()["state"]))
        assert states.get(failed[-1]) in (None, "pending")     # re-asked or dropped
        assert all(states[k] == "failed" for k in failed[:-1] if k in states)
    with pytest.raises(ValueError, match="retry_failed=True needs study="):
        pas.run_pas(LF, good, retry_failed=True, n_waves=N, p_exp=1e-2, eps1=1e-3)
    with pytest.raises(ValueError, match="needs a study store"):
        pas.make_study(NO_BAND, LF, max_hf=MAX_HF, **KW).retry_failed()


def test_a_result_told_for_a_dropped_pending_event_is_kept(tmp_path):
    db = str(tmp_path / "s.db")
    study = pas.make_study(NO_BAND, LF, store=db, max_hf=MAX_HF, **KW)
    first = study.ask()
    for ev in first[:-1]:
        study.tell(ev, good(ev))
    study.tell(first[-1], error="mesh missing")
    later = study.ask(2)                           # substitutes, pending at the basin
    study.store.close()
    with StudyStore(db, create=False) as store:
        report = store.retry_failed()
        assert report["dropped"] == 2 and report["kept"] == 0
        assert store.tell_by_key(later[0].id, 7.5, source="basin")   # arrives after the retry
        kept = [d for d in store.dropped() if d["key"] == str(later[0].id)]
        assert kept[0]["hf"] == 7.5 and kept[0]["reusable"] == 1
        assert isinstance(store.ops()[-1], Tell)     # the log ends before the retried failure


# -- the command line ------------------------------------------------------------------------
ORACLE = textwrap.dedent(f"""\
    import os, pathlib
    FLAG = pathlib.Path(__file__).with_name("broken.flag")

    def load(event):
        with open(pathlib.Path(__file__).with_name("calls.log"), "a") as f:
            f.write(f"{{event.id}}\\n")
        if FLAG.exists() and event.lf > {BROKEN_ABOVE}:
            raise RuntimeError("input deck names a missing mesh")
        return 2.0 * event.lf ** 1.2
    """)


@pytest.fixture()
def case(tmp_path):
    pd.DataFrame({"id": [f"e{i}" for i in range(N)], "lf": LF}).to_csv(tmp_path / "lf.csv",
                                                                        index=False)
    (tmp_path / "oracle.py").write_text(ORACLE)
    argv = [str(tmp_path / "lf.csv"), "--oracle", f"python:{tmp_path / 'oracle.py'}:load",
            "--n-waves", str(N), "--p-exp", "1e-2", "--eps1", "1e-3", "--seed", "5",
            "--max-hf", "8", "--quiet", "--preset", "paper"]  # paper: no bootstrap, fast
    return tmp_path, argv


def _calls(folder):
    log = folder / "calls.log"
    n = len(log.read_text().split()) if log.exists() else 0
    log.unlink(missing_ok=True)
    return n


def _run(capsys, *argv):
    code = main(["run", *map(str, argv)])
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_failure_limit_then_retry_failed_matches_an_uninterrupted_run(case, capsys):
    folder, argv = case
    bad, good_out = folder / "bad", folder / "good"
    (folder / "broken.flag").touch()
    code, _, err = _run(capsys, *argv, "--max-failures", "1", "--out", bad)
    assert code == 1 and _calls(folder) == 2
    assert (
        "fix the oracle and rerun with --retry-failed (same --out), or raise --max-failures" in err
    )
    # reproduction: rerunning the same command stops at once, and now says how to go on
    code, _, err = _run(capsys, *argv, "--out", bad)
    assert code == 1 and _calls(folder) == 0 and "--retry-failed" in err
    assert "max_failures changed" not in err      # the stored limit (1) is not undone
    assert "resuming " in err and "2 results reused (2 failed)" in err
    (folder / "broken.flag").unlink()
    code, _, err = _run(capsys, *argv, "--out", bad, "--retry-failed")
    assert code == 0 and "retrying 2 failed event(s)" in err
    code, _, _ = _run(capsys, *argv, "--out", good_out)
    assert code == 0
    got = json.loads((bad / "summary.json").read_text())
    ref = json.loads((good_out / "summary.json").read_text())
    assert got["n_failed"] == 0 and got["n_hf"] == ref["n_hf"]
    assert got["mpm"] == pytest.approx(ref["mpm"], rel=1e-6)


def test_cli_keeps_a_limit_set_with_study_set_unless_given(case, capsys):
    """Reproduction: 'pas study set --max-failures 30' was undone by the next 'pas run'."""
    folder, argv = case
    out = folder / "run"
    argv = [a if a != "8" else "4" for a in argv]   # --max-hf 4: the initial samples only
    assert _run(capsys, *argv, "--out", out)[0] == 0
    db = str(out / "study.sqlite")
    assert main(["study", "set", db, "--max-failures", "30", "--eps2", "0.2"]) == 0
    code, _, err = _run(capsys, *argv, "--out", out)
    assert code == 0 and "changed from" not in err and "resuming" in err
    assert "4 results reused" in err
    with StudyStore(db, create=False) as store:
        s = store.settings()
    assert (s["max_failures"], s["eps2"]) == (30, 0.2)
    code, _, err = _run(capsys, *argv, "--out", out, "--max-failures", "3")
    assert code == 0 and "max_failures changed from 30 to 3" in err
    for bad in ("-1", "x"):
        with pytest.raises(SystemExit):
            main(["run", *argv, "--out", str(out), "--max-failures", bad])
        assert "--max-failures" in capsys.readouterr().err
    code, _, err = _run(capsys, *argv, "--no-store", "--retry-failed")
    assert code == 2 and "--retry-failed needs the study store" in err


def test_cli_study_retry(case, capsys):
    folder, argv = case
    out = folder / "run"
    (folder / "broken.flag").touch()
    argv = [a if a != "8" else "4" for a in argv]
    # finished, 2 failed events left out of the fit
    assert _run(capsys, *argv, "--out", out, "--max-failures", "5")[0] == 3
    db = str(out / "study.sqlite")
    assert main(["study", "retry", db, "nope"]) == 2
    assert "event nope was never asked for" in capsys.readouterr().err
    assert main(["study", "retry", db]) == 0
    said = capsys.readouterr().out
    assert "2 failed event(s) will run again" in said and "pas study run" in said
    with sqlite3.connect(db) as c:
        assert c.execute("SELECT COUNT(*) FROM events WHERE state = 'failed'").fetchone()[0] == 0
        assert c.execute("SELECT COUNT(*) FROM dropped WHERE reason = 'retried failure'"
                         ).fetchone()[0] == 2
    assert main(["study", "retry", db]) == 0
    assert "no failed event to retry" in capsys.readouterr().out
    assert main(["study", "status", db, "--events"]) == 0
    text = capsys.readouterr().out
    assert ("dropped by a retry: event e295 (retried failure): error 'RuntimeError: input deck "
            "names a missing mesh' not reused") in text


SCRIPT = f"""\
import pathlib, sys
lf, result = float(sys.argv[1]), sys.argv[2]
if pathlib.Path(__file__).with_name("broken.flag").exists() and lf > {BROKEN_ABOVE}:
    sys.exit("mesh file not found")
pathlib.Path(result).write_text(repr(2.0 * lf ** 1.2))
"""


def test_cli_study_run_stops_at_the_limit_and_continues_after_retry(tmp_path, capsys):
    import sys

    pd.DataFrame({"lf": LF}).to_csv(tmp_path / "lf.csv", index=False)
    (tmp_path / "cfd.py").write_text(SCRIPT)
    (tmp_path / "broken.flag").touch()
    (tmp_path / "study.toml").write_text(textwrap.dedent(f"""\
        n_waves = {N}
        p_exp = 0.01
        eps1 = 0.001
        seed = 5
        preset = "paper"
        max_hf = 6
        max_failures = 1
        [lf]
        file = "lf.csv"
        column = "lf"
        [oracle]
        command = ["{sys.executable}", "{tmp_path / 'cfd.py'}", "{{lf}}", "{{result}}"]
        """))
    db = str(tmp_path / "s.db")
    assert main(["study", "create", db, "--config", str(tmp_path / "study.toml")]) == 0
    capsys.readouterr()
    assert main(["study", "run", db, "--quiet"]) == 1
    err = capsys.readouterr().err
    assert "max_failures=1" in err and f"'pas study retry {db}'" in err
    assert "--max-failures N" in err and "Traceback" not in err
    (tmp_path / "broken.flag").unlink()
    assert main(["study", "retry", db]) == 0
    assert main(["study", "run", db, "--quiet"]) == 0
    assert "0 failed" in capsys.readouterr().out


def test_retry_keeps_the_named_loads_of_reused_results(tmp_path):
    """Several loads per event and a retry: a reused result keeps its loads, a retried one gets
    new."""
    from pas.study.loads import stored_loads

    def loads(ev):
        return {"deck": good(ev), "panel": 0.5 * ev.lf ** 1.5}

    class FlakyLoads(Flaky):
        def __call__(self, ev):
            return {"deck": super().__call__(ev), "panel": 0.5 * ev.lf ** 1.5}

    ref_db, db = str(tmp_path / "ref.db"), str(tmp_path / "s.db")
    ref = pas.make_study(NO_BAND, LF, store=ref_db, target="deck", max_hf=MAX_HF,
                         **KW).optimize(loads)
    oracle = FlakyLoads()
    pas.make_study(NO_BAND, LF, store=db, target="deck", budget=LENIENT, **KW).optimize(oracle)
    oracle.fixed = True
    study = pas.make_study(NO_BAND, LF, store=db, target="deck", budget=LENIENT, **KW)
    study.retry_failed()
    res = study.optimize(oracle)
    assert res.n_failed == 0 and res.mpm == pytest.approx(ref.mpm, rel=1e-9)
    with StudyStore(db, create=False) as store:
        final = set(store.events()["idx"])
        kept = stored_loads(store)
    for idx in final:   # every event of the final log has both loads, as the oracle gave them
        lf = LF[idx]
        assert kept[idx]["deck"][0] == pytest.approx(2.0 * lf ** 1.2, rel=1e-12)
        assert kept[idx]["panel"][0] == pytest.approx(0.5 * lf ** 1.5, rel=1e-12)
    panel = pas.refit(db, target="panel")
    panel_ref = pas.refit(ref_db, target="panel")
    assert panel.mpm == pytest.approx(panel_ref.mpm, rel=1e-9)


def test_command_oracle_campaign_fails_then_retried_matches_an_uninterrupted_run(
        tmp_path, monkeypatch, capsys):
    """A new user's campaign: a CFD command with a wrong input fails to the limit, is fixed and
    rerun with --retry-failed on the same --out; it ends as a run with the fixed command."""
    import sys

    monkeypatch.chdir(tmp_path)
    pd.DataFrame({"id": [f"e{i}" for i in range(N)], "lf": LF}).to_csv("lf.csv", index=False)
    (tmp_path / "cfd.py").write_text(SCRIPT)      # a relative script path, as a user writes it
    argv = ["lf.csv", "--oracle", f"command:{sys.executable} cfd.py {{lf}} {{result}}",
            "--n-waves", str(N), "--p-exp", "1e-2", "--eps1", "1e-3", "--seed", "5",
            "--max-hf", "8", "--quiet", "--preset", "paper", "--max-failures", "1"]
    (tmp_path / "broken.flag").touch()
    assert _run(capsys, *argv, "--out", "campaign")[0] == 1      # the failure limit
    (tmp_path / "broken.flag").unlink()
    code, _, err = _run(capsys, *argv, "--out", "campaign", "--retry-failed")
    assert code == 0 and "retrying 2 failed event(s)" in err
    assert _run(capsys, *argv, "--out", "fresh")[0] == 0
    got = json.loads((tmp_path / "campaign" / "summary.json").read_text())
    ref = json.loads((tmp_path / "fresh" / "summary.json").read_text())
    assert got["n_failed"] == 0 and got["n_hf"] == ref["n_hf"]
    assert got["mpm"] == pytest.approx(ref["mpm"], rel=1e-6)
