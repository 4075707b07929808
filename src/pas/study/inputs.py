"""Reading input files: LF peaks (the one loader behind ``pas run LF_FILE`` and ``pas study``'s
``[lf]``) and the CSV/Parquet tables of HF results."""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["read_lf_peaks", "read_table", "split_lf_table", "lf_table", "FIELD_NAMES"]

FIELD_NAMES = {"file": "file", "column": "column", "id_column": "id_column",
               "meta_columns": "meta_columns"}
"""Default ``names`` of :func:`read_lf_peaks`: the roles called by its parameter names."""

_TABLE_SUFFIXES = (".csv", ".txt", ".parquet")


def read_table(path, *, columns=()):
    """Read a CSV or Parquet file into a DataFrame, checking that ``columns`` exist."""
    import pandas as pd

    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path} does not exist")
    suffix = path.suffix.lower()
    if suffix == ".parquet":
        df = pd.read_parquet(path)
    elif suffix in (".csv", ".txt"):
        df = pd.read_csv(path)
    else:
        raise ValueError(f"{path}: unsupported table format {suffix!r} (use .csv or .parquet)")
    for c in columns:
        if c not in df.columns:
            raise ValueError(f"column {c!r} is missing from {path.name} "
                             f"(columns: {', '.join(map(str, df.columns))})")
    return df


def read_lf_peaks(path, *, column=None, id_column=None, meta_columns=(), guess_columns=False,
                  names=None):
    """Read LF peaks (and optional ids and metadata) from a CSV, Parquet or ``.npy`` file.

    Parameters
    ----------
    path : str or os.PathLike
        ``.csv``/``.txt`` (header row required), ``.parquet`` or ``.npy`` (a
        1-D array, whose column is called ``lf``, or a structured array with
        named columns).
    column : str, optional
        Column of the LF peaks.  Required for a table unless
        ``guess_columns``; ``lf`` for a plain ``.npy`` array.
    id_column : str, optional
        Column of event ids; default the row index (with ``guess_columns``:
        ``id`` if present).
    meta_columns : sequence of str
        Columns handed to the oracle as ``event.meta``.
    guess_columns : bool, default False
        Without ``column``, take ``lf`` if present, else the only column; and
        without ``id_column``, ``id`` if present.
    names : dict, optional
        The user-facing name of each role (keys as in :data:`FIELD_NAMES`:
        ``file``, ``column``, ``id_column``, ``meta_columns``) used in the
        error messages, e.g. the command-line option or the TOML key.

    Returns
    -------
    lf : ndarray
    ids : list or None
    meta : list of dict or None

    Raises
    ------
    FileNotFoundError
        The file does not exist.
    ValueError
        One line naming the field to fix.
    """
    import pandas as pd

    names = {**FIELD_NAMES, **(names or {})}
    meta_columns = list(meta_columns)
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{names['file']} {path} does not exist")
    suffix = path.suffix.lower()
    if suffix == ".npy":
        try:
            arr = np.load(path, allow_pickle=False)
        except ValueError as exc:
            raise ValueError(
                f"{names['file']} {path.name}: not a plain .npy array ({exc})"
            ) from None
        if arr.dtype.names is None:
            if arr.ndim != 1:
                raise ValueError(f"{names['file']} {path.name}: expected a 1-D array, "
                                 f"got shape {arr.shape}")
            fields = [names[k] for k, v in (("id_column", id_column),
                                            ("meta_columns", meta_columns)) if v]
            if fields:
                raise ValueError(f"{'/'.join(fields)} need{'s' if len(fields) == 1 else ''} a "
                                 f"structured array; {path.name} is a plain array")
            df = pd.DataFrame({"lf": arr})
            column = column or "lf"
        else:
            df = pd.DataFrame({n: arr[n] for n in arr.dtype.names})
    elif suffix in _TABLE_SUFFIXES:
        try:
            df = read_table(path)
        except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
            what = "Parquet" if suffix == ".parquet" else "CSV"
            raise ValueError(
                f"{names['file']} {path.name}: cannot read it as {what} ({exc})"
            ) from None
    else:
        raise ValueError(f"{names['file']} {path.name}: unsupported format {suffix!r} "
                         "(use .csv, .parquet or .npy)")
    cols = [str(c) for c in df.columns]
    df.columns = cols
    if column is None:
        if not guess_columns:
            raise ValueError(f"{names['column']} is missing (the column of {path.name} "
                             "with the LF peaks)")
        if "lf" in cols:
            column = "lf"
        elif len(cols) == 1:
            column = cols[0]
        else:
            raise ValueError(f"{names['column']}: {path.name} has columns {', '.join(cols)}; "
                             "name the one holding the LF peaks")
    if guess_columns and id_column is None and "id" in cols and column != "id":
        id_column = "id"
    wanted = [("column", column)] + ([("id_column", id_column)] if id_column is not None else []) \
        + [("meta_columns", c) for c in meta_columns]
    for role, c in wanted:
        if c not in cols:
            raise ValueError(f"{names[role]}: column {c!r} is missing from {path.name} "
                             f"(columns: {', '.join(cols)})")
    lf = pd.to_numeric(df[column], errors="coerce").to_numpy(dtype=float)
    bad = np.flatnonzero(~np.isfinite(lf))
    if bad.size:
        raise ValueError(f"{names['column']}: column {column!r} of {path.name} has a missing or "
                         f"non-numeric value in data row {bad[0] + 1}")
    ids = None
    if id_column is not None:
        col = df[id_column]
        if col.isna().any():
            raise ValueError(f"{names['id_column']}: column {id_column!r} of {path.name} is empty "
                             f"in data row {int(np.flatnonzero(col.isna().to_numpy())[0]) + 1}")
        keys = col.astype(str)
        if keys.duplicated().any():
            raise ValueError(f"{names['id_column']}: column {id_column!r} of {path.name} repeats "
                             f"the id {keys[keys.duplicated()].iloc[0]!r}")
        ids = [x.item() if hasattr(x, "item") else x for x in col.tolist()]
    meta = df[meta_columns].to_dict("records") if meta_columns else None
    return lf, ids, meta


