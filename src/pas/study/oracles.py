"""HF oracles: calling one safely, the built-in ones, and building one from a text spec.

An oracle is any callable ``oracle(event) -> float`` (0 = no impact, a false
positive), or ``-> {name: float}`` when one HF run gives several loads (panels,
pressure sensors, forces): the study screens on its ``target`` and the store
keeps them all (:func:`check_hf_answer`).  A failure is an exception with a
message; the study records it as a failed event and never takes it as 0
(:func:`call_oracle`).  The built-in
oracles, a results table (:class:`TableOracle`) and an external command per event
(:class:`pas.study.command_oracle.CommandOracle`), hold only plain data, so they
pickle for process pools and Dask workers.
:func:`pas.study.oracle_spec.oracle_from_spec` builds one from ``pas run
--oracle`` text or a ``pas study`` ``[oracle]`` table.
"""

from __future__ import annotations

import math
from pathlib import Path

from .answers import check_hf_answer, check_hf_value, check_target, lacks_target
from .inputs import read_table

__all__ = ["OracleError", "OracleFailureLimit", "check_hf_value", "check_hf_answer",
           "lacks_target", "check_oracle", "call_oracle", "call_oracle_loads", "check_target",
           "TableOracle"]


class OracleError(RuntimeError):
    """An HF evaluation failed; the message is stored with the event."""


class OracleFailureLimit(RuntimeError):
    """Raised when the oracle failed more often than ``max_failures``.

    ``result`` holds the study's result so far (nothing evaluated is lost).
    """

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


def check_oracle(oracle) -> None:
    """Raise a one-line :class:`TypeError` naming ``oracle`` unless it can be called."""
    if not callable(oracle):
        raise TypeError(f"oracle must be a callable oracle(event) -> float (a function, "
                        f"pas.TableOracle or pas.CommandOracle), got {type(oracle).__name__} "
                        f"{oracle!r:.60}")


def call_oracle(oracle, event):
    """Call ``oracle(event)`` and validate the answer: ``(value, error)``."""
    return call_oracle_loads(oracle, event)[:2]


def call_oracle_loads(oracle, event, target=None):
    """Call ``oracle(event)``, its answer checked: ``(value, error, loads)``.

    :func:`~pas.study.answers.check_hf_answer` with ``target``.
    """
    try:
        raw = oracle(event)
    except Exception as exc:  # the oracle is user code: any failure is recorded
        return None, f"{type(exc).__name__}: {exc}", None
    return check_hf_answer(raw, target)


class TableOracle:
    """HF results looked up by event id: basin tests or a finished HF Monte-Carlo.

    Parameters
    ----------
    table : str, os.PathLike or pandas.DataFrame
        CSV or Parquet file, or a DataFrame.
    id_column : str, default "id"
        Column holding the event ids (matched to ``str(event.id)``).
    value_column : str or sequence of str, default "hf"
        Column holding the HF peak (0 = no impact).  Several columns (one per
        load: panels, sensors, forces) make the oracle answer ``{column:
        value}`` (a study then screens on its ``target``; ``pas run --oracle
        table:FILE:ID:COL1,COL2``).
    sea_state_column : str, default "sea_state"
        When the table has this column, rows are keyed by sea state and event
        id, and an event is looked up by ``(event.sea_state, event.id)`` (a
        long-term analysis, :func:`pas.run_long_term`, where ids may repeat
        across sea states); an event of no sea state by its id alone.

    Notes
    -----
    An event missing from the table, or with an empty value, is a failure,
    never 0 (with several columns: an empty one is a failure when it is the
    study's target, else that load is missing, :func:`check_hf_answer`).

    Examples
    --------
    >>> import pandas as pd
    >>> from pas.strategies.screening import Event
    >>> oracle = TableOracle(pd.DataFrame({"id": ["a", "b"], "hf": [1.5, 0.0]}))
    >>> oracle(Event(index=0, id="a", lf=1.0, d=0.1))
    1.5
    """

    def __init__(self, table, *, id_column: str = "id", value_column: str = "hf",
                 sea_state_column: str = "sea_state"):
        import pandas as pd

        if isinstance(table, pd.DataFrame):
            name, df = "the table", table
        else:
            name, df = Path(table).name, read_table(table)
        named = not isinstance(value_column, str)
        columns = list(value_column) if named else [value_column]
        if not columns or len(set(columns)) < len(columns):
            raise ValueError(f"value_column: give one column or several different ones, got "
                             f"{value_column!r}")
        for field, c in (("id_column", id_column), *(("value_column", c) for c in columns)):
            if c not in df.columns:
                raise ValueError(f"{field}: column {c!r} is missing from {name} "
                                 f"(columns: {', '.join(map(str, df.columns))})")
        keys = df[id_column].astype(str)
        self.by_sea_state = sea_state_column in df.columns and sea_state_column != id_column
        if self.by_sea_state:
            keys = df[sea_state_column].astype(str) + "\x1f" + keys
        dup = keys[keys.duplicated()]
        if len(dup):
            where = " (within its sea state)" if self.by_sea_state else ""
            raise ValueError(f"{id_column}: event id {dup.iloc[0].split(chr(31))[-1]!r} appears "
                             f"more than once{where} in {name}")
        values = [pd.to_numeric(df[c], errors="coerce").to_numpy(dtype=float).tolist()
                  for c in columns]
        self.name = name
        self.columns = columns if named else None
        self.values = dict(zip(keys, zip(*values)))
        if self.by_sea_state:  # a single-sea-state study looks up its ids alone, if unique
            plain = df[id_column].astype(str)
            once = set(plain[~plain.duplicated(keep=False)])
            self.values.update({k.split("\x1f", 1)[1]: v for k, v in self.values.items()
                                if k.split("\x1f", 1)[1] in once})

    def __call__(self, event):
        key = str(event.id)
        lookup = key
        sea_state = getattr(event, "sea_state", None)
        if self.by_sea_state and sea_state is not None:
            lookup = f"{sea_state}\x1f{key}"
            key = f"{key} of sea state {sea_state}"
        if lookup not in self.values:
            raise OracleError(f"event {key} is not in {self.name}")
        row = self.values[lookup]
        if self.columns is not None:
            return dict(zip(self.columns, row))
        if not math.isfinite(row[0]):
            raise OracleError(f"{self.name} has no valid value for event {key}")
        return row[0]
