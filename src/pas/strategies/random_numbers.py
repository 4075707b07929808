"""The uniforms of Step 9 (Eq. 7): redrawn every iteration, or common to the study.

Van Essen & Seyffert (2026) draw ``z`` new uniforms per conditioning peak
each iteration, so two predictions of the same fitted model differ by draw
noise, which App. C's stopping measure then reads as learning.  With common
random numbers each LF peak (pool position) keeps its ``z`` uniforms for the
whole study, and a change of the predicted distribution is a change of the
model (``docs/explanation/departures.md``, ``common_random_numbers``).
"""

from __future__ import annotations

import copy

import numpy as np

from .steps import EPS

CRN_BLOCK = 1024

Q_ROUNDING = 2.0**-24
"""Kept as float32, an impact uniform ``q < 1`` moves by at most ``2^-25``: farther than
this from an impact probability ``p`` it decides ``q < p`` as its float64 value does."""


class PeakUniforms:
    """Uniforms ``r`` (copula) and ``q`` (impact) per LF peak, shape ``(z, n0)`` each.

    ``common=True``: block ``k`` of :data:`CRN_BLOCK` peaks draws from its own
    stream ``(seed, k)``, so a growing conditioning set only appends blocks
    and no peak's uniforms ever change; the ``q`` of the stream (drawn after its
    ``r``) are kept only once asked for (``impacts=True``), since only the impact
    model reads them, and as float32 (60 MB instead of 120 at 1.5 M peaks and
    ``z = 10``): :meth:`q_for` gives values that decide ``q < p`` exactly as the
    float64 stream does.  ``r`` stays float64: rounded to float32 it would move
    the MPM.  ``common=False``:
    new uniforms from the caller's ``rng`` on every call (the paper).
    """

    def __init__(self, z: int, seed: int | None, common: bool = True):
        self.z, self.seed, self.common = int(z), 0 if seed is None else seed, bool(common)
        self._r = self._q = self._r_max = None

    def __deepcopy__(self, memo):
        """A copy sharing the kept uniforms: they are read-only and a function of
        ``(z, seed, common)`` and the peak, so every copy would hold the same numbers
        (the study copies the strategy before each fit: 240 MB at 1.5 M peaks)."""
        twin = PeakUniforms(self.z, self.seed, self.common)
        twin._r, twin._q, twin._r_max = self._r, self._q, self._r_max
        return twin

    def replayable(self, n0: int, rng: np.random.Generator | None, impacts: bool = True):
        """``(r, q, r_max, again)``: the uniforms of :meth:`draw`, each peak's largest ``r``
        over the ``z`` rows, and a function that gives the same ``(r, q)`` again.

        Common uniforms are kept, so ``again`` reads them; otherwise it replays a copy
        of ``rng`` as it was before this draw, and nothing of shape ``(z, n0)`` is kept.
        """
        if not self.common:
            before = copy.deepcopy(rng)
            r, q = self.draw(n0, rng)
            return r, q, r.max(axis=0), lambda: self.draw(n0, copy.deepcopy(before))
        r, q = self.draw(n0, None, impacts)
        return r, q, self._r_max[:n0], lambda: self.draw(n0, None, impacts)

    def draw(self, n0: int, rng: np.random.Generator | None, impacts: bool = True):
        """``(r, q)`` of the first ``n0`` peaks (``q`` None when common and not ``impacts``)."""
        if not self.common:
            return (rng.uniform(EPS, 1 - EPS, size=(self.z, n0)),
                    rng.uniform(size=(self.z, n0)))
        if self._r is None or self._r.shape[1] < n0:
            self._r = self._grown(self._r, n0, 0)
            self._r_max = self._r.max(axis=0)
            self._r_max.flags.writeable = False  # shared by copies
        if impacts and (self._q is None or self._q.shape[1] < n0):
            self._q = self._grown(self._q, self._r.shape[1], 1)
        return self._r[:, :n0], None if not impacts else self._q[:, :n0]

    def _grown(self, kept, n0: int, which: int) -> np.ndarray:
        """``kept`` (r: ``which`` 0, q: 1) grown to whole blocks covering ``n0`` peaks,
        filled in place block by block: one array of the uniforms' size alive, not two."""
        have = 0 if kept is None else kept.shape[1]
        grown = np.empty((self.z, -(-n0 // CRN_BLOCK) * CRN_BLOCK),
                         dtype=float if which == 0 else np.float32)
        if have:
            grown[:, :have] = kept
        for k in range(have // CRN_BLOCK, grown.shape[1] // CRN_BLOCK):
            crn = np.random.default_rng([self.seed, 0x43524E, k])
            r = crn.uniform(EPS, 1 - EPS, size=(self.z, CRN_BLOCK))
            grown[:, k * CRN_BLOCK:(k + 1) * CRN_BLOCK] = (
                r if which == 0 else crn.uniform(size=(self.z, CRN_BLOCK)))
        grown.flags.writeable = False  # shared by copies
        return grown

    def _exact_q(self, rows, cols) -> np.ndarray:
        """The float64 impact uniforms at ``(rows, cols)``, drawn again from their blocks."""
        out = np.empty(rows.size)
        blocks = cols // CRN_BLOCK
        for k in np.unique(blocks):
            crn = np.random.default_rng([self.seed, 0x43524E, k])
            crn.uniform(EPS, 1 - EPS, size=(self.z, CRN_BLOCK))
            q = crn.uniform(size=(self.z, CRN_BLOCK))
            at = blocks == k
            out[at] = q[rows[at], cols[at] - k * CRN_BLOCK]
        return out

    def q_for(self, q, impact, cols, rows=None) -> np.ndarray:
        """Impact uniforms ``q`` (of :meth:`draw`, at peaks ``cols`` and rows ``rows``, all
        when None) as float64 values that decide ``q < impact`` as the float64 stream does:
        the float32 ones within :data:`Q_ROUNDING` of ``impact`` drawn again."""
        q = np.asarray(q, dtype=float)
        if not self.common:
            return q
        near = np.abs(q - impact) <= Q_ROUNDING
        if near.any():
            j, i = np.nonzero(near)
            rows = np.arange(self.z) if rows is None else np.asarray(rows)
            q[j, i] = self._exact_q(rows[j], np.asarray(cols)[i])
        return q
