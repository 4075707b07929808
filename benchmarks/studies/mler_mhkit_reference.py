"""Write ``tests/data/mler_mhkit.json``: MLER coefficients from mhkit, the peer check of
:func:`pas.waves.design.mler_amplitudes` (``tests/strategies/test_design_waves.py``).

mhkit (1.1.2) pulls in xarray, netCDF4, statsmodels, scikit-learn, fatpack and
more (~0.7 GB), so the test suite does not install it: this script, run once in
a separate environment, stores mhkit's numbers with the inputs it was given.
The inputs are built here with plain numpy, independently of ``pas``.

    python3 -m venv /tmp/venv-mhkit && . /tmp/venv-mhkit/bin/activate
    pip install mhkit==1.1.2 statsmodels scikit-learn fatpack
    python benchmarks/studies/mler_mhkit_reference.py   # rewrites tests/data/mler_mhkit.json

Conventions of ``mhkit.loads.extreme.mler_coefficients`` (read from its source):
the spectrum is given in m^2/Hz on a frequency index in Hz and converted to
rad/s; the step is taken as ``d_w = 2 pi / (N - 1)``, i.e. the grid must span
exactly 1 Hz, so both grids below run from 0 to 1 Hz; the output
``WaveSpectrum`` (m^2 s/rad) and ``Phase`` (rad) describe the episode
``sum sqrt(2 WaveSpectrum d_w) cos(w (t - T0) + Phase)``.
"""

import argparse
import json
from importlib.metadata import version
from pathlib import Path

import numpy as np
import pandas as pd


def pierson_moskowitz_hz(f, hs, tp):
    """Bretschneider/PM spectrum in m^2/Hz (DNV-RP-C205 Eq. 3.5.5.1 times 2 pi)."""
    w, wp = 2 * np.pi * f, 2 * np.pi / tp
    s = np.zeros_like(f)
    pos = w > 0
    s[pos] = 5 / 16 * hs**2 * wp**4 * w[pos] ** -5 * np.exp(-1.25 * (wp / w[pos]) ** 4)
    return 2 * np.pi * s


def jonswap_hz(f, hs, tp, gamma):
    """JONSWAP with the shape normalised numerically to 4 sqrt(m0) = hs, m^2/Hz."""
    fine = np.linspace(1e-4, 5.0, 400_001)

    def shape(ff):
        out = np.zeros_like(ff)
        pos = ff > 0
        x = ff[pos] * tp
        sig = np.where(x <= 1, 0.07, 0.09)
        out[pos] = (
            ff[pos] ** -5 * np.exp(-1.25 * x**-4) * gamma ** np.exp(-((x - 1) ** 2) / (2 * sig**2))
        )
        return out

    return hs**2 / 16 * shape(f) / np.trapezoid(shape(fine), fine)


def oscillator_rao(w, wn, zeta, lag):
    """A damped single-degree oscillator with a time lag: complex, phase varies."""
    r = w / wn
    return np.exp(-1j * w * lag) / (1 - r**2 + 2j * zeta * r)


CASES = {
    "pm_oscillator": dict(
        f=np.linspace(0.0, 1.0, 257),
        spectrum=lambda f: pierson_moskowitz_hz(f, 8.0, 10.0),
        rao=lambda w: oscillator_rao(w, 0.7, 0.15, 1.3),
        target=3.0,
    ),
    "jonswap_lagged": dict(
        f=np.linspace(0.0, 1.0, 401),
        spectrum=lambda f: jonswap_hz(f, 13.2, 10.0, 3.0),
        rao=lambda w: 2.5 * np.exp(-0.4 * w) * oscillator_rao(w, 0.9, 0.3, -4.0),
        target=12.5,
    ),
}


def main():
    from mhkit.loads.extreme import mler_coefficients  # a separate environment (module docs)

    out = {"mhkit_version": version("mhkit"), "cases": {}}
    for name, c in CASES.items():
        f = c["f"]
        s_hz = c["spectrum"](f)
        rao = c["rao"](2 * np.pi * f)
        mler = mler_coefficients(rao, pd.Series(s_hz, index=pd.Index(f, name="frequency")),
                                 float(c["target"]))
        out["cases"][name] = {
            "frequency_hz": f.tolist(), "spectrum_m2_per_hz": s_hz.tolist(),
            "rao_real": rao.real.tolist(), "rao_imag": rao.imag.tolist(), "target": c["target"],
            "omega": mler.index.to_numpy().tolist(),
            "wave_spectrum": mler["WaveSpectrum"].to_numpy().tolist(),
            "phase": mler["Phase"].to_numpy().tolist(),
            "d_w": 2 * np.pi / (f.size - 1),
        }
    path = Path(__file__).resolve().parents[2] / "tests" / "data" / "mler_mhkit.json"
    path.write_text(json.dumps(out, indent=0))
    print(f"wrote {path} (mhkit {out['mhkit_version']})")


if __name__ == "__main__":
    argparse.ArgumentParser(description=__doc__,
                            formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    main()
