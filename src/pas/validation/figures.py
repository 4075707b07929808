"""Figures of :func:`pas.validation.reproduce`, drawn with :mod:`pas.plotting.figures`.

Per case ``case_<case>.png`` with three panels — MPM against the number of HF
samples with the truth line (paper Fig. 6/7 top), the final exceedance
distributions with bands and the truth (Fig. 6/7 bottom; design waves as one
point per level), the LF–HF scatter with τ and tail dependence (Fig. 16) — and
``metrics.png``, the M1/M2/M3 bars of all cases (Fig. 8).  Each panel's legend
sits under it, at 8 pt, covering no curve.  With a design-wave result, ``design_<case>.png``: the
HF exceedance curves of the truth, PAS and AS with the RCW (and MLER) points
(Dermatis et al. 2025, Fig. 14) and, where HF and the conditioned linear
response are the same quantity (cases 1–2), ``f_NL`` against the linear
response (their Fig. 15).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["write_figures"]

_DPI = 100
"""Pixels per inch of the PNG files: the 8 pt legend text is 11 px high at 100 % zoom."""


def write_figures(out, datasets, results, table) -> list[Path]:
    """Write the figures into ``out``; returns the paths."""
    import matplotlib.pyplot as plt

    from ..plotting.figures import (
        plot_distribution,
        plot_metrics,
        plot_mpm_convergence,
        plot_scatter,
    )
    from .registry import get_case

    out = Path(out)
    files = []
    for cid, data in datasets.items():
        spec = get_case(cid)
        fig, axes = plt.subplots(1, 3, figsize=(17, 7.5), constrained_layout=True)
        strat = [(s, r) for (c, s), r in results.items() if c == cid]
        for s, res in strat:
            plot_mpm_convergence(res, truth=data.truth_mpm if s == strat[0][0] else None,
                                 ax=axes[0], unit=data.unit)
            plot_distribution(res, truth=(data.truth_d, data.truth_h) if s == strat[0][0]
                              else None, ax=axes[1], unit=data.unit, quantity=spec.hf_variable)
        pas_res = dict(strat).get("pas")
        plot_scatter(data.lf, data.hf, result=pas_res, ax=axes[2], unit=data.unit,
                     lf_label=spec.lf_indicator, hf_label=spec.hf_variable)
        fig.suptitle(f"Case {cid} (synthetic analogue): {spec.hf_variable} from "
                     f"{spec.lf_indicator}; truth MPM {data.truth_mpm:.4g} {data.unit}, "
                     f"paper {spec.paper_truth:.4g}")
        path = out / f"case_{cid}.png"
        fig.savefig(path, dpi=_DPI)
        plt.close(fig)
        files.append(path)
        if any(s in ("rcw", "mler") for s, _ in strat):
            files.append(_design_figure(out, cid, data, dict(strat)))
    fig, _ = plot_metrics(table.assign(strategy=table["strategy"].str.lower()))
    path = out / "metrics.png"
    fig.savefig(path, dpi=_DPI)
    plt.close(fig)
    return files + [path]


def _design_figure(out, cid, data, results) -> Path:
    """``design_<case>.png``: Fig. 14 (and for cases 1–2 Fig. 15) of Dermatis et al. (2025)."""
    import matplotlib.pyplot as plt

    from ..plotting.design import plot_design_points, plot_nonlinear_factor
    from ..plotting.figures import plot_distribution
    from ..stats.exceedance import exceedance_probabilities
    from .registry import get_case

    spec = get_case(cid)
    same_quantity = spec.family in "12"
    fig, axes = plt.subplots(1, 2 if same_quantity else 1,
                             figsize=(13 if same_quantity else 7, 6.5),
                             constrained_layout=True, squeeze=False)
    ax = axes[0, 0]
    truth = (data.truth_d, data.truth_h)
    screening = [(s, r) for s, r in results.items() if s in ("pas", "as")]
    for k, (s, res) in enumerate(screening):
        plot_distribution(res, truth=truth if k == 0 else None, ax=ax, unit=data.unit,
                          quantity=spec.hf_variable, show_samples=False)
    if not screening:
        ax.plot(*truth, "k--", lw=1.2, label="truth (HF Monte-Carlo)")
    design = [(s, results[s]) for s in ("rcw", "mler") if s in results]
    for k, (s, res) in enumerate(design):
        plot_design_points(res, ax=ax, unit=data.unit, quantity=spec.hf_variable,
                           marker="o" if s == "rcw" else "s",
                           show_p_exp=not screening and k == 0)
    lv = np.concatenate([r.distribution["exceedance_probability"].to_numpy() for _, r in design])
    lo, hi = lv.min() / 3, lv.max() * 3
    ax.set_xlim(hi, lo)
    seen = [r.distribution["h_mean"].to_numpy() for _, r in design]
    for d, h in [truth] + [(r.distribution["exceedance_probability"].to_numpy(),
                            r.distribution["h_mean"].to_numpy()) for _, r in screening]:
        seen.append(np.asarray(h)[(np.asarray(d) >= lo) & (np.asarray(d) <= hi)])
    seen = np.concatenate(seen)
    seen = seen[np.isfinite(seen)]
    span = seen.max() - seen.min()
    ax.set_ylim(seen.min() - 0.08 * span, seen.max() + 0.08 * span)
    ax.set_title("HF exceedance: truth, PAS, AS and one design wave per level")
    if same_quantity:
        lf = exceedance_probabilities(data.lf, data.n_waves)
        for k, (s, res) in enumerate(design):
            plot_nonlinear_factor(res, lf=lf if k == 0 else None, truth=truth if k == 0 else None,
                                  ax=axes[0, 1], unit=data.unit,
                                  marker="o" if s == "rcw" else "s")
        axes[0, 1].set_title("non-linear factor against the linear response")
    fig.suptitle(f"Case {cid} (synthetic analogue): design waves beside PAS and AS")
    path = Path(out) / f"design_{cid}.png"
    fig.savefig(path, dpi=_DPI)
    plt.close(fig)
    return path
