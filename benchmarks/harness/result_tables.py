"""The validation tables of the documentation, as text, from the runs that measured them.

``benchmarks/studies/validation_spread.py --write`` reads its ``runs.csv`` and
puts :func:`validation_tables` into ``docs/results/validation.md`` and
:func:`readme_summary` into ``README.md``, each between the page's markers
(:func:`write_between_markers`), so that no table is edited by hand.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path

import pandas as pd

from pas.validation.registry import CASE_IDS, get_case

STRATEGY_LABELS = {"pas": "PAS", "pas-paper": "PAS paper preset", "as": "AS",
                   "rcw": "RCW", "mler": "MLER"}
"""The name of each strategy of ``runs.csv`` in the tables."""

VALIDATION_HEADER = ("| case | strategy | analogue truth (median) | HF samples (median) | "
                     "median M1 | median M2 | M2 range | median \\|M2\\| | worst \\|M2\\| | "
                     "median M3 | converged |")

README_GROUPS = (("analogues 1a–2b (crests, bending moments)", ("1a", "1b", "2a", "2b")),
                 ("green water 3a, 3b", ("3a", "3b")),
                 ("bow-flare slamming 4a, 4b", ("4a", "4b")))
"""The analogue rows of the README's summary: a label and the cases it pools."""


def write_between_markers(text: str, blocks: dict[str, str], tag: str) -> str:
    """Put each block between its markers in a page.

    Parameters
    ----------
    text : str
        The page.
    blocks : dict of str to str
        Block text by marker name.
    tag : str
        The markers' tag: a block ``NAME`` goes between ``<!-- BEGIN tag NAME -->``
        and ``<!-- END tag NAME -->`` (the markers stay).  Markers indented
        (a table inside a list item) get the block indented as they are, with a
        blank line either side.

    Returns
    -------
    str
        The page with every block replaced.

    Raises
    ------
    ValueError
        If the page lacks a block's markers.
    """
    for name, block in blocks.items():
        begin, end = f"<!-- BEGIN {tag} {name} -->", f"<!-- END {tag} {name} -->"
        pattern = re.compile(r"^([ \t]*)" + re.escape(begin) + r"\n.*?" + re.escape(end),
                             re.DOTALL | re.MULTILINE)
        found = pattern.search(text)
        if not found:
            raise ValueError(f"--write: the page has no '{begin}' … '{end}' markers; "
                             "add them where the table goes")
        indent = found.group(1)
        inner = "\n".join(indent + line if line else line for line in block.split("\n"))
        # in a list item Markdown reads a table only after a blank line
        gap = "\n\n" if indent else "\n"
        replacement = f"{indent}{begin}{gap}{inner}{gap}{indent}{end}"
        text = text[:found.start()] + replacement + text[found.end():]
    return text


def rewrite_page(page, blocks: dict[str, str], tag: str) -> None:
    """Put each block between its markers in the page file ``page`` (:func:`write_between_markers`).

    Parameters
    ----------
    page : str or path-like
        The Markdown file, rewritten in place.
    blocks : dict of str to str
        Block text by marker name.
    tag : str
        The markers' tag, the name of the script that writes them.
    """
    page = Path(page)
    page.write_text(write_between_markers(page.read_text(encoding="utf-8"), blocks, tag),
                    encoding="utf-8")
    print(f"wrote {', '.join(blocks)} in {page}")


def _ordered_groups(runs: pd.DataFrame):
    """(case, strategy, rows) in the order of :data:`CASE_IDS` and :data:`STRATEGY_LABELS`."""
    cases = sorted(runs["case"].unique(), key=lambda c: (CASE_IDS + (c,)).index(c))
    order = list(STRATEGY_LABELS)
    for case in cases:
        of_case = runs[runs["case"] == case]
        for strategy in sorted(of_case["strategy"].unique(),
                               key=lambda s: (order + [s]).index(s)):
            yield case, strategy, of_case[of_case["strategy"] == strategy]


def _validation_row(case: str, strategy: str, g: pd.DataFrame) -> str:
    m2, unit = 100 * g["M2"], get_case(case).unit
    return (f"| {case} | {STRATEGY_LABELS.get(strategy, strategy)} | "
            f"{g['truth'].median():.4g} {unit} | {g['n_hf'].median():g} | "
            f"{100 * g['M1'].median():.2f} % | {m2.median():+.1f} % | "
            f"{m2.min():+.1f} … {m2.max():+.1f} % | {m2.abs().median():.1f} % | "
            f"{m2.abs().max():.1f} % | {100 * g['M3'].median():+.1f} % | "
            f"{int(g['converged'].astype(bool).sum())}/{len(g)} |")


