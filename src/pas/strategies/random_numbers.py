"""The uniforms of Step 9 (Eq. 7): redrawn every iteration, or common to the study.

Van Essen & Seyffert (2026) draw ``z`` new uniforms per conditioning peak
each iteration, so two predictions of the same fitted model differ by draw
noise, which App. C's stopping measure then reads as learning.  With common
random numbers each LF peak (pool position) keeps its ``z`` uniforms for the
whole study, and a change of the predicted distribution is a change of the
model (``docs/departures.md``, ``common_random_numbers``).
"""

from __future__ import annotations

import numpy as np
from scipy import special

from .steps import EPS

CRN_BLOCK = 1024


class PeakUniforms:
    """Uniforms ``r`` (copula) and ``q`` (impact) per LF peak, shape ``(z, n0)`` each.

    ``common=True``: block ``k`` of :data:`CRN_BLOCK` peaks draws from its own
    stream ``(seed, k)``, so a growing conditioning set only appends blocks
    and no peak's uniforms ever change.  ``common=False``: new uniforms from
    the caller's ``rng`` on every call (the paper).
    """

    def __init__(self, z: int, seed: int | None, common: bool = True):
        self.z, self.seed, self.common = int(z), 0 if seed is None else seed, bool(common)
        self._uniforms = None
        self._scores = None

    def scores(self, n0: int):
        """``Φ⁻¹(r)`` of the common copula uniforms of :meth:`draw`, computed once per peak
        (None when the uniforms are redrawn every call)."""
        if not self.common:
            return None
        have = 0 if self._scores is None else self._scores.shape[1]
        if have < n0:
            r, _ = self.draw(n0, None)
            new = special.ndtri(r[:, have:])
            self._scores = new if self._scores is None else np.concatenate([self._scores, new],
                                                                           axis=1)
        return self._scores[:, :n0]

    def draw(self, n0: int, rng: np.random.Generator | None):
        if not self.common:
            return (rng.uniform(EPS, 1 - EPS, size=(self.z, n0)),
                    rng.uniform(size=(self.z, n0)))
        have = 0 if self._uniforms is None else self._uniforms.shape[2]
        if have < n0:
            blocks = []
            for k in range(have // CRN_BLOCK, -(-n0 // CRN_BLOCK)):
                crn = np.random.default_rng([self.seed, 0x43524E, k])
                blocks.append(np.stack([crn.uniform(EPS, 1 - EPS, size=(self.z, CRN_BLOCK)),
                                        crn.uniform(size=(self.z, CRN_BLOCK))]))
            new = np.concatenate(blocks, axis=2)
            self._uniforms = new if self._uniforms is None else np.concatenate([self._uniforms, new], axis=2)
        return self._uniforms[0, :, :n0], self._uniforms[1, :, :n0]
