"""The environment: scatter diagrams of (Hs, Tz or Tp) and the joint models behind them.

A :class:`ScatterDiagram` holds bin centres and the probability of each
(Hs, period) bin; :meth:`ScatterDiagram.sea_states` gives the table the
long-term analyses take (one row per sea state: ``name``, ``probability``,
``hs``, ``tp``, ``tz``, ``gamma``, ``heading``, ``speed``). It is built from a
table of counts or probabilities, from the IACS Rec. 34 North Atlantic
diagram shipped with the package (:func:`north_atlantic`), or by binning a
joint Hs-Tz model of virocon (Haselsteiner et al. 2022), e.g. the DNV model
of DNV-RP-C205 fitted to a data set with :func:`fit_joint_model`.

Periods: a JONSWAP spectrum of peak enhancement ``gamma`` has
``Tz / Tp = sqrt(I0 / I2)`` with ``I_n`` the n-th moment of its shape on
``omega / omega_p`` (:func:`tz_over_tp`, computed by quadrature, not the DNV
polynomial), which converts the diagram's period into the other one.

References
----------
IACS (2001). Recommendation No. 34, Standard wave data, Rev. 1.
    The table (``data/iacs_rec34_north_atlantic.csv``) is IACS's published
    reference data, which IACS distributes free of charge and which class rules
    and codes reproduce widely; it is reproduced here with this attribution.  IACS
    states no licence for it: where yours must be cleared, pass your own table
    (:meth:`ScatterDiagram.from_table`).

Haselsteiner, A.F., Coe, R.G., Manuel, L., Chai, W., Leira, B., Clarindo, G.,
Guedes Soares, C., Hannesdóttir, Á., Dimitrov, N., Sander, A., Ohlendorf,
J.-H., Thoben, K.-D., de Hauteclocque, G., Mackay, E., Jonathan, P., Qiao, C.,
Myers, A., Rode, A., Hildebrandt, A., Schmidt, B., Vanem, E., Huseby, A.B.
(2022). A benchmarking exercise for environmental contours. Ocean
Engineering 236, 109504 (virocon).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

import numpy as np
import pandas as pd
from scipy import integrate

from .spectra import _jonswap_shape

__all__ = ["ScatterDiagram", "north_atlantic", "tz_over_tp", "fit_joint_model",
           "dnv_joint_model"]

_PERIODS = ("tz", "tp")


@lru_cache(maxsize=32)
def tz_over_tp(gamma=3.3, sigma_a=0.07, sigma_b=0.09):
    """Ratio ``Tz / Tp`` of a JONSWAP spectrum (1 for none: 0.7104 at ``gamma = 1``).

    Examples
    --------
    >>> round(tz_over_tp(1.0), 4)
    0.7104
    """
    if not gamma >= 1.0:
        raise ValueError(f"gamma must be >= 1, got {gamma!r}")

    def moment(n):
        def f(x):
            return x**n * float(_jonswap_shape(np.array([x]), gamma, sigma_a, sigma_b)[0])
        parts = [integrate.quad(f, a, b, epsabs=0.0, epsrel=1e-12, limit=200)[0]
                 for a, b in ((0.0, 1.0), (1.0, 3.0), (3.0, np.inf))]
        return sum(parts)

    return float(np.sqrt(moment(0) / moment(2)))


def _check_period_kind(period):
    if period not in _PERIODS:
        raise ValueError(f"period must be 'tz' or 'tp', got {period!r}")
    return period


@dataclass(frozen=True)
class ScatterDiagram:
    """Probabilities of (Hs, period) bins.

    Attributes
    ----------
    hs : ndarray, shape (n_hs,)
        Bin centres of the significant wave height (m).
    period : ndarray, shape (n_t,)
        Bin centres of the period (s), ``Tz`` or ``Tp`` as ``period_kind``.
    probability : ndarray, shape (n_hs, n_t)
        Share of time in each bin; sums to 1.
    period_kind : {'tz', 'tp'}
    gamma : float
        JONSWAP peak enhancement used for the sea states and to convert the
        period.
    name : str
    coverage : float
        Probability mass the bins hold before normalising (1 for a table;
        below 1 when a joint model has mass outside the bin edges).
    """

    hs: np.ndarray
    period: np.ndarray
    probability: np.ndarray
    period_kind: str = "tz"
    gamma: float = 3.3
    name: str = ""
    coverage: float = 1.0

    def __post_init__(self):
        hs = np.asarray(self.hs, dtype=float)
        per = np.asarray(self.period, dtype=float)
        p = np.asarray(self.probability, dtype=float)
        _check_period_kind(self.period_kind)
        if hs.ndim != 1 or per.ndim != 1 or p.shape != (hs.size, per.size):
            raise ValueError(f"probability must have shape (len(hs), len(period)) = "
                             f"({hs.size}, {per.size}), got {p.shape}")
        if (np.any(~np.isfinite(hs)) or np.any(hs <= 0)
                or np.any(~np.isfinite(per)) or np.any(per <= 0)):
            raise ValueError("hs and period bin centres must be positive and finite")
        if np.any(~np.isfinite(p)) or np.any(p < 0) or not p.sum() > 0:
            raise ValueError(
                "probabilities (or counts) must be finite, non-negative and not all zero"
            )
        if not self.gamma >= 1.0:
            raise ValueError(f"gamma must be >= 1, got {self.gamma!r}")
        for name, v in (("hs", hs), ("period", per), ("probability", p / p.sum())):
            v.setflags(write=False)
            object.__setattr__(self, name, v)

    @classmethod
    def from_table(cls, table, *, period="tz", gamma=3.3, name=""):
        """Build from counts or probabilities (normalised here).

        Parameters
        ----------
        table : pandas.DataFrame
            Either wide -- index the Hs bin centres, columns the period bin
            centres, cells counts or probabilities -- or long, with columns
            ``hs``, ``tz`` or ``tp`` (as ``period``) and ``probability`` or
            ``count``.
        period : {'tz', 'tp'}, default 'tz'
            Which period the table's periods are.
        gamma : float, default 3.3
        name : str, optional
        """
        _check_period_kind(period)
        if not isinstance(table, pd.DataFrame):
            raise TypeError(f"table must be a pandas DataFrame, got {type(table).__name__}")
        if "hs" in table.columns:
            weight = next((c for c in ("probability", "count") if c in table.columns), None)
            if period not in table.columns or weight is None:
                raise ValueError(f"a long table needs columns 'hs', {period!r} and 'probability' "
                                 f"or 'count'; it has {list(table.columns)}")
            wide = table.pivot_table(index="hs", columns=period, values=weight,
                                     aggfunc="sum", fill_value=0.0)
        else:
            wide = table
        try:
            hs = wide.index.to_numpy(dtype=float)
            per = np.asarray([float(c) for c in wide.columns])
        except (TypeError, ValueError) as exc:
            raise ValueError("a wide table needs numeric Hs bin centres as index and numeric "
                             f"period bin centres as columns ({exc})") from None
        order_h, order_t = np.argsort(hs), np.argsort(per)
        p = wide.to_numpy(dtype=float)[np.ix_(order_h, order_t)]
        return cls(hs=hs[order_h], period=per[order_t], probability=p, period_kind=period,
                   gamma=gamma, name=name)

    @classmethod
    def from_csv(cls, path, *, period="tz", gamma=3.3, name=None):
        """Read a wide table (first column Hs, header the periods; ``#`` comments)."""
        table = pd.read_csv(path, comment="#", index_col=0)
        return cls.from_table(table, period=period, gamma=gamma,
                              name=str(path) if name is None else name)

    @classmethod
    def from_joint_model(cls, model, hs_edges, period_edges, *, period="tz", gamma=3.3,
                         name="", n_gauss=16):
        """Bin a virocon joint model ``[Hs, period | Hs]`` on the given edges.

        ``P(bin) = integral_{Hs bin} f_Hs(h) [F_T(t1 | h) - F_T(t0 | h)] dh``:
        the Hs marginal ``F_Hs(b) - F_Hs(a)`` exactly, times the mean of the
        conditional mass over the Hs bin weighted by ``f_Hs`` (Gauss-Legendre,
        ``n_gauss`` nodes on the part of the bin where Hs can lie, so a
        3-parameter Weibull's location inside a bin does not spoil it). The mass
        outside the edges is dropped and reported as ``coverage``.

        Parameters
        ----------
        model : virocon.GlobalHierarchicalModel
            Fitted or predefined model whose dimension 0 is Hs and dimension 1
            the period conditional on Hs.
        hs_edges, period_edges : array_like
            Increasing bin edges (m, s).
        """
        he = np.asarray(hs_edges, dtype=float)
        te = np.asarray(period_edges, dtype=float)
        for label, e in (("hs_edges", he), ("period_edges", te)):
            if e.ndim != 1 or e.size < 2 or np.any(np.diff(e) <= 0) or e[0] < 0:
                raise ValueError(f"{label} must be increasing non-negative edges (at least two)")
        dist_hs, dist_t = model.distributions[0], model.distributions[1]
        x, w = np.polynomial.legendre.leggauss(n_gauss)
        prob = np.zeros((he.size - 1, te.size - 1))
        lowest = float(np.nan_to_num(dist_hs.icdf(0.0), nan=0.0))  # e.g. a Weibull's location
        for i, (a, b) in enumerate(zip(he[:-1], he[1:])):
            a = max(a, lowest)
            if b <= a:
                continue
            h = 0.5 * (a + b) + 0.5 * (b - a) * x
            mass = float(dist_hs.cdf(b) - dist_hs.cdf(a))
            weight = w * dist_hs.pdf(h)
            if not (mass > 0 and weight.sum() > 0):
                continue
            cdf = np.array([dist_t.cdf(np.full(h.size, t), given=h) for t in te])
            prob[i] = mass * (weight @ np.diff(cdf, axis=0).T) / weight.sum()
        coverage = float(prob.sum())
        return cls(hs=0.5 * (he[:-1] + he[1:]), period=0.5 * (te[:-1] + te[1:]),
                   probability=prob, period_kind=period, gamma=gamma, name=name,
                   coverage=coverage)

    @property
    def tz(self):
        """Zero-crossing period of each period bin (s)."""
        return self.period if self.period_kind == "tz" else self.period * tz_over_tp(self.gamma)

    @property
    def tp(self):
        """Peak period of each period bin (s)."""
        return self.period if self.period_kind == "tp" else self.period / tz_over_tp(self.gamma)

    def to_frame(self):
        """The diagram as a wide DataFrame of probabilities (index Hs, columns period)."""
        return pd.DataFrame(self.probability, index=pd.Index(self.hs, name="hs"),
                            columns=pd.Index(self.period, name=self.period_kind))

    def sample(self, n, *, seed):
        """``n`` (Hs, period) pairs drawn from the bins, uniform inside each 1-bin cell.

        A data set to fit a joint model to (e.g. :func:`fit_joint_model`);
        the cell widths are those between neighbouring centres.

        Returns
        -------
        ndarray, shape (n, 2)
        """
        rng = np.random.default_rng(seed)
        flat = rng.choice(self.probability.size, size=int(n), p=self.probability.ravel())
        i, j = np.unravel_index(flat, self.probability.shape)

        def jitter(centres, idx):
            width = np.gradient(centres) if centres.size > 1 else np.ones(1)
            return centres[idx] + (rng.uniform(size=idx.size) - 0.5) * width[idx]

        return np.column_stack([jitter(self.hs, i), jitter(self.period, j)])

    def sea_states(self, *, heading=180.0, speed=0.0, min_probability=0.0):
        """One row per occupied bin: the table the long-term analyses take.

        Parameters
        ----------
        heading : float or mapping, default 180
            Wave heading relative to the ship (deg, 180 = head seas), or
            ``{heading: probability}`` to spread every bin over headings.
        speed : float, default 0
            Ship speed (m/s).
        min_probability : float, default 0
            Bins at or below this probability are left out (the rest are not
            renormalised, so the dropped share stays visible as ``1 - sum``).

        Returns
        -------
        pandas.DataFrame
            ``name``, ``probability``, ``hs``, ``tp``, ``tz``, ``gamma``,
            ``heading``, ``speed``.
        """
        headings = dict(heading) if isinstance(heading, dict) else {float(heading): 1.0}
        total = sum(headings.values())
        if not all(np.isfinite(v) and v >= 0 for v in headings.values()) or not total > 0:
            raise ValueError("heading probabilities must be non-negative with a positive sum")
        i, j = np.nonzero(self.probability > min_probability)
        rows = []
        for mu, p_mu in headings.items():
            for a, b in zip(i, j):
                name = f"hs{self.hs[a]:g}_{self.period_kind}{self.period[b]:g}"
                rows.append({"name": name if len(headings) == 1 else f"{name}_mu{mu:g}",
                             "probability": self.probability[a, b] * p_mu / total,
                             "hs": self.hs[a], "tp": self.tp[b], "tz": self.tz[b],
                             "gamma": self.gamma, "heading": float(mu), "speed": float(speed)})
        return pd.DataFrame(rows)


def north_atlantic(*, gamma=3.3):
    """The IACS Rec. 34 (Rev. 1) North Atlantic Hs-Tz scatter diagram (1 m x 1 s bins).

    Examples
    --------
    >>> sd = north_atlantic()
    >>> sd.probability.shape, round(float(sd.probability.sum()), 12)
    ((17, 18), 1.0)
    """
    path = resources.files("pas.waves") / "data" / "iacs_rec34_north_atlantic.csv"
    with resources.as_file(path) as p:
        return ScatterDiagram.from_csv(p, period="tz", gamma=gamma,
                                       name="IACS Rec. 34 North Atlantic")


def dnv_joint_model(*, hs_weibull=(3.041, 1.484, 0.661), mu=(0.70, 1.27, 0.131),
                    sigma=(0.1334, 0.0264, -0.1906)):
    """The joint Hs-Tz model of DNV-RP-C205 Sec. 3.6.3 with given parameters, as virocon's.

    Hs is a 3-parameter Weibull; ln Tz given Hs is normal with mean
    ``a0 + a1 Hs^a2`` and standard deviation ``b0 + b1 exp(b2 Hs)``.  The
    defaults are DNV's North Atlantic parameters (DNV-RP-C205, 2010); pass a
    site's published ones to bin them (:meth:`ScatterDiagram.from_joint_model`)
    or draw their contour (:func:`pas.waves.iform_contour`) without fitting.

    Parameters
    ----------
    hs_weibull : (scale, shape, location)
        Of Hs (m, -, m).
    mu, sigma : (a0, a1, a2), (b0, b1, b2)
        Of ln Tz given Hs.

    Returns
    -------
    virocon.GlobalHierarchicalModel
    """
    from virocon import (
        DependenceFunction,
        GlobalHierarchicalModel,
        LogNormalDistribution,
        WeibullDistribution,
    )

    def fixed(func, abc):
        dependence = DependenceFunction(func)
        dependence.parameters = dict(zip("abc", map(float, abc)))
        return dependence

    scale, shape, location = map(float, hs_weibull)
    if not (scale > 0 and shape > 0 and location >= 0):
        raise ValueError(f"hs_weibull must be (scale > 0, shape > 0, location >= 0), "
                         f"got {hs_weibull!r}")
    ln_tz = {"mu": fixed(lambda h, a, b, c: a + b * h**c, mu),
             "sigma": fixed(lambda h, a, b, c: a + b * np.exp(c * h), sigma)}
    return GlobalHierarchicalModel([
        {"distribution": WeibullDistribution(alpha=scale, beta=shape, gamma=location)},
        {"distribution": LogNormalDistribution(), "conditional_on": 0, "parameters": ln_tz}])


def fit_joint_model(data, *, model="DNV"):
    """Fit virocon's predefined joint Hs-Tz model to a data set.

    Parameters
    ----------
    data : array_like, shape (n, 2)
        Columns Hs (m) and Tz (s).
    model : {'DNV', 'OMAE2020'}, default 'DNV'
        ``'DNV'``: 3-parameter Weibull Hs and log-normal Tz | Hs of
        DNV-RP-C205 Sec. 3.6.3; ``'OMAE2020'``: the exponentiated-Weibull
        model of Haselsteiner et al. (2020).

    Returns
    -------
    virocon.GlobalHierarchicalModel
    """
    from virocon import GlobalHierarchicalModel
    from virocon.predefined import get_DNVGL_Hs_Tz, get_OMAE2020_Hs_Tz

    makers = {"DNV": get_DNVGL_Hs_Tz, "OMAE2020": get_OMAE2020_Hs_Tz}
    if model not in makers:
        raise ValueError(f"model must be one of {sorted(makers)}, got {model!r}")
    arr = np.asarray(data, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 2 or arr.shape[0] < 50:
        raise ValueError(f"data must have shape (n >= 50, 2) with columns Hs, Tz; got {arr.shape}")
    if np.any(~np.isfinite(arr)) or np.any(arr <= 0):
        raise ValueError("data must hold positive finite Hs and Tz")
    descriptions, fit_descriptions, _ = makers[model]()
    joint = GlobalHierarchicalModel(descriptions)
    joint.fit(arr, fit_descriptions)
    return joint
