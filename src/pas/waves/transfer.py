"""Linear transfer functions of a hull: from the built-in model, a Capytaine dataset or an RAO
table.

A :class:`TransferFunction` holds complex amplitudes per unit wave amplitude
on an (heading, omega) grid for named degrees of freedom, in the convention
of :mod:`pas.waves.realisation`: a response is ``Re[H A exp(i w_e t)]`` for a
wave component ``A`` referred to the reference point (midship or the centre
of rotation), ``x`` forward, ``y`` to port, ``z`` up, heading 180 deg = head
seas. Rotations are right-handed about the axes through the reference point,
so roll is positive starboard down and pitch positive bow down.

Responses at a point ``(x, y)`` of the ship (from the reference point) are
formed from the motions:

* vertical motion ``w = heave + y roll - x pitch``;
* relative wave elevation (RWE) ``R = eta(x, y) - w``, with the undisturbed
  incident wave ``eta(x, y) = exp(-i k (x cos mu + y sin mu))`` per unit
  amplitude at the reference point (no swell-up, no diffraction);
* relative vertical velocity (RRV) ``dR/dt = i w_e R`` in the ship-fixed frame
  (positive when the water rises relative to the deck);
* VBM (and any other load) only where the RAO set has it (the built-in model
  does, a rigid-body BEM dataset does not).

Capytaine writes complex amplitudes for ``exp(-i omega t)`` and an incident
wave ``exp(i k (x cos b + y sin b))`` with ``b`` the propagation direction
(``b = pi`` travels to ``-x``: head seas for a bow at ``+x``), so its heading
is ours and its amplitudes are the complex conjugates of ours.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .encounter import encounter_frequency
from .ship import ship_rao
from .spectra import GRAVITY

__all__ = ["TransferFunction", "MOTIONS"]

MOTIONS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
_CAPYTAINE_DOFS = {"Surge": "surge", "Sway": "sway", "Heave": "heave",
                   "Roll": "roll", "Pitch": "pitch", "Yaw": "yaw"}


def _interp_complex(x_new, x, y):
    """Linear interpolation of complex ``y(x)`` along the last axis, held below, 0 above."""
    re = np.interp(x_new, x, y.real, right=0.0)
    im = np.interp(x_new, x, y.imag, right=0.0)
    return re + 1j * im


@dataclass(frozen=True)
class TransferFunction:
    """Complex transfer functions on a (heading, omega) grid.

    Attributes
    ----------
    omega : ndarray, shape (n_w,)
        Increasing absolute wave frequencies (rad/s).
    heading : ndarray, shape (n_h,)
        Wave headings relative to the ship (deg, 180 = head seas), increasing.
    values : dict of str to ndarray, shape (n_h, n_w), complex
        Per unit wave amplitude: translations m/m, rotations rad/m, loads
        their unit per m.
    speed : float
        Ship speed (m/s) the transfer functions hold (encounter frequencies
        are formed with it).
    source : str
        Where they come from, for reports.

    Notes
    -----
    Between grid points the real and imaginary parts are interpolated
    linearly; below the lowest frequency the lowest value is held (the
    long-wave limit), above the highest the transfer function is taken as 0,
    and the spectral routines report how much wave energy lies outside the
    grid (``coverage``).
    """

    omega: np.ndarray
    heading: np.ndarray
    values: dict
    speed: float = 0.0
    source: str = ""
    _g: float = field(default=GRAVITY, repr=False)

    def __post_init__(self):
        w = np.asarray(self.omega, dtype=float)
        h = np.atleast_1d(np.asarray(self.heading, dtype=float))
        if w.ndim != 1 or w.size < 2 or np.any(np.diff(w) <= 0) or w[0] <= 0:
            raise ValueError("omega must be at least two increasing positive frequencies (rad/s)")
        if np.any(np.diff(h) <= 0):
            raise ValueError("heading must be increasing (deg)")
        vals = {}
        for name, v in self.values.items():
            a = (
                np.asarray(v, dtype=complex).reshape(h.size, w.size)
                if np.size(v) == h.size * w.size
                else None
            )
            if a is None or not np.all(np.isfinite(a)):
                raise ValueError(
                    f"values[{name!r}] must be finite with shape (n_heading, n_omega) = "
                    f"({h.size}, {w.size})"
                )
            a.setflags(write=False)
            vals[str(name)] = a
        for name, v in (("omega", w), ("heading", h)):
            v.setflags(write=False)
            object.__setattr__(self, name, v)
        object.__setattr__(self, "values", vals)

    # --- construction -----------------------------------------------------------------
    @classmethod
    def from_ship(cls, ship, omega, heading=(180.0,), *, speed=0.0):
        """The closed-form box model of :mod:`pas.waves.ship` (heave, pitch, VBM at midship)."""
        hs = np.atleast_1d(np.asarray(heading, dtype=float))
        raos = [ship_rao(ship, omega, speed=speed, heading=mu) for mu in hs]
        return cls(omega=np.asarray(omega, dtype=float), heading=hs,
                   values={dof: np.array([getattr(r, dof) for r in raos])
                           for dof in ("heave", "pitch", "vbm")},
                   speed=float(speed), source=f"pas.waves.ship ({ship.length:g} m box model)")

    @classmethod
    def from_table(cls, table, *, speed=0.0, source="RAO table"):
        """From a long table: ``omega``, ``heading``, ``dof``, ``amplitude``, ``phase`` (deg).

        ``table`` is a DataFrame, the path of a CSV file, or the path of a
        NetCDF file (``.nc``, read with xarray + h5netcdf) whose variables
        ``amplitude`` and ``phase`` have the dimensions ``omega``,
        ``heading``, ``dof``. The phase is that of ``exp(i w t)`` (this
        package's convention): a response leading the wave at the reference
        point by ``phase`` degrees. Every (dof, heading) must have every
        frequency. :meth:`to_table` writes the same layout.
        """
        if not isinstance(table, pd.DataFrame) and str(table).endswith(".nc"):
            import xarray as xr

            ds = xr.load_dataset(table, engine="h5netcdf")
            table = ds[["amplitude", "phase"]].to_dataframe().reset_index()
        elif not isinstance(table, pd.DataFrame):
            table = pd.read_csv(table, comment="#")
        need = ["omega", "heading", "dof", "amplitude", "phase"]
        missing = [c for c in need if c not in table.columns]
        if missing:
            raise ValueError(f"RAO table lacks columns {missing}; it needs {need}")
        omega = np.unique(table["omega"].to_numpy(dtype=float))
        heading = np.unique(table["heading"].to_numpy(dtype=float))
        values = {}
        for dof, part in table.groupby("dof", sort=True):
            grid = part.pivot_table(index="heading", columns="omega", aggfunc="first",
                                    values=["amplitude", "phase"])
            amp = grid["amplitude"].reindex(index=heading, columns=omega).to_numpy()
            ph = grid["phase"].reindex(index=heading, columns=omega).to_numpy()
            if np.any(~np.isfinite(amp)) or np.any(~np.isfinite(ph)):
                raise ValueError(f"RAO table: dof {dof!r} lacks some (heading, omega) pairs; "
                                 "give every dof every heading and frequency")
            values[str(dof)] = amp * np.exp(1j * np.deg2rad(ph))
        return cls(omega=omega, heading=heading, values=values, speed=speed, source=source)

    @classmethod
    def from_capytaine(cls, dataset, *, source=None):
        """RAOs of the rigid-body motions of a Capytaine dataset.

        Solves ``[-w^2 (M + A) - i w B + C] X = F`` per frequency and heading
        from the dataset's ``added_mass``, ``radiation_damping``,
        ``excitation_force``, ``inertia_matrix`` and ``hydrostatic_stiffness``
        (Capytaine's ``post_pro.rao`` does the same; Capytaine itself is not
        needed) and converts to this package's convention (complex
        conjugate). Reading a file needs xarray and h5netcdf (the
        ``longterm`` extra).

        Parameters
        ----------
        dataset : xarray.Dataset or path
            From ``capytaine.assemble_dataset`` (zero speed), or a NetCDF file
            written by Capytaine's ``export_dataset``. The RWE's incident wave
            uses the deep-water wave number, so for a finite-depth dataset
            only the motions are exact.
        """
        import xarray as xr

        label = source
        if not isinstance(dataset, xr.Dataset):
            label = label or str(dataset)
            dataset = xr.load_dataset(dataset, engine="h5netcdf")
        ds = _merge_complex(dataset)
        speed = ds.coords.get("forward_speed", ds.attrs.get("forward_speed", 0.0))
        if np.any(np.asarray(speed, dtype=float) != 0.0):
            raise ValueError("Capytaine dataset has a forward speed; only zero-speed datasets "
                             "are read (their RAOs on the wave frequency)")
        need = ["added_mass", "radiation_damping", "excitation_force", "inertia_matrix",
                "hydrostatic_stiffness"]
        missing = [v for v in need if v not in ds]
        if missing:
            raise ValueError(f"Capytaine dataset lacks {missing}; set body.inertia_matrix and "
                             "body.hydrostatic_stiffness before assemble_dataset")
        dofs = [str(d) for d in ds["radiating_dof"].values]
        w = np.asarray(ds["omega"].values, dtype=float)
        mu = np.rad2deg(np.asarray(ds["wave_direction"].values, dtype=float))
        order = np.argsort(mu)
        sel = dict(influenced_dof=dofs, radiating_dof=dofs)
        m = ds["inertia_matrix"].sel(**sel).to_numpy()
        c = ds["hydrostatic_stiffness"].sel(**sel).to_numpy()
        a = (
            ds["added_mass"]
            .sel(**sel)
            .transpose("omega", "influenced_dof", "radiating_dof")
            .to_numpy()
        )
        b = ds["radiation_damping"].sel(**sel).transpose("omega", "influenced_dof",
                                                         "radiating_dof").to_numpy()
        f = ds["excitation_force"].sel(influenced_dof=dofs).transpose(
            "omega", "wave_direction", "influenced_dof").to_numpy()
        impedance = -w[:, None, None] ** 2 * (m + a) - 1j * w[:, None, None] * b + c
        x = np.linalg.solve(impedance[:, None], f[..., None])[..., 0]  # (omega, heading, dof)
        values = {_CAPYTAINE_DOFS.get(d, d): np.conj(x[:, order, i]).T for i, d in enumerate(dofs)}
        return cls(omega=w, heading=mu[order], values=values, speed=0.0,
                   source=label or "Capytaine dataset")

    def to_table(self):
        """The long table of :meth:`from_table`: ``omega``, ``heading``, ``dof``, ``amplitude``,
        ``phase``.

        ``table.set_index(["omega", "heading", "dof"]).to_xarray()`` is the
        NetCDF layout :meth:`from_table` reads.
        """
        rows = [(w, mu, dof, abs(v), np.angle(v, deg=True))
                for dof, arr in self.values.items() for i, mu in enumerate(self.heading)
                for w, v in zip(self.omega, arr[i])]
        return pd.DataFrame(rows, columns=["omega", "heading", "dof", "amplitude", "phase"])

    # --- evaluation -------------------------------------------------------------------
    def _heading_index(self, heading):
        hit = np.flatnonzero(np.abs(self.heading - heading) < 1e-9)
        return int(hit[0]) if hit.size else None

    def _on(self, array, omega, heading):
        i = self._heading_index(heading)
        if i is not None:
            return _interp_complex(omega, self.omega, array[i])
        if not self.heading[0] <= heading <= self.heading[-1]:
            raise ValueError(f"heading {heading:g} deg lies outside the transfer function's "
                             f"headings {self.heading.min():g}..{self.heading.max():g}; "
                             "give the RAOs at that heading")
        j = int(np.searchsorted(self.heading, heading))
        t = (heading - self.heading[j - 1]) / (self.heading[j] - self.heading[j - 1])
        return ((1 - t) * _interp_complex(omega, self.omega, array[j - 1])
                + t * _interp_complex(omega, self.omega, array[j]))

    def dof(self, name, omega, heading=180.0):
        """Transfer function of a degree of freedom or load at frequencies ``omega``."""
        if name not in self.values:
            raise KeyError(f"no {name!r} in this transfer function ({self.source}); it has "
                           f"{sorted(self.values)}")
        return self._on(self.values[name], np.asarray(omega, dtype=float), heading)

    def vertical_motion(self, omega, heading=180.0, *, x=0.0, y=0.0):
        """``heave + y roll - x pitch`` at the point ``(x, y)`` (roll 0 if absent)."""
        w = np.asarray(omega, dtype=float)
        out = self.dof("heave", w, heading) - x * self.dof("pitch", w, heading)
        if y and "roll" in self.values:
            out = out + y * self.dof("roll", w, heading)
        elif y:
            raise KeyError("a point off the centre line needs roll; this transfer function has "
                           f"{sorted(self.values)}")
        return out

    def relative_elevation(self, omega, heading=180.0, *, x, y=0.0):
        """RWE ``eta(x, y) - w(x, y)`` per unit wave amplitude (deep-water ``k``)."""
        w = np.asarray(omega, dtype=float)
        k = w**2 / self._g
        mu = np.deg2rad(heading)
        incident = np.exp(-1j * k * (x * np.cos(mu) + y * np.sin(mu)))
        return incident - self.vertical_motion(w, heading, x=x, y=y)

    def relative_velocity(self, omega, heading=180.0, *, x, y=0.0):
        """RRV ``i w_e R`` (m/s per m) with the encounter frequency at this ``speed``."""
        w = np.asarray(omega, dtype=float)
        we = encounter_frequency(w, self.speed, heading, g=self._g)
        return 1j * we * self.relative_elevation(w, heading, x=x, y=y)

    def response(self, spec, omega, heading=180.0):
        """Evaluate a response named by ``spec``.

        Parameters
        ----------
        spec : str or tuple
            A dof or load name (``'heave'``, ``'vbm'``), or ``('rwe', x)``,
            ``('rwe', x, y)``, ``('rrv', x)``, ``('rrv', x, y)``.
        """
        if isinstance(spec, str):
            return self.dof(spec, omega, heading)
        kind, *point = spec
        if kind not in ("rwe", "rrv") or not 1 <= len(point) <= 2:
            raise ValueError(f"response must be a dof name or ('rwe'|'rrv', x[, y]); got {spec!r}")
        fn = self.relative_elevation if kind == "rwe" else self.relative_velocity
        return fn(omega, heading, x=point[0], y=point[1] if len(point) > 1 else 0.0)


def _merge_complex(ds):
    """Join Capytaine's split re/im variables (its ``merge_complex_values``) without it."""
    if "complex" not in ds.dims:
        return ds
    out = ds.copy()
    for name in list(out.data_vars):
        da = out[name]
        if "complex" in da.dims:
            out[name] = da.sel(complex="re", drop=True) + 1j * da.sel(complex="im", drop=True)
    return out.drop_vars("complex", errors="ignore")