def validation_tables(runs: pd.DataFrame) -> dict[str, str]:
    """The two tables of ``docs/results/validation.md``.

    Parameters
    ----------
    runs : DataFrame
        The ``runs.csv`` of ``validation_spread.py``: one row per case, strategy
        and replication with ``truth``, ``n_hf``, ``M1``, ``M2``, ``M3`` and
        ``converged``.

    Returns
    -------
    dict of str to str
        ``"paper-like"`` and ``"hard"``: one row per case and strategy, medians
        over the replications, cases and strategies in their usual order.
    """
    lines: dict[str, list[str]] = {"paper-like": [], "hard": []}
    for case, strategy, g in _ordered_groups(runs):
        lines[get_case(case).variant].append(_validation_row(case, strategy, g))
    rule = "|---" * VALIDATION_HEADER.count(" | ") + "|---|"
    return {name: "\n".join([VALIDATION_HEADER, rule, *rows]) for name, rows in lines.items()}


def short_pct(fraction: float) -> str:
    """A percentage for the README: one decimal below 10 %, none from there."""
    value = 100 * fraction
    return f"{value:.1f}" if abs(value) < 9.95 else f"{value:.0f}"


def _pooled(runs: pd.DataFrame, strategy: str, cases: Sequence[str]) -> str:
    """Median |M2| per case (a range over many cases, a list over two) / worst |M2|."""
    of = runs[(runs["strategy"] == strategy) & runs["case"].isin(cases)]
    if of.empty:
        return "–"
    absm2 = of.groupby("case")["M2"].apply(lambda m: m.abs().median())
    medians = [absm2[c] for c in cases if c in absm2.index]
    worst = of["M2"].abs().max()
    shown = (f"{short_pct(min(medians))}–{short_pct(max(medians))}" if len(medians) > 2
             else ", ".join(short_pct(m) for m in medians))
    return f"{shown} % / {short_pct(worst)} %"


def _hf_cell(pas_runs: pd.DataFrame, cases: Sequence[str], max_hf: int) -> str:
    medians = [pas_runs[pas_runs["case"] == c]["n_hf"].median() for c in cases
               if (pas_runs["case"] == c).any()]
    if not medians:
        return "–"
    if all(m == max_hf for m in medians):
        return f"{max_hf:g} (budget)"
    if len(medians) > 2:
        return f"{min(medians):g}–{max(medians):g}"
    return ", ".join(f"{m:g}" for m in medians)


def readme_summary(runs: pd.DataFrame, known_truth_defaults: pd.DataFrame,
                   known_truth_paper: pd.DataFrame, max_hf: int = 160) -> str:
    """The summary table of ``README.md`` and the sentence on U95 coverage under it.

    Parameters
    ----------
    runs : DataFrame
        The ``runs.csv`` of ``validation_spread.py`` (strategies ``pas``,
        ``pas-paper``, ``as``), with ``covered``.
    known_truth_defaults, known_truth_paper : DataFrame
        The ``runs.csv`` of ``benchmarks/studies/known_truth.py`` with the defaults and
        with ``--preset paper``: ``error`` (relative), ``covered``, ``n_hf``.
    max_hf : int
        The HF budget of the runs: a median at it is shown as "(budget)".

    Returns
    -------
    str
        Markdown: median and worst |MPM error| per group of problems, then the
        U95 coverage of PAS's defaults.
    """
    rows = ["| problems | HF runs (PAS, median) | PAS (defaults) | paper preset | AS |",
            "|---|---|---|---|---|"]
    kt = [known_truth_defaults["error"].abs(), known_truth_paper["error"].abs()]
    rows.append(f"| known truth, {len(known_truth_defaults)} runs | "
                f"{known_truth_defaults['n_hf'].median():g} | "
                + " | ".join(f"{short_pct(a.median())} % / {short_pct(a.max())} %" for a in kt)
                + " | – |")
    pas_runs = runs[runs["strategy"] == "pas"]
    for label, cases in README_GROUPS:
        rows.append(f"| {label} | {_hf_cell(pas_runs, cases, max_hf)} | "
                    + " | ".join(_pooled(runs, s, cases) for s in ("pas", "pas-paper", "as"))
                    + " |")
    covered = pas_runs["covered"].astype(bool)
    coverage = (f"The reported U95 holds the truth in "
                f"{100 * known_truth_defaults['covered'].astype(bool).mean():.0f} % of the "
                f"known-truth runs and {int(covered.sum())} of {len(covered)} analogue data "
                "sets (nominal 95 %).")
    return "\n".join(rows) + "\n\n" + coverage


