"""Storage modulus against the degree of heterogeneity (doh-elastic-properties Fig. 6) with the
power law G' = C (a - a0)^beta (eq. 7). The CSV has columns ``a``, ``storage_modulus`` [Pa],
``std`` [Pa] and optionally ``label`` (points with the same label share a marker, e.g. "this
work" and "paper"); the fit uses the rows whose label is ``--fit-label`` (all when not given;
several labels separated by ``|``)."""

import numpy as np

from packlab.plot._common import argument, new_figure, read_csv, run


def fit_power_law(a, g, a0_bounds=None):
    """Least-squares fit of g = C (a - a0)^beta: scans a0 below min(a), log-linear fit for each."""
    a = np.asarray(a, float)
    g = np.asarray(g, float)
    lo, hi = a0_bounds if a0_bounds else (min(a) - 0.5 * (max(a) - min(a)), min(a) - 1e-6)
    best = None
    for a0 in np.linspace(lo, hi, 4000):
        x = np.log(a - a0)
        beta, logc = np.polyfit(x, np.log(g), 1)
        r = np.sum((np.exp(logc) * (a - a0) ** beta - g) ** 2)
        if best is None or r < best[0]:
            best = (r, a0, beta, np.exp(logc))
    return {"a0": best[1], "beta": best[2], "prefactor": best[3], "residual": best[0]}


def figure(table_csv, fit_label=None):
    data = read_csv(table_csv)
    labels = data.get("label", ["data"] * len(data["a"]))
    fig, ax = new_figure(5.5, 3.8)
    markers = ["o", "^", "s", "D"]
    for k, name in enumerate(dict.fromkeys(labels)):
        m = np.array([lab == name for lab in labels])
        ax.errorbar(data["a"][m], data["storage_modulus"][m] / 1e6, yerr=data["std"][m] / 1e6, fmt=markers[k % 4],
                    mfc="none", capsize=3, label=name)
    fitted = None if fit_label is None else fit_label.split("|")
    m = np.array([fitted is None or lab in fitted for lab in labels])
    if m.sum() >= 3:
        f = fit_power_law(data["a"][m], data["storage_modulus"][m])
        x = np.linspace(f["a0"] + 1e-4, max(data["a"]) * 1.02, 300)
        ax.plot(x, f["prefactor"] * (x - f["a0"]) ** f["beta"] / 1e6, "k-",
                label=f"fit: $a_0$ = {f['a0']:.3f}, $\\beta$ = {f['beta']:.2f}")
        ax.axvline(f["a0"], color="k", ls="--", lw=0.8)
    ax.set_xlabel("degree of heterogeneity $a$")
    ax.set_ylabel("$G'$ [MPa]")
    ax.legend(fontsize=8)
    return fig


def main(argv):
    return run("storage_modulus", argv, figure, argument("table_csv"), argument("--fit-label", default=None))
