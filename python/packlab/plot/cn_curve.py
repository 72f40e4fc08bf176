"""CN(q) curve of the void expansion method (the ``cn_curve.csv`` written by ``packlab
generate vem``): mean coordination number of the structural particles against q = r_V/r_S,
the inflection point and its tangent, and the strain energy on a second axis.

Several CSV files can be given (one curve each, e.g. the n-study); the inflection point is
marked when ``--qi``, ``--cni`` and ``--slope`` are given (for the first curve)."""

import os

from packlab.plot._common import argument, new_figure, read_csv, run


def figure(csv_paths, qi=None, cni=None, slope=None, labels=None, energy=True):
    import numpy as np

    if isinstance(csv_paths, (str, os.PathLike)):
        csv_paths = [csv_paths]
    fig, ax = new_figure()
    ax2 = ax.twinx() if energy else None
    for k, path in enumerate(csv_paths):
        data = read_csv(path)
        label = labels[k] if labels and k < len(labels) else (os.path.basename(os.path.dirname(os.path.abspath(path)))
                                                              if len(csv_paths) > 1 else "CN")
        ax.plot(data["q"], data["cn"], "o-", ms=2.5, lw=0.8, color=f"C{k}", label=label)
        if ax2 is not None:
            e = np.asarray(data["strain_energy"], dtype=float)
            q = np.asarray(data["q"], dtype=float)
            positive = e > 0
            if positive.any():
                ax2.semilogy(q[positive], e[positive], ":", lw=0.8, color=f"C{k}")
    if qi is not None and cni is not None:
        ax.plot([qi], [cni], "k*", ms=10, zorder=5, label=f"inflection q_i={qi:.3f}, CN_i={cni:.2f}")
        if slope is not None:
            half = 1.0 / max(slope, 1e-12)
            xs = np.array([qi - half, qi + half])
            ax.plot(xs, cni + slope * (xs - qi), "k--", lw=0.8, label=f"slope {slope:.1f}")
    ax.set_xlabel("q = r_V / r_S")
    ax.set_ylabel("mean coordination number CN (structural)")
    if ax2 is not None:
        ax2.set_ylabel("strain energy [J] (dotted)")
    ax.legend(loc="upper left", fontsize=7)
    ax.set_title("void expansion method")
    return fig


def main(argv):
    return run("cn_curve", argv, figure, argument("csv", nargs="+"), argument("--qi", type=float),
               argument("--cni", type=float), argument("--slope", type=float), argument("--labels", nargs="*"),
               argument("--no-energy", dest="energy", action="store_false"))