def _minus(text: str) -> str:
    return text.replace("-", "−")


def _signed_int(value: float) -> str:
    text = f"{value:+.0f}"
    return "0" if text in ("+0", "-0") else _minus(text)


def _magnitude(value: float, sci: str) -> str:
    """A truth: two decimals below 100, none below 1e5, else ``sci`` with a short exponent."""
    if abs(value) >= 1e5:
        mantissa, exponent = format(value, sci).split("e")
        return f"{mantissa}e{int(exponent)}"
    return f"{value:.2f}" if abs(value) < 100 else f"{value:.0f}"


def _with_paper(row, key: str, own_format, paper_format) -> str:
    own = own_format(row[key]) if pd.notna(row[key]) else "–"
    paper = row.get(f"paper_{key}")
    return f"{own} [{paper_format(paper)}]" if isinstance(paper, float) and pd.notna(paper) else own


def _percent(decimals: int):
    return lambda fraction: f"{100 * fraction:.{decimals}f} %"


def _as_stated(fraction: float) -> str:
    return f"{100 * fraction:g} %"


def properties_seed_table(table: pd.DataFrame) -> str:
    """The data properties of one data seed, one row per case
    (``docs/results/analogue-properties.md``).

    Parameters
    ----------
    table : DataFrame
        Rows of :func:`pas.validation.properties.data_properties` (the
        ``properties.csv`` of ``case_properties.py``) for one seed.

    Returns
    -------
    str
        Markdown; the paper's value in brackets where it states one.
    """
    lines = [("| case | τ | λ_U / λ_L | miss all | miss ln-d 50 | impact rate | truth β | "
              "truth MPM | paper truth | Δ | AIC family (gap) |"), "|---" * 10 + "|---|"]
    for _, r in table.iterrows():
        beta = f"{r['weibull_beta']:.2f}" if pd.notna(r["weibull_beta"]) else "–"
        family = (f"{str(r['family']).capitalize()} ({r['aic_gap']:.0f})"
                  if isinstance(r["family"], str) and r["family"] else "–")
        delta = _minus(f"{100 * r['truth_vs_paper']:+.1f}")
        lines.append(
            f"| {r['case']} | {r['tau']:.2f} | {r['lambda_u']:.2f} / {r['lambda_l']:.2f} | "
            f"{100 * r['miss_all']:.0f} % | "
            f"{_with_paper(r, 'miss_lnu50', _percent(0), _percent(0))} | "
            f"{_with_paper(r, 'impact_rate', _percent(1), _as_stated)} | "
            f"{beta} | {_magnitude(r['truth_mpm'], '.4g')} {r['unit']} | "
            f"{_magnitude(r['paper_truth'], '.2e')} | {delta} % | {family} |")
    return "\n".join(lines)



def _spread_formats(decimals: int, unit: str = ""):
    def median(value):
        return f"{value:.{decimals}f}{unit}"
    return median, lambda value: f"{value:.{decimals}f}"


SPREAD_COLUMNS = (("λ_U", "lambda_u", 1, *_spread_formats(2)),
                  ("λ_L", "lambda_l", 1, *_spread_formats(2)),
                  ("miss all", "miss_all", 100, *_spread_formats(0, " %")),
                  ("miss ln-d 50", "miss_lnu50", 100, *_spread_formats(0, " %")),
                  ("impact rate", "impact_rate", 100, *_spread_formats(1, " %")),
                  ("truth vs paper", "truth_vs_paper", 100,
                   lambda value: f"{_signed_int(value)} %", _signed_int))
"""Columns of the spread table: heading, property, scale, format of the median and of the range."""


