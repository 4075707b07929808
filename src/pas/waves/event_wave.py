"""The wave of one LF event, as a wave maker of an HF tool reads it.

An HF run of an event (CFD, a basin test) has to meet the same linear waves
the LF record met at the structure, from its own inlet and its own start
time.  :func:`event_wave` takes the linear components of the LF record's sea
and refers them to a point ``upwave`` metres up-wave of the structure (a CFD
inlet, a basin's wave maker) and to a start time ``t_start`` of the LF
record, so that time 0 of the HF run is ``t_start`` of the record; waves
travel from that point towards the structure (the +x direction of a tank).

Conventions
-----------
Component ``j`` has angular frequency ``omega_j``, the finite-depth wave
number ``k_j`` (``omega^2 = g k tanh(k h)``), amplitude ``a_j`` and phase
``phase_j``; at distance ``x`` from the reference point (the inlet), down-wave,
and run time ``t``

``eta(x, t) = sum_j a_j cos(omega_j t - k_j x + phase_j)``.

At the structure (``x = upwave``) this is the LF record's linear surface at
record time ``t_start + t``.  OpenFOAM's ``irregularMultiDirectional`` model
writes ``(H/2) cos(k x - omega t + psi)``, so its phase is ``psi = -phase``
(:meth:`EventWave.openfoam_dict`).

Cutting components (``energy=`` below 1) keeps the fewest largest
components that hold that share of the variance; :meth:`EventWave.cut_effect`
says what the cut does to the event's linear crest and its time.
"""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np

from .spectra import GRAVITY, wave_number

__all__ = ["EventWave", "event_wave"]


@dataclass(frozen=True)
class EventWave:
    """Linear components of one event, referred to an inlet and a start time.

    Attributes
    ----------
    omega, wave_number, amplitude, phase : ndarray
        Per component (rad/s, rad/m, m, rad), as in the module's convention.
    depth : float
        Water depth (m) of the wave numbers.
    upwave : float
        Distance from the reference point (inlet) to the structure (m).
    t_start : float
        LF-record time of run time 0 (s).
    t_peak : float
        LF-record time of the event's crest at the structure (s).
    energy : float
        Share of the record's variance the components hold.
    """

    omega: np.ndarray
    wave_number: np.ndarray
    amplitude: np.ndarray
    phase: np.ndarray
    depth: float
    upwave: float
    t_start: float
    t_peak: float
    energy: float = 1.0

    @property
    def n_components(self) -> int:
        return int(self.omega.size)

    @property
    def t_event(self) -> float:
        """Run time at which the event's linear crest reaches the structure (s)."""
        return self.t_peak - self.t_start

    def elevation(self, t, x=None, *, chunk=2048):
        """Linear elevation at run times ``t`` (s) and distance ``x`` from the inlet
        (default: at the structure)."""
        t = np.atleast_1d(np.asarray(t, float))
        x = self.upwave if x is None else float(x)
        amp = self.amplitude * np.exp(1j * (self.phase - self.wave_number * x))
        out = np.empty(t.size)
        for s in range(0, t.size, chunk):
            out[s:s + chunk] = (np.exp(1j * np.outer(t[s:s + chunk], self.omega)) @ amp).real
        return out

    def time_series(self, duration, dt=0.05):
        """``t``, ``eta_inlet`` and ``eta_structure`` over the run as a DataFrame."""
        import pandas as pd

        t = np.arange(0.0, float(duration) + 0.5 * dt, dt)
        return pd.DataFrame({"t": t, "eta_inlet": self.elevation(t, 0.0),
                             "eta_structure": self.elevation(t)})

    def crest(self, *, window=None, dt=0.02):
        """The linear crest at the structure nearest the event: ``(height m, run time s)``.

        Searched within ``window`` (s) around :attr:`t_event` (default half the
        mean period of the components, weighted by energy).
        """
        if window is None:
            m0 = np.sum(self.amplitude ** 2)
            window = 0.5 * np.pi * m0 / max(np.sum(self.amplitude ** 2 * self.omega), 1e-12)
        t = np.arange(self.t_event - window, self.t_event + window + dt, dt)
        eta = self.elevation(t)
        i = int(np.argmax(eta))
        if 0 < i < t.size - 1:                      # parabola through the top three samples
            y0, y1, y2 = eta[i - 1:i + 2]
            den = y0 - 2 * y1 + y2
            off = 0.5 * (y0 - y2) / den if den < 0 else 0.0
            return float(y1 - 0.25 * (y0 - y2) * off), float(t[i] + off * dt)
        return float(eta[i]), float(t[i])

    def cut(self, energy):
        """The fewest largest components holding ``energy`` (0-1] of this wave's variance."""
        if not 0.0 < energy <= 1.0:
            raise ValueError(f"energy must be in (0, 1], got {energy!r}; e.g. energy=0.99")
        var = self.amplitude ** 2
        order = np.argsort(var)[::-1]
        share = np.cumsum(var[order]) / var.sum()
        n = int(np.searchsorted(share, energy * (1.0 - 1e-12))) + 1
        keep = np.sort(order[:n])
        return EventWave(self.omega[keep], self.wave_number[keep], self.amplitude[keep],
                         self.phase[keep], self.depth, self.upwave, self.t_start, self.t_peak,
                         self.energy * float(share[n - 1]))

    def cut_effect(self, energy):
        """What :meth:`cut` does to the event: crest and its time before and after."""
        full, (c1, t1) = self.crest(), self.cut(energy).crest()
        return {"energy": energy, "n_components": self.cut(energy).n_components,
                "crest": full[0], "crest_cut": c1, "crest_error": c1 / full[0] - 1.0,
                "time_shift": t1 - full[1]}

    def components(self):
        """One row per component: ``omega``, ``wave_number``, ``period``, ``amplitude``,
        ``height`` (``2 a``) and ``phase`` (module convention) as a DataFrame."""
        import pandas as pd

        return pd.DataFrame({"omega": self.omega, "wave_number": self.wave_number,
                             "period": 2 * np.pi / self.omega, "amplitude": self.amplitude,
                             "height": 2 * self.amplitude, "phase": self.phase})

    def to_json(self, path=None):
        """The wave as JSON (components and references); written to ``path`` if given."""
        doc = {"convention": "eta(x, t) = sum a cos(omega t - k x + phase); x from the inlet, "
                             "t from t_start of the LF record",
               "depth": self.depth, "upwave": self.upwave, "t_start": self.t_start,
               "t_peak": self.t_peak, "t_event": self.t_event, "energy": self.energy,
               "components": {c: [float(v) for v in getattr(self, c)]
                              for c in ("omega", "wave_number", "amplitude", "phase")}}
        text = json.dumps(doc, indent=1)
        if path is not None:
            with open(path, "w") as f:
                f.write(text)
        return text

    def openfoam_dict(self, *, patch="inlet", ramp_time=2.0, absorption=True,
                      outlet="outlet"):
        """A ``constant/waveProperties`` dictionary for OpenFOAM's
        ``irregularMultiDirectional`` model (v1912 and later), long-crested.

        ``patch`` is the generating patch; ``outlet``, if not None, gets the
        ``shallowWaterAbsorption`` model.  OpenFOAM takes the water depth from
        the initial ``alpha.water`` on the patch.
        """
        def rows(values):
            return "\n".join(f"        ({v:.10g})" for v in values)

        n = self.n_components
        psi = np.mod(-self.phase, 2 * np.pi)
        text = [
            "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
            "    location \"constant\";\n    object waveProperties;\n}\n",
            f"// event wave: t_start {self.t_start:.6g} s of the LF record, crest at the "
            f"structure at run time {self.t_event:.6g} s, {self.upwave:g} m down-wave\n",
            f"{patch}\n{{\n    alpha alpha.water;\n    waveModel irregularMultiDirectional;\n"
            f"    nPaddle 1;\n    rampTime {ramp_time:g};\n"
            f"    activeAbsorption {'yes' if absorption else 'no'};\n",
        ]
        for key, values in (("wavePeriods", 2 * np.pi / self.omega),
                            ("waveHeights", 2 * self.amplitude),
                            ("wavePhases", psi), ("waveDirs", np.zeros(n))):
            text.append(f"    {key}\n    {n}\n    (\n{rows(values)}\n    );\n")
        text.append("}\n")
        if outlet is not None:
            text.append(f"{outlet}\n{{\n    alpha alpha.water;\n"
                        "    waveModel shallowWaterAbsorption;\n    nPaddle 1;\n}\n")
        return "".join(text)


