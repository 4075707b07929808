"""The TOML file of ``pas study create``: reading and checking it, its oracle and LF peaks.

The keys are described in :mod:`pas.cli.study` and ``docs/guide/study-file.md``;
every error is one line naming the key to fix (``lf.column``,
``oracle.timeout`` ...).
"""

from __future__ import annotations

import os
import tomllib
from pathlib import Path

__all__ = ["load_config", "load_peaks", "study_objects", "check_oracle_command"]

_TOP = {"n_waves": int, "n_waves_convention": str, "p_exp": float, "eps1": float,
        "precision": (float, str), "fit_check": float, "eps2": float,
        "threshold": float, "strategy": str, "preset": str, "seed": int, "max_hf": int,
        "max_failures": int, "batch_size": int, "target": str,
        "lf": dict, "settings": dict, "oracle": dict}
_LF = {"file": str, "column": str, "id_column": str, "meta_columns": list}
_REQUIRED = ("n_waves", "p_exp", "lf")
_ORACLE = {"command": list, "root": str, "timeout": float, "result_name": str, "table": str,
           "id_column": str, "value_column": (str, list), "on_interrupt": str}


def _typed(value, kind, field, where):
    if isinstance(kind, tuple):  # one of several kinds: the message names the first
        ok = [k for k in kind if _typed_ok(value, k)]
        return _typed(value, (ok or kind)[0], field, where)
    if not _typed_ok(value, kind):
        what = {int: "an integer", float: "a number", str: "a string", dict: "a table",
                list: "a list of strings"}[kind]
        raise ValueError(f"{where}: {field} must be {what}, got {value!r}")
    return float(value) if kind is float else value


def _typed_ok(value, kind) -> bool:
    return {int: lambda v: isinstance(v, int) and not isinstance(v, bool),
          float: lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
          str: lambda v: isinstance(v, str), dict: lambda v: isinstance(v, dict),
          list: lambda v: isinstance(v, list) and all(isinstance(x, str) for x in v)}[kind](value)


def load_config(path) -> dict:
    """Read and check a study TOML file; returns the checked keys plus ``lf`` data."""
    from ..study.factory import STRATEGIES
    from ..study.settings import lacks_a_limit

    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"config file {path} does not exist")
    try:
        raw = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path.name}: {exc}") from None
    where = path.name
    for key in raw:
        if key not in _TOP:
            raise ValueError(f"{where}: unknown key {key!r} (known: {', '.join(_TOP)})")
    for key in _REQUIRED:
        if key not in raw:
            raise ValueError(f"{where}: {key} is missing")
    cfg = {k: _typed(v, _TOP[k], k, where) for k, v in raw.items()}
    if (missing := lacks_a_limit(cfg)) is not None:
        raise ValueError(f"{where}: {missing}")
    if isinstance(cfg.get("precision"), str):
        from argparse import ArgumentTypeError

        from ._stopping_options import precision_option

        try:
            cfg["precision"] = precision_option(cfg["precision"])
        except ArgumentTypeError as exc:
            raise ValueError(f"{where}: precision: {exc}") from None
    lf = cfg["lf"]
    for key in lf:
        if key not in _LF:
            raise ValueError(f"{where}: unknown key lf.{key} (known: {', '.join(_LF)})")
    if "file" not in lf:
        raise ValueError(f"{where}: lf.file is missing")
    cfg["lf"] = {k: _typed(v, _LF[k], f"lf.{k}", where) for k, v in lf.items()}
    strategy = cfg.setdefault("strategy", "pas")
    if strategy not in STRATEGIES:
        raise ValueError(f"{where}: strategy must be {' or '.join(map(repr, STRATEGIES))}, "
                         f"got {strategy!r}")
    _check_settings(cfg, where)
    cfg["lf"]["file"] = str((path.parent / cfg["lf"]["file"]))
    if "oracle" in cfg:
        cfg["oracle"] = _oracle_config(cfg["oracle"], path.parent, where)
    if cfg.get("batch_size", 1) < 1:
        raise ValueError(f"{where}: batch_size must be at least 1, got {cfg['batch_size']}")
    if cfg.get("max_failures", 0) < 0:
        raise ValueError(
            f"{where}: max_failures must be an integer >= 0, got {cfg['max_failures']}"
        )
    return cfg


