"""The paper's eight validation cases as seeded, physics-based synthetic analogues.

The paper's HF data (model-basin tests, proprietary non-linear simulations)
are not public, so :func:`generate_case` builds an *analogue* of each sub-case
from the package's own wave and ship models, with the paper's conditions,
``n_w``, ``P_exp``, thresholds and ε1 (:data:`CASES`).  :func:`reproduce`
runs PAS (and AS) on them as a user would.  See ``cases/README.md``.
"""

from .data import CaseData
from .generate import cache_path, generate_case
from .registry import CASE_IDS, CASES, CONDITIONS, CaseSpec, Condition, get_case
from .reproduce import reproduce  # noqa: E402  (the function; the module stays importable)

__all__ = ["CaseData", "generate_case", "cache_path", "CASES", "CASE_IDS", "CONDITIONS",
           "CaseSpec", "Condition", "get_case", "reproduce"]

