"""Figures of :func:`pas.validation.reproduce`, drawn with :mod:`pas.plotting.figures`.

Per case ``<case>.png`` with four panels — MPM against the number of HF
samples with the truth line (paper Fig. 6/7 top), the final exceedance
distributions with bands and the truth (Fig. 6/7 bottom), the LF–HF scatter
with τ and tail dependence (Fig. 16) — and ``metrics.png``, the M1/M2/M3 bars
of all cases (Fig. 8).
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["write_figures"]


def write_figures(out, datasets, results, table) -> list[Path]:
    """Write the figures into ``out``; returns the paths."""
    import matplotlib.pyplot as plt

    from ..plotting.figures import (plot_distribution, plot_metrics, plot_mpm_convergence,
                                    plot_scatter)
    from .registry import get_case

    out = Path(out)
    files = []
    for cid, data in datasets.items():
        spec = get_case(cid)
        fig, axes = plt.subplots(1, 3, figsize=(17, 5), constrained_layout=True)
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
        fig.savefig(path, dpi=90)
        plt.close(fig)
        files.append(path)
    fig, _ = plot_metrics(table.assign(strategy=table["strategy"].str.lower()))
    path = out / "metrics.png"
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return files + [path]