def properties_spread_table(table: pd.DataFrame) -> str:
    """Median [min, max] over the data seeds of the impact cases' key properties.

    Parameters
    ----------
    table : DataFrame
        Rows of :func:`pas.validation.properties.data_properties` with a
        ``seed`` column; only the impact cases (those with an impact rate) are
        shown, in the order of :data:`CASE_IDS`.

    Returns
    -------
    str
        Markdown, with the count of data seeds where λ_L ≥ λ_U.
    """
    heads = [column[0] for column in SPREAD_COLUMNS]
    lines = ["| case | " + " | ".join(heads[:2] + ["λ_L ≥ λ_U"] + heads[2:]) + " |",
             "|---" * (len(heads) + 2) + "|"]
    impacts = table[table["impact_rate"].notna()]
    for case in (c for c in CASE_IDS if c in set(impacts["case"])):
        rows = impacts[impacts["case"] == case]
        cells = []
        for _, key, scale, median_format, range_format in SPREAD_COLUMNS:
            values = scale * rows[key]
            cells.append(f"{median_format(values.median())} "
                         f"[{range_format(values.min())}, {range_format(values.max())}]")
        ordered = int((rows["lambda_l"] >= rows["lambda_u"]).sum())
        cells.insert(2, f"{ordered}/{len(rows)}")
        lines.append(f"| {case} | " + " | ".join(cells) + " |")
    return "\n".join(lines)



SUMMARY_GROUPS = (("1a / 1b / 2a / 2b", ("1a", "1b", "2a", "2b")), ("3a / 3b", ("3a", "3b")),
                  ("4a / 4b", ("4a", "4b")),
                  ("3a-hard / 3b-hard / 4a-hard / 4b-hard",
                   ("3a-hard", "3b-hard", "4a-hard", "4b-hard")))
"""The rows of the validation page's summary: a label and the cases it lists."""


def validation_summary(summary: pd.DataFrame) -> str:
    """The summary of ``docs/results/validation.md``: per group of cases, PAS's accuracy,
    HF, stops and U95 coverage beside the paper preset's and AS's accuracy.

    Parameters
    ----------
    summary : DataFrame
        The ``summary.csv`` of ``validation_spread.py``: one row per case and
        strategy with ``n`` (replications), ``absM2_median``, ``absM2_max``,
        ``n_hf_median``, ``converged`` and ``covered`` (shares).

    Returns
    -------
    str
        Markdown, one value per case in each cell, then the U95 coverage of
        all PAS runs.
    """
    by = summary.set_index(["case", "strategy"])

    def cells(strategy, cases, show, unit=" %"):
        values = [show(by.loc[(c, strategy)]) if (c, strategy) in by.index else "–"
                  for c in cases]
        return " / ".join(values) + ("" if all(v == "–" for v in values) else unit)

    def counted(key, cases):
        """``k / k / … of n``, or ``k/n / …`` where the replications differ."""
        present = [c for c in cases if (c, "pas") in by.index]
        ns = {int(by.loc[(c, "pas"), "n"]) for c in present}
        shown = (lambda r: f"{round(r[key] * r['n']):.0f}") if len(ns) == 1 else (
            lambda r: f"{round(r[key] * r['n']):.0f}/{r['n']:.0f}")
        return cells("pas", cases, shown, f" of {ns.pop()}" if len(ns) == 1 else "")

    def pct(key):
        return lambda r: f"{100 * r[key]:.1f}"

    lines = [
        (
            "| cases | PAS median \\|M2\\| | PAS worst \\|M2\\| | PAS HF (median) | "
            "PAS converged | PAS U95 holds the truth | paper preset median \\|M2\\| | "
            "AS median \\|M2\\| |"
        ),
        "|---" * 8 + "|",
    ]
    for label, cases in SUMMARY_GROUPS:
        lines.append(f"| {label} | {cells('pas', cases, pct('absM2_median'))} | "
                     f"{cells('pas', cases, pct('absM2_max'))} | "
                     f"{cells('pas', cases, lambda r: f'{r.n_hf_median:g}', '')} | "
                     f"{counted('converged', cases)} | {counted('covered', cases)} | "
                     f"{cells('pas-paper', cases, pct('absM2_median'))} | "
                     f"{cells('as', cases, pct('absM2_median'))} |")
    pas = summary[summary["strategy"] == "pas"]
    held, runs = float((pas["covered"] * pas["n"]).sum()), int(pas["n"].sum())
    return ("\n".join(lines) + f"\n\nThe U95 of PAS holds the data set's truth in {held:.0f} of "
            f"{runs} runs ({100 * held / max(runs, 1):.0f} %; nominal 95 %).")
