"""The user guide's shell blocks for the table oracle and for ask/tell run verbatim.

Each ``pas ...`` line of the block (continuations joined, comments dropped)
is run in order through the CLI's ``main(argv)`` in a folder holding the
files the page names: the LF peaks and basin results of
``tests/docs/test_docs_pages.py`` and, for ask/tell, a study file and a results
table written here the way a user would.  Each command must exit 0 (the
table-oracle run may exit 3 only if the page's data leave events out, which
they do not).
"""

from __future__ import annotations

import shlex

import pandas as pd
import pytest
from _snippets import code_blocks
from test_docs_pages import write_inputs

from pas.cli import main

PAGE_HF, PAGE_CAMPAIGN = "docs/guide/hf-tool.md", "docs/guide/campaigns.md"


def commands(block: str) -> list[list[str]]:
    """The ``pas`` command lines of a shell block as argument lists (without ``pas``)."""
    joined = block.replace("\\\n", " ")
    out = []
    for line in joined.splitlines():
        argv = shlex.split(line, comments=True)
        if argv:
            assert argv[0] == "pas", line
            out.append(argv[1:])
    return out


def run_all(cmds, capsys):
    for argv in cmds:
        code = main(argv)
        captured = capsys.readouterr()
        assert code == 0, f"pas {' '.join(argv)} -> {code}: {captured.err}"


@pytest.mark.slow
def test_table_oracle_shell_block_runs(tmp_path, monkeypatch, capsys):
    (block,) = code_blocks(PAGE_HF, "the table oracle", "bash")
    monkeypatch.chdir(tmp_path)
    write_inputs(tmp_path)
    cmds = commands(block)
    assert [c[0] for c in cmds] == ["run", "plot"]
    run_all(cmds, capsys)
    assert (tmp_path / "run1" / "summary.json").exists()
    # pas plot --kind all: the MPM convergence, distribution, scatter and AIC figures
    assert len(list((tmp_path / "run1" / "figures").glob("*.png"))) == 4


STUDY_TOML = """\
n_waves = 16364
p_exp = 2.55e-3
eps1 = 20.0
threshold = 12.0
seed = 1

[lf]
file = "lf_peaks.csv"
column = "rwe"
id_column = "event"
"""


def test_ask_tell_shell_block_runs(tmp_path, monkeypatch, capsys):
    (block,) = code_blocks(PAGE_CAMPAIGN, "ask/tell from the shell", "bash")
    monkeypatch.chdir(tmp_path)
    write_inputs(tmp_path)
    (tmp_path / "study.toml").write_text(STUDY_TOML)
    cmds = commands(block)
    # the page tells s07-w123 by hand, so that event must be one the study asks first:
    # make it the largest LF peak, which MD's first events include
    lf = pd.read_csv(tmp_path / "lf_peaks.csv")
    lf.loc[lf["event"] == "s07-w123", "rwe"] = lf["rwe"].max() + 1.0
    lf.to_csv(tmp_path / "lf_peaks.csv", index=False)
    basin = pd.read_csv(tmp_path / "basin.csv").set_index("event")["force_kN"]
    for argv in cmds:
        if argv[:2] == ["study", "tell"] and "--csv" in argv:
            # the basin's results of the events asked so far, but the one told by hand
            asked = pd.read_csv(tmp_path / "next.csv")["id"].astype(str)
            asked = [e for e in asked if e != "s07-w123"]
            pd.DataFrame({"id": asked, "hf": basin.loc[asked].to_numpy()}).to_csv(
                tmp_path / "measured.csv", index=False)
        code = main(argv)
        captured = capsys.readouterr()
        assert code == 0, f"pas {' '.join(argv)} -> {code}: {captured.err}"
        if argv[:2] == ["study", "status"] and "--events" in argv:
            assert "s07-w123" in captured.out and "821" in captured.out
