"""docs/guide/lf-events.md: the page's code runs verbatim up to the events and the threshold,
its printed lines are what the code prints, and its ``pas events`` line gives the same table.

The page's two screening runs (tens of seconds) run in ``test_docs_pages.py`` with the
other slow pages.
"""

import io
import shlex
from contextlib import redirect_stdout

import numpy as np
import pandas as pd
from _snippets import code_blocks

from pas.cli import main

PAGE = "docs/guide/lf-events.md"


def _run(block, namespace):
    out = io.StringIO()
    with redirect_stdout(out):
        exec(compile(block, PAGE, "exec"), namespace)
    return out.getvalue()


def _page_up_to_the_threshold():
    (record,) = code_blocks(PAGE, "An LF record", "python")
    (events,) = code_blocks(PAGE, "Events, n_waves and p_exp", "python")
    cut = [b for b in code_blocks(PAGE, "A threshold", "python") if "run_pas" not in b]
    namespace = {"__name__": "__docs__"}
    _run(record, namespace)
    printed = _run(events, namespace) + _run(cut[0], namespace)
    return namespace, printed


def test_page_events_count_every_wave_and_match_the_printed_lines(tmp_path, monkeypatch):
    ns, printed = _page_up_to_the_threshold()
    x, ev, cut = ns["rwe"], ns["ev"], ns["cut"]
    ups = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    assert ev.n_waves == ups.size - 1 == cut.n_waves
    # the counted mean period lies near the spectral mean zero-crossing period 2 pi sqrt(m0/m2)
    s, w = ns["spectrum"], ns["omega"]
    tz = 2 * np.pi * np.sqrt(s.sum() / (s * w ** 2).sum())
    assert abs(ev.mean_period / tz - 1) < 0.05
    assert ev.p_exp == ev.mean_period / 10_800.0
    assert (cut.table["lf"] > 3.0).all() and len(cut.table) == (ev.table["lf"] > 3.0).sum()
    shown = "\n".join(code_blocks(PAGE, "Events, n_waves and p_exp", "text")
                      + code_blocks(PAGE, "A threshold", "text")[:1])
    for line in printed.splitlines():
        assert line in shown, line

    (shell,) = code_blocks(PAGE, "From the shell", "bash")
    monkeypatch.chdir(tmp_path)
    np.save("bow_rwe.npy", x)
    argv = shlex.split(shell.replace("\\\n", " "), comments=True)
    assert argv[0] == "pas" and main(argv[1:]) == 0
    written = pd.read_csv("events.csv")
    np.testing.assert_allclose(written["lf"], cut.table["lf"])
    assert written["id"].tolist() == [i.replace("0-", "bow_rwe-", 1) for i in cut.table["id"]]
