"""Results the investigation scripts save, and tables of relative errors over data sets.

A script that writes a table of ``docs/results/investigations.md`` saves its
results with ``--csv FILE`` and, in a later call, reads them back with
``--write --from-csv A,B,…`` (:func:`add_write_options`,
:func:`saved_results`).  ``final_sample_refits.py`` saves one error per case,
mode, setting and data seed and lays them out with :func:`grid_table`; each
cell is :func:`median_worst` of its errors.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import pandas as pd

from .result_tables import rewrite_page, short_pct


def median_worst(errors, decimals: int | None = None) -> str:
    """``median / worst %`` of the absolute relative errors.

    ``decimals`` of a per cent each, or (None) as :func:`short_pct` shows them;
    "–" without errors.
    """
    magnitude = pd.Series(errors, dtype=float).abs().dropna()
    if magnitude.empty:
        return "–"
    show = short_pct if decimals is None else (lambda f: f"{100 * f:.{decimals}f}")
    return f"{show(magnitude.median())} / {show(magnitude.max())} %"


def grid_table(results: pd.DataFrame, corner: str, rows, columns, cell=median_worst) -> str:
    """A Markdown table whose cells summarise the ``error`` of the matching results.

    Parameters
    ----------
    results : DataFrame
        One row per run, with an ``error`` column and the columns the selectors name.
    corner : str
        The heading of the first column.
    rows, columns : sequence of (str, dict)
        A label and a selector (column name to value); a cell takes the results
        that match its row's and its column's selectors.
    cell : callable
        The summary of a cell's errors (default :func:`median_worst`).

    Returns
    -------
    str
        Markdown, "–" where no result matches.
    """
    lines = ["| " + " | ".join([corner, *(label for label, _ in columns)]) + " |",
             "|---" * (len(columns) + 1) + "|"]
    for label, row in rows:
        cells = []
        for _, column in columns:
            keep = pd.Series(True, index=results.index)
            for key, value in {**row, **column}.items():
                keep &= results[key] == value
            cells.append(cell(results.loc[keep, "error"]))
        lines.append("| " + " | ".join([label, *cells]) + " |")
    return "\n".join(lines)


def add_write_options(parser: argparse.ArgumentParser, page) -> None:
    """Give a script ``--csv FILE``, ``--from-csv A,B,…`` and ``--write [PAGE]``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The script's parser.
    page : str or path-like
        The page ``--write`` writes when given no path.
    """
    parser.add_argument("--csv", type=Path, help="save the results to this file")
    parser.add_argument("--from-csv", metavar="A.csv,B.csv",
                        help="with --write: the --csv files of earlier runs")
    parser.add_argument("--write", nargs="?", const=Path(page), type=Path, metavar="PAGE",
                        help=f"run nothing: write the tables between the markers of PAGE "
                             f"(default {page}) from --from-csv")


def saved_results(parser: argparse.ArgumentParser, args) -> pd.DataFrame:
    """The rows of the ``--from-csv`` files, one table; a usage error without them."""
    if not args.from_csv:
        parser.error("--write needs --from-csv A.csv,B.csv (the --csv files of earlier runs)")
    return pd.concat([pd.read_csv(f) for f in args.from_csv.split(",")], ignore_index=True)


def has_results(table: str) -> bool:
    """Whether a Markdown table has a row with a value other than "–" beside its label."""
    rows = [line.strip().strip("|").split("|") for line in table.split("\n")[2:]]
    return any(cell.strip() not in ("", "–") for row in rows for cell in row[1:])


def write_tables(page, blocks: dict[str, str], tag: str) -> None:
    """:func:`~harness.result_tables.rewrite_page` with the tables that hold results;
    those without any are left in the page as they were, and said so."""
    empty = [name for name, table in blocks.items() if not has_results(table)]
    kept = {name: table for name, table in blocks.items() if name not in empty}
    if kept:
        rewrite_page(page, kept, tag)
    if empty:
        print(f"left as they were in {page} (no results for them in --from-csv): "
              + ", ".join(empty))
