"""The generated data set of one validation case and its ground truth.

A :class:`CaseData` holds one LF peak per wave event, the HF value of every
event (the HF Monte-Carlo; a PAS run only sees it through :meth:`CaseData.oracle`),
event ids and metadata, the paper's ``n_w``, ``P_exp``, threshold and ε1 (scaled
with ``scale``), and the ground truth computed from the *full* HF set:

* ``"empirical"`` (cases 1–2): HF values sorted descending, ``d = k / n_w``,
  the MPM read at ``P_exp`` on ``ln d`` (Eq. 8, 12);
* ``"weibull30"`` (cases 3–4, as the paper): a 3-parameter Weibull least-squares
  fit (:func:`pas.stats.weibull.fit_weibull3_ls`) to the top 30 % of the
  ``n_pos`` non-zero HF peaks, with the plotting positions of all of them, so
  that ``d(h) = (n_pos / n_w) · sf(h)`` and ``MPM = isf(P_exp · n_w / n_pos)``.

Dependence diagnostics (Kendall τ, empirical λ_U/λ_L at q = 0.9, paper Fig. 16)
are computed on the pairs a copula sees: LF over the threshold and HF > 0.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field

import numpy as np

from ..stats.dependence import empirical_tail_dependence, kendall_tau
from ..stats.exceedance import exceedance_probabilities, value_at_exceedance
from ..stats.weibull import fit_weibull3_ls

__all__ = ["CaseData", "ground_truth", "dependence"]


@dataclass
class CaseData:
    """One generated validation case (see module docs).

    Attributes
    ----------
    case : str
    lf, hf : ndarray, shape (n,)
        LF indicator peak and HF value (0 = no impact) of every event.
    ids : ndarray of str, shape (n,)
        ``"<case>-s<seed>-w<wave>"``.
    seed_no, t_start, t_end : ndarray, shape (n,)
        Seed (realisation) number and time window (s, within the seed).
    n_waves : int
    p_exp : float
    threshold : float or None
    eps1 : float
    unit : str
    truth_mpm : float
    truth_d, truth_h : ndarray
        True exceedance distribution (``d`` ascending).
    tau, lambda_u, lambda_l : float
    seed, scale : int, float
    info : dict
        Model coefficients and physics diagnostics (JSON-serialisable).
    """

    case: str
    lf: np.ndarray
    hf: np.ndarray
    ids: np.ndarray
    seed_no: np.ndarray
    t_start: np.ndarray
    t_end: np.ndarray
    n_waves: int
    p_exp: float
    threshold: float | None
    eps1: float
    unit: str
    truth_mpm: float
    truth_d: np.ndarray
    truth_h: np.ndarray
    tau: float
    lambda_u: float
    lambda_l: float
    seed: int
    scale: float
    info: dict = field(default_factory=dict)

    @property
    def n_events(self) -> int:
        return int(self.lf.size)

    def meta(self) -> list[dict]:
        """Per-event metadata for :func:`pas.run_pas` (seed number and time window)."""
        return [{"seed": int(s), "t_start": float(a), "t_end": float(b)}
                for s, a, b in zip(self.seed_no, self.t_start, self.t_end)]

    def run_kwargs(self) -> dict:
        """The case's own arguments of :func:`pas.run_pas`, :func:`pas.run_as` and
        :func:`pas.make_study`.

        ``n_waves``, ``p_exp``, ``eps1``, ``threshold`` and
        ``n_waves_convention="spectral"``: the case's ``n_w`` is ``T_MCS /
        T_p,e`` as in the paper's Table 2 and may lie below its number of LF
        peaks (cases 1 and 4), so it is stated, not counted.

        Examples
        --------
        ``pas.run_pas(d.lf_table(), d.oracle(), **d.run_kwargs(), seed=1)`` on a case
        ``d = pas.validation.generate_case("3b")``.
        """
        return {"n_waves": int(self.n_waves), "p_exp": float(self.p_exp),
                "eps1": float(self.eps1), "threshold": self.threshold,
                "n_waves_convention": "spectral"}

    def lf_table(self, *, meta: bool = False):
        """The LF peaks as :func:`pas.run_pas` reads a table: column ``lf``, the event ids as
        the index and, with ``meta=True``, the per-event :meth:`meta` columns."""
        from ..study.inputs import lf_table

        return lf_table(self.lf, list(self.ids), self.meta() if meta else None)

    def oracle(self):
        """A table oracle: ``oracle(event) -> hf[event.index]``; counts its calls."""
        return table_oracle(self.hf)

    # -- persistence -----------------------------------------------------
    def save(self, path) -> None:
        arrays = {k: getattr(self, k) for k in ("lf", "hf", "ids", "seed_no", "t_start", "t_end",
                                                "truth_d", "truth_h")}
        scalars = {k: getattr(self, k) for k in ("case", "n_waves", "p_exp", "threshold", "eps1",
                                                 "unit", "truth_mpm", "tau", "lambda_u",
                                                 "lambda_l", "seed", "scale", "info")}
        np.savez_compressed(path, meta=np.array(json.dumps(scalars)), **arrays)

    @classmethod
    def load(cls, path) -> "CaseData":
        with np.load(path, allow_pickle=False) as z:
            scalars = json.loads(str(z["meta"]))
            arrays = {k: z[k] for k in z.files if k != "meta"}
        return cls(**arrays, **scalars)


def table_oracle(hf):
    """``oracle(event) -> hf[event.index]`` for the HF values ``hf``; counts its calls."""
    def oracle(event):
        oracle.calls += 1
        return float(hf[event.index])

    oracle.calls = 0
    return oracle


def ground_truth(hf, n_waves, p_exp, method):
    """True MPM and exceedance distribution of the full HF set (module docs).

    Returns
    -------
    mpm : float
    d, h : ndarray
        ``d`` ascending.
    extra : dict
        Fit parameters / empirical MPM for the record.
    """
    hf = np.asarray(hf, float)
    if method == "empirical":
        d, h = exceedance_probabilities(hf, n_waves)
        return float(value_at_exceedance(d, h, p_exp)), d, h, {}
    if method != "weibull30":
        raise ValueError(f"unknown truth method {method!r}")
    pos = hf[hf > 0]
    if pos.size < 10:
        raise ValueError(f"only {pos.size} non-zero HF peaks: too few for a Weibull truth; "
                         "use a larger scale")
    w = fit_weibull3_ls(pos, top_fraction=0.3)
    frac = pos.size / n_waves
    d = np.geomspace(0.1 / n_waves, 0.3 * frac, 200)
    h = w.isf(d / frac)
    d_emp, h_emp = exceedance_probabilities(pos, n_waves)
    q = p_exp / frac
    extra = {
        "weibull": {"theta": w.theta, "alpha": w.alpha, "beta": w.beta},
        "n_pos": int(pos.size),
        "empirical_mpm": float(value_at_exceedance(d_emp, h_emp, p_exp)),
        "mpm_inside_fit": bool(q <= 0.3),
    }
    return float(w.isf(q)), d, h, extra


def dependence(lf, hf, threshold=None):
    """Kendall τ and empirical λ_U, λ_L (q = 0.9) of the true-positive pairs over threshold."""
    lf, hf = np.asarray(lf, float), np.asarray(hf, float)
    keep = hf > 0
    if threshold is not None:
        keep &= lf > threshold
    if keep.sum() < 10:
        return float("nan"), float("nan"), float("nan")
    lu, ll = empirical_tail_dependence(lf[keep], hf[keep], q=0.9)
    return kendall_tau(lf[keep], hf[keep]), lu, ll
