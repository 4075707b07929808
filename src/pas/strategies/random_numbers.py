"""The uniforms of Step 9 (Eq. 7): redrawn every iteration, or common to the study.

Van Essen & Seyffert (2026) draw ``z`` new uniforms per conditioning peak
each iteration, so two predictions of the same fitted model differ by draw
noise, which App. C's stopping measure then reads as learning.  With common
random numbers each LF peak (pool position) keeps its ``z`` uniforms for the
whole study, and a change of the predicted distribution is a change of the
model (``docs/departures.md``, ``common_random_numbers``).
"""

from __future__ import annotations

import copy

import numpy as np

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
        self._r_max = None

    def replayable(self, n0: int, rng: np.random.Generator | None):
        """``(r, q, r_max, again)``: the uniforms of :meth:`draw`, each peak's largest ``r``
        over the ``z`` rows, and a function that gives the same ``(r, q)`` again.

        Common uniforms are kept, so ``again`` reads them; otherwise it replays a copy
        of ``rng`` as it was before this draw, and nothing of shape ``(z, n0)`` is kept.
        """
        if not self.common:
            before = copy.deepcopy(rng)
            r, q = self.draw(n0, rng)
            return r, q, r.max(axis=0), lambda: self.draw(n0, copy.deepcopy(before))
        r, q = self.draw(n0, None)
        return r, q, self._r_max[:n0], lambda: self.draw(n0, None)

    def draw(self, n0: int, rng: np.random.Generator | None):
        if not self.common:
            return (rng.uniform(EPS, 1 - EPS, size=(self.z, n0)),
                    rng.uniform(size=(self.z, n0)))
        have = 0 if self._uniforms is None else self._uniforms.shape[2]
        if have < n0:
            # filled in place, block by block: one array of the uniforms' size alive, not two
            grown = np.empty((2, self.z, -(-n0 // CRN_BLOCK) * CRN_BLOCK))
            if have:
                grown[:, :, :have] = self._uniforms
            self._uniforms = None
            for k in range(have // CRN_BLOCK, grown.shape[2] // CRN_BLOCK):
                crn = np.random.default_rng([self.seed, 0x43524E, k])
                block = grown[:, :, k * CRN_BLOCK:(k + 1) * CRN_BLOCK]
                block[0] = crn.uniform(EPS, 1 - EPS, size=(self.z, CRN_BLOCK))
                block[1] = crn.uniform(size=(self.z, CRN_BLOCK))
            self._uniforms = grown
            self._r_max = grown[0].max(axis=0)
        return self._uniforms[0, :, :n0], self._uniforms[1, :, :n0]