def event_wave(sea, t_peak, *, upwave, lead, depth=None, energy=1.0, x=0.0, g=GRAVITY):
    """The event at LF-record time ``t_peak`` as an :class:`EventWave`.

    Parameters
    ----------
    sea : LinearSea or ComponentSea
        The LF record's linear sea (e.g. ``linear_sea(spectrum, duration,
        seed=event.meta["seed"], depth=...)``), at rest (no forward speed).
    t_peak : float
        LF-record time of the event's crest at the structure (s).
    upwave : float
        Distance from the HF tool's inlet (wave maker) to the structure (m).
    lead : float
        Run time before ``t_peak`` at which the HF run starts (s): the run's
        ``t_start = t_peak - lead``.  Leave room for the ramp and for the
        waves to travel ``upwave``.
    depth : float, optional
        Water depth (m) for the wave numbers; default the sea's.
    energy : float, default 1.0
        Keep the fewest largest components holding this share of the variance.
    x : float, default 0
        Position of the structure in the sea's frame (m along the wave direction).
    """
    if not np.isfinite(upwave) or upwave < 0:
        raise ValueError(f"upwave must be a distance >= 0 in metres, got {upwave!r}")
    if not np.isfinite(lead) or lead <= 0:
        raise ValueError(f"lead must be a positive time in seconds, got {lead!r}")
    if getattr(sea, "speed", 0.0):
        raise ValueError("sea: event_wave refers components to a fixed inlet; give the sea "
                         "at rest (speed=0)")
    depth = float(getattr(sea, "depth", np.inf) if depth is None else depth)
    amp = sea.amplitude_at(x) if hasattr(sea, "amplitude_at") else np.asarray(sea.amplitude)
    keep = np.abs(amp) > 0
    omega = np.asarray(sea.omega, float)[keep]
    amp = amp[keep]
    k = wave_number(omega, depth, g=g)
    t_start = float(t_peak) - float(lead)
    # at the structure: Re A exp(i w t_rec); t_rec = t_start + t; x = upwave at the structure
    phase = np.angle(amp) + omega * t_start + k * upwave
    wave = EventWave(omega, k, np.abs(amp), np.mod(phase, 2 * np.pi), depth, float(upwave),
                     t_start, float(t_peak))
    return wave if energy >= 1.0 else wave.cut(energy)
