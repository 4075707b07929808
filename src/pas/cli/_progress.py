"""The progress line ``pas run`` and ``pas study run`` print after every HF result."""

from __future__ import annotations

import math
import sys

__all__ = ["Progress"]


class Progress:
    """``callback(study, row)`` printing one line per told result.

    Iteration, HF count, event, LF, the HF value (or the failure), and once a
    model is fitted the MPM with its band, the copula family, ``Ē`` and the
    COV against their limits.

    Parameters
    ----------
    stream : file, optional
        Where to print; default ``sys.stderr`` (read when called).
    """

    def __init__(self, stream=None):
        self.stream = stream

    def __call__(self, study, row) -> None:
        status = row.get("status")
        if status == "failed":
            what = f"FAILED ({row.get('error')})"
        elif status == "false_positive":
            what = "HF 0 (false positive)"
        else:
            what = f"HF {row.get('hf'):.4g}"
        model = "no fit yet"
        if _finite(row.get("mpm")):
            fam = f" {row['family']}" if row.get("family") else ""
            model = (f"MPM {row['mpm']:.4g} [{_num(row.get('mpm_low'), '.4g')}, "
                     f"{_num(row.get('mpm_high'), '.4g')}]{fam}  "
                     f"E_bar {_num(row.get('E_bar'))} (eps1 {study.stopping.eps1:g})  "
                     f"COV {_num(row.get('COV'))} (eps2 {study.stopping.eps2:g})")
            if row.get("stop"):
                model += "  converged"
        print(f"[pas] it {row['row'] + 1:>4}  n_HF {study.n_hf:>4}  event {row['event_id']}  "
              f"LF {row['lf']:.4g}  {what}  {model}", file=self.stream or sys.stderr, flush=True)


def _finite(x) -> bool:
    return x is not None and math.isfinite(x)


def _num(x, fmt=".3g") -> str:
    return format(x, fmt) if _finite(x) else "-"
