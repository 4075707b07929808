"""The stopping rule's noise floor: Ē when the model does not change at all.

Issue 10, cause 2.  App. C's ``E(j)`` is the mean change of the predicted
distribution over ``[P_exp/2, 2 P_exp]`` between iterations.  Redrawing the
``z`` conditional realisations every iteration (Eq. 7 as printed) makes ``E``
positive even when nothing was learnt.  This script fits PAS's model to the
pairs of a finished run, predicts twice from the *same* fit with two random
streams, and prints the change, with and without common random numbers
(each LF peak keeping its own uniforms for the whole study), against the case's
ε1.  Then it reruns the study both ways and prints Ē over the last K1
iterations and the HF count at convergence.

Run: python benchmarks/investigations/noise_floor.py [CASE ...]   (default: 4a-hard 4b-hard 3a)
"""

from __future__ import annotations

import argparse
import warnings

import numpy as np

import pas
from pas.strategies.band import ModelBand
from pas.strategies.base import Pairs
from pas.strategies.pas import PAS
from pas.strategies.screening import LFSet
from pas.strategies.stopping import distribution_change, range_grid
from pas.validation import generate_case


def same_model_change(data, result, crn: bool, repeats: int = 20) -> float:
    """Median E between two predictions of one fitted model (same pairs, same family)."""
    s = LFSet(data.lf, n_waves=data.n_waves, p_exp=data.p_exp, threshold=data.threshold)
    h = result.history
    told = h[h["status"].isin(["true_positive", "false_positive"])]
    pos = np.array([s.position_of(int(i)) for i in told["event_index"]])
    tp = told["status"].to_numpy() == "true_positive"
    pairs = Pairs(pos[tp], s.lf[pos[tp]], told["hf"].to_numpy(float)[tp], s.d[pos[tp]],
                  s.lf[pos[~tp]], pos[~tp])
    grid = range_grid(data.p_exp)
    out = []
    for k in range(repeats):
        st = PAS(common_random_numbers=crn, band=ModelBand(n_bootstrap=0))
        st.reset(k)
        a = st.predict(pairs, s, np.random.default_rng([k, 0])).at(grid)
        b = st.predict(pairs, s, np.random.default_rng([k, 1])).at(grid)
        out.append(distribution_change(a, b))
    return float(np.median(out))


def main(cases):
    for case in cases:
        data = generate_case(case)
        for crn in (False, True):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                res = pas.make_study(PAS(common_random_numbers=crn), data.lf_table(),
                                     **data.run_kwargs(), seed=0,
                                     max_hf=160).optimize(data.oracle())
            h = res.history.dropna(subset=["E_bar"])
            floor = same_model_change(data, res, crn)
            print(f"{case} CRN {'on ' if crn else 'off'}: same-model E {floor:9.3g} "
                  f"(eps1 {data.eps1:g}); run: E_bar at end {h['E_bar'].iloc[-1]:9.3g}, "
                  f"HF {res.n_hf}, converged {res.converged}", flush=True)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="*", default=["4a-hard", "4b-hard", "3a"])
    main(ap.parse_args().cases)
