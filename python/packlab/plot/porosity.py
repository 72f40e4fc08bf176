"""Young's modulus and strength against porosity with the fitted laws (bpm-inverse-opals
eq. 22-26). Reads a CSV with columns porosity, youngs_modulus, strength (one row per sample)
and optional fit parameters."""

from packlab.plot._common import argument, read_csv, run, subplots


def figure(samples_csv, e0=0.0, b=0.0, m=0.0, s0=0.0, bs=0.0):
    import numpy as np

    data = read_csv(samples_csv)
    fig, (ax1, ax2) = subplots(1, 2, width=9.0)
    eps = data["porosity"]
    ax1.plot(eps, data["youngs_modulus"] * 1e-9, "ko", ms=4, label="BPM samples")
    x = np.linspace(0.0, max(eps.max(), 0.75), 100)
    if e0 > 0:
        ax1.plot([0.0], [e0 * 1e-9], "ks", mfc="none", ms=6, label="pore-free sample (E0)")
    if e0 > 0 and b > 0:
        ax1.plot(x, e0 * np.exp(-b * x) * 1e-9, "C0--", label=f"E0 exp(-{b:.3g} eps) (eq. 22)")
    if e0 > 0 and m > 0:
        ax1.plot(x, e0 * (1 - x) ** m * 1e-9, "C1-", label=f"E0 (1-eps)^{m:.3g} (eq. 23)")
    ax1.set_xlabel("porosity eps")
    ax1.set_ylabel("Young's modulus [GPa]")
    ax1.legend(fontsize=7)
    ax2.plot(eps, data["strength"] * 1e-6, "ko", ms=4, label="BPM samples")
    if s0 > 0 and bs > 0:
        ax2.plot(x, s0 * np.exp(-bs * x) * 1e-6, "C2-", label=f"{s0 * 1e-6:.4g} exp(-{bs:.3g} eps) MPa (eq. 26)")
    ax2.set_xlabel("porosity eps")
    ax2.set_ylabel("compressive strength [MPa]")
    ax2.legend(fontsize=7)
    return fig


def main(argv):
    return run("porosity", argv, figure, argument("samples_csv"), argument("--e0", type=float, default=0.0),
               argument("--b", type=float, default=0.0), argument("--m", type=float, default=0.0),
               argument("--s0", type=float, default=0.0), argument("--bs", type=float, default=0.0))
