"""The paper's eight validation cases as seeded, physics-based synthetic analogues.

Twelve ids: ``1a`` … ``4b`` (the impact cases 3–4 paper-like), and the first
impact analogues kept as ``3a-hard`` … ``4b-hard`` (:data:`CASE_IDS`).

The paper's HF data (model-basin tests, proprietary non-linear simulations)
are not public, so :func:`generate_case` builds an *analogue* of each sub-case
from the package's own wave and ship models, with the paper's conditions,
``n_w``, ``P_exp``, thresholds and ε1 (:data:`CASES`).  :func:`reproduce`
runs PAS (and AS) on them as a user would.  See ``cases/README.md``.
"""

from .data import CaseData
from .generate import cache_path, generate_case
from .registry import CASE_IDS, CASES, CONDITIONS, PAPER_CASE_IDS, CaseSpec, Condition, get_case
from .reproduce import reproduce  # noqa: E402  (the function; the module stays importable)

__all__ = ["CaseData", "generate_case", "cache_path", "CASES", "CASE_IDS", "PAPER_CASE_IDS",
           "CONDITIONS", "CaseSpec", "Condition", "get_case", "reproduce"]

