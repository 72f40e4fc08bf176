"""Cumulative pore-size distribution P(r_P > r) with its confidence band and the fit of
eq. 6 (doh-elastic-properties), from the ``pore_size.csv`` written by ``packlab analyze``."""

import math

from packlab.plot._common import argument, new_figure, read_csv, run


def figure(pore_csv, a=None, b=None, r0=None, fit_min=None, fit_max=None):
    data = read_csv(pore_csv)
    r, p = data["r"], data["probability"]
    fig, ax = new_figure()
    if "band_low" in data and "band_high" in data:
        ax.fill_between(r, data["band_low"], data["band_high"], color="C0", alpha=0.25, lw=0,
                        label="95 % band (uniform)")
    ax.plot(r, p, "C0-", lw=1.5, label="measured")
    if a is not None and b is not None and r0:
        x = r / r0
        fit = [1.0 - math.erf((xi - b) / (a * math.sqrt(2.0))) for xi in x]
        ax.plot(r, fit, "C3--", lw=1.2, label=f"eq. 6: a = {a:.3f}, b = {b:.3f}")
        if fit_min is not None and fit_max is not None:
            ax.axvspan(fit_min, fit_max, color="0.9", zorder=0, label="fit range")
    ax.set_xlim(0, r[-1] if len(r) else 1)
    ax.set_ylim(0, 1.05)
    ax.set_xlabel("r (distance to the nearest particle surface)")
    ax.set_ylabel(r"$P(r_P > r)$")
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title("pore-size distribution")
    return fig


def main(argv):
    return run("pore_size", argv, figure, argument("pore_csv"), argument("--a", type=float),
               argument("--b", type=float), argument("--r0", type=float), argument("--fit-min", type=float),
               argument("--fit-max", type=float))