def _check_settings(cfg: dict, where: str) -> None:
    """The settings of the file by the rules of the Python API and ``pas study set``.

    Top-level keys and the study settings of ``[settings]`` go through
    :func:`pas._support.checks.check_setting`, the strategy settings through the
    strategy's objects (:func:`pas.study.flat.from_flat`).
    """
    from .._support.checks import SETTING_CHECKS, check_setting
    from ..study.factory import STUDY_SETTINGS
    from ..study.flat import from_flat

    for key in sorted(SETTING_CHECKS.keys() & cfg.keys()):
        _in_file(lambda: check_setting(key, cfg[key]), where, "", cfg)
    settings = cfg.get("settings", {})
    misplaced = sorted(settings.keys() & _TOP.keys())
    if misplaced:
        raise ValueError(f"{where}: settings.{misplaced[0]}: give {misplaced[0]} at the top of "
                         "the file, not in [settings]")
    for key in sorted(settings.keys() & set(STUDY_SETTINGS)):
        _in_file(lambda: check_setting(key, settings[key]), where, "settings", settings)
    own = {k: v for k, v in settings.items() if k not in STUDY_SETTINGS}

    def strategy_settings():
        try:
            from_flat(own, strategy=cfg["strategy"], preset=cfg.get("preset"))
        except ValueError as exc:
            if not str(exc).startswith("unknown setting"):
                raise
            study = ", ".join(k for k in STUDY_SETTINGS if k not in _TOP)
            raise ValueError(f"{exc}; and the study's: {study}") from None

    _in_file(strategy_settings, where, "settings", settings)


_FLAT_TOP = ("eps1", "precision", "fit_check", "eps2", "max_hf", "max_failures", "target")
"""Top-level keys of the file that are flat study settings (:func:`pas.study.flat.from_flat`)."""


def study_objects(cfg: dict) -> dict:
    """The strategy, ``stopping``, ``budget`` and other study settings of a checked file."""
    from ..study.flat import from_flat

    flat = {**{k: cfg[k] for k in _FLAT_TOP if k in cfg}, **cfg.get("settings", {})}
    return from_flat(flat, strategy=cfg["strategy"], preset=cfg.get("preset"))


def _in_file(check, where: str, table: str, keys) -> None:
    """Run ``check``; its ``ValueError`` is re-raised naming the file and the key's table.

    A message that starts with a key of ``keys`` (``k1 must be ...``) gets
    that key's full name (``settings.k1 must be ...``).
    """
    try:
        check()
    except ValueError as exc:
        msg = str(exc)
        first = msg.split(" ", 1)[0]
        if table and first in keys:
            raise ValueError(f"{where}: {table}.{msg}") from None
        raise ValueError(f"{where}: {table + ': ' if table else ''}{msg}") from None


def _oracle_config(o: dict, base: Path, where: str) -> dict:
    from ..study.oracle_spec import oracle_from_spec

    for key in o:
        if key not in _ORACLE:
            raise ValueError(f"{where}: unknown key oracle.{key} (known: {', '.join(_ORACLE)})")
    o = {k: _typed(v, _ORACLE[k], f"oracle.{k}", where) for k, v in o.items()}
    if ("command" in o) == ("table" in o):
        raise ValueError(f"{where}: oracle needs exactly one of oracle.command and oracle.table")
    if "command" in o:
        if not o["command"]:
            raise ValueError(f"{where}: oracle.command must not be empty")
        o["root"] = str((base / o.get("root", "runs")).resolve())
        o["cwd"] = str(base.resolve())  # the command's relative paths: next to the TOML file
        if o.get("timeout", 1) <= 0:
            raise ValueError(f"{where}: oracle.timeout must be > 0, got {o['timeout']}")
    else:
        o["table"] = str((base / o["table"]).resolve())
    try:
        oracle_from_spec(o)
    except (ValueError, FileNotFoundError) as exc:
        raise ValueError(f"{where}: oracle: {exc}") from None
    return o


_LF_NAMES = {"file": "lf.file", "column": "lf.column", "id_column": "lf.id_column",
             "meta_columns": "lf.meta_columns"}


def load_peaks(lf_cfg: dict):
    """LF peaks, ids and meta from the file named in the ``[lf]`` table
    (:func:`pas.study.inputs.read_lf_peaks`)."""
    from ..study.inputs import read_lf_peaks

    return read_lf_peaks(lf_cfg["file"], column=lf_cfg.get("column"),
                         id_column=lf_cfg.get("id_column"),
                         meta_columns=lf_cfg.get("meta_columns", ()), names=_LF_NAMES)


def check_oracle_command(spec, event, config) -> None:
    """Fill the ``[oracle]`` command's placeholders for ``event`` (the first of the study):
    a typo (``{sede}``) is an error of ``pas study create``, not a failure of every event
    in ``pas study run``."""
    from ..study.oracle_spec import oracle_from_spec
    from ..study.oracles import OracleError

    if not (isinstance(spec, dict) and "command" in spec):
        return  # a table may not exist yet, a python oracle is not imported before its run
    try:
        oracle = oracle_from_spec({**spec, "cwd": os.getcwd()})
    except ValueError:
        return  # 'pas study run' says what is wrong with it, where it runs
    try:
        oracle.command(event, oracle.root)  # a spec with a command makes a CommandOracle
    except OracleError as exc:
        raise ValueError(f"[oracle] command of {config}: {exc}") from None