def split_lf_table(lf_peaks):
    """``(lf, ids, meta)`` of the ``lf_peaks`` given to :func:`pas.run_pas`.

    An array gives the LF peaks alone (ids are the positions).  A
    :class:`pandas.DataFrame` holds one row per wave event: the column ``lf``
    (or its only column) the LF peaks, the column ``id`` — or else its index,
    unless that is the default ``0 … n-1`` — the event ids, and every other
    column the event's ``meta`` handed to the oracle.  A
    :class:`pandas.Series` gives the peaks, and its index (unless the
    default) the ids.

    Examples
    --------
    >>> import pandas as pd
    >>> split_lf_table(pd.DataFrame({"lf": [1.0, 2.0], "seed": [7, 8]}, index=["a", "b"]))
    (array([1., 2.]), ['a', 'b'], [{'seed': 7}, {'seed': 8}])
    """
    import pandas as pd

    if isinstance(lf_peaks, pd.Series):
        lf_peaks = lf_peaks.to_frame("lf")
    if not isinstance(lf_peaks, pd.DataFrame):
        return lf_peaks, None, None
    df = lf_peaks.rename(columns=str)
    cols = list(df.columns)
    if "lf" not in cols and len(cols) != 1:
        raise ValueError(f"lf_peaks: a table needs a column 'lf' with the LF peaks; it has "
                         f"{', '.join(cols)}")
    column = "lf" if "lf" in cols else cols[0]
    if "id" in cols and column != "id":
        ids = df["id"].tolist()
    elif isinstance(df.index, pd.RangeIndex) and df.index.start == 0 and df.index.step == 1:
        ids = None
    else:
        ids = df.index.tolist()
    if ids is not None and len(set(map(str, ids))) != len(ids):
        raise ValueError("lf_peaks: the event ids (column 'id' or the index) repeat an id")
    ids = None if ids is None else [x.item() if hasattr(x, "item") else x for x in ids]
    meta_cols = [c for c in cols if c not in (column, "id")]
    meta = df[meta_cols].to_dict("records") if meta_cols else None
    return df[column].to_numpy(dtype=float), ids, meta


def lf_table(lf, ids=None, meta=None, meta_name: str = "meta"):
    """The table :func:`split_lf_table` reads back into ``(lf, ids, meta)`` (of
    :func:`read_lf_peaks`); ``meta_name`` names the meta's source in the error for a meta
    key ``lf`` or ``id``, which the table keeps for the peaks and the ids."""
    import pandas as pd

    clash = sorted({"lf", "id"} & set(meta[0] if meta else ()))
    if clash:
        raise ValueError(f"{meta_name}: a column named {clash[0]!r} cannot be handed to the "
                         "oracle as meta (the name is taken by the LF peaks or the event ids); "
                         "rename it")
    table = pd.DataFrame({"lf": np.asarray(lf, dtype=float)},
                         index=None if ids is None else pd.Index(ids, dtype=object))
    if meta:
        table = table.join(pd.DataFrame(meta, index=table.index))
    return table
