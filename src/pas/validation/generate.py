"""Generate (and cache) the data set of a validation case.

``generate_case("1a")`` runs the case's physics for the paper's full duration
(or ``scale`` of it, with ``n_w`` scaled alike), computes the ground truth from
the full HF set and the LF–HF dependence, and caches the result as
``<cache>/<case>_seed<seed>_scale<scale>_<key>.npz``; ``key`` hashes the code
version and the frozen model coefficients, so a change of either regenerates.
The cache directory is ``$PAS_CACHE`` or ``./pas-cache``.
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

import numpy as np

from .._version import __version__
from . import case_impacts, case_impacts_hard, case_vbm, case_waves
from ._common import seed_plan
from .data import CaseData, dependence, ground_truth
from .registry import get_case

__all__ = ["generate_case", "cache_dir", "cache_path"]


def cache_dir(path=None) -> Path:
    """The cache directory: ``path``, else ``$PAS_CACHE``, else ``./pas-cache``."""
    return Path(path or os.environ.get("PAS_CACHE") or "pas-cache")


def _impact_module(spec):
    return case_impacts_hard if spec.variant == "hard" else case_impacts


def _model_key(case_id):
    spec = get_case(case_id)
    fam = spec.family
    if fam in "34":
        mod = _impact_module(spec)
        model = (mod.VERSION, mod.COEFFICIENTS)
    else:
        model = {"1": (case_waves.VERSION, case_waves.NOISE),
                 "2": (case_vbm.VERSION, case_vbm.COEFFICIENTS)}[fam]
    blob = json.dumps([__version__, model], sort_keys=True, default=str)
    return hashlib.sha1(blob.encode()).hexdigest()[:10]


def cache_path(case_id, seed=0, scale=1.0, path=None) -> Path:
    """Where :func:`generate_case` caches ``case_id`` for this seed and scale."""
    spec = get_case(case_id)
    return (
        cache_dir(path)
        / f"{spec.id}_seed{int(seed)}_scale{float(scale):g}_{_model_key(spec.id)}.npz"
    )


def _events(spec, seed, n_seeds, duration, n_waves):
    fam = spec.family
    if fam == "1":
        return case_waves.generate_case1(spec, seed, n_seeds, duration, n_waves,
                                         noise=spec.id == "1b")
    if fam == "2":
        return case_vbm.generate_case2(spec, seed, n_seeds, duration,
                                       mode="hog" if spec.id == "2a" else "sag")
    if fam == "3":
        return _impact_module(spec).generate_green_water(spec, seed, n_seeds, duration)
    return _impact_module(spec).generate_slamming(spec, seed, n_seeds, duration)


def build_case(case_id, *, seed=0, scale=1.0) -> CaseData:
    """Run the physics of ``case_id`` (no cache); see :func:`generate_case`."""
    spec = get_case(case_id)
    n_seeds, duration = seed_plan(spec.t_mcs, scale)
    n_waves = max(1, int(round(spec.n_waves * scale)))
    ev, info = _events(spec, seed, n_seeds, duration, n_waves)
    if 1.0 / n_waves > spec.p_exp:
        raise ValueError(
            f"scale={scale:g} leaves n_w={n_waves}, too few waves to reach "
            f"P_exp={spec.p_exp:g}; use scale >= {1.5 / (spec.n_waves * spec.p_exp):.2g}"
        )
    mpm, d, h, extra = ground_truth(ev["hf"], n_waves, spec.p_exp, spec.truth_method)
    tau, lu, ll = dependence(ev["lf"], ev["hf"], spec.threshold)
    hf = ev["hf"]
    info.update(extra)
    info.update({"n_seeds": n_seeds, "seed_duration_s": duration, "n_events": int(hf.size),
                 "impact_rate": float(np.sum(hf > 0) / n_waves) if spec.family in "34" else None,
                 "n_lf_over_threshold": int(np.sum(ev["lf"] > spec.threshold))
                 if spec.threshold is not None else int(hf.size)})
    ids = np.array([f"{spec.id}-s{s:03d}-w{i:05d}" for s, i in
                    zip(ev["seed_no"], _wave_numbers(ev["seed_no"]))])
    return CaseData(case=spec.id, lf=ev["lf"], hf=hf, ids=ids, seed_no=ev["seed_no"],
                    t_start=ev["t_start"], t_end=ev["t_end"], n_waves=n_waves,
                    p_exp=spec.p_exp, threshold=spec.threshold, eps1=spec.eps1, unit=spec.unit,
                    truth_mpm=mpm, truth_d=d, truth_h=h, tau=tau, lambda_u=lu, lambda_l=ll,
                    seed=int(seed), scale=float(scale), info=_jsonable(info))


def _wave_numbers(seed_no):
    """0-based wave number inside its realisation."""
    s = np.asarray(seed_no)
    start = np.flatnonzero(np.r_[True, s[1:] != s[:-1]])
    return np.arange(s.size) - np.repeat(start, np.diff(np.r_[start, s.size]))


def _jsonable(obj):
    return json.loads(
        json.dumps(obj, default=lambda o: o.tolist() if hasattr(o, "tolist") else str(o))
    )


def generate_case(case_id, *, seed=0, scale=1.0, cache=True, path=None) -> CaseData:
    """The :class:`~pas.validation.data.CaseData` of a case, from the cache when present.

    Parameters
    ----------
    case_id : str
        ``"1a"`` … ``"4b"``, ``"3a-hard"`` … ``"4b-hard"``.
    seed : int, default 0
        Seed of the wave phases and of the random parts of the HF model.
    scale : float, default 1.0
        Fraction of the paper's duration (``n_w`` scaled alike), e.g. 0.1 for
        quick runs.
    cache : bool, default True
        Read and write the ``.npz`` cache.
    path : str or Path, optional
        Cache directory (default ``$PAS_CACHE`` or ``./pas-cache``).

    Returns
    -------
    CaseData

    Examples
    --------
    >>> from pas.validation import generate_case
    >>> data = generate_case("1a", scale=0.05, cache=False)
    >>> data.lf.shape == data.hf.shape, bool(data.tau > 0.8)
    (True, True)
    """
    file = cache_path(case_id, seed, scale, path)
    if cache and file.exists():
        try:
            return CaseData.load(file)
        except (OSError, ValueError, KeyError):
            pass  # unreadable cache entry: regenerate
    data = build_case(case_id, seed=seed, scale=scale)
    if cache:
        file.parent.mkdir(parents=True, exist_ok=True)
        tmp = file.with_suffix(".tmp.npz")
        data.save(tmp)
        os.replace(tmp, file)
    return data
