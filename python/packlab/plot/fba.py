"""Force-biased algorithm convergence: the largest relative overlap at the target diameters and
the nominal (outer) diameter against the iteration (the ``fba_log.csv`` written by
``packlab generate fba``); the dashed line is the stop tolerance."""

from packlab.plot._common import argument, new_twin_figure, read_csv, run, twin_legend


def figure(log_csv, tolerance=None):
    data = read_csv(log_csv)
    fig, ax, ax2 = new_twin_figure("iteration", "max relative overlap", "nominal / target diameter",
                                   "Force-biased algorithm")
    it = data["iteration"]
    overlap = [max(v, 1e-16) for v in data["max_overlap"]]
    ax.semilogy(it, overlap, "C0-", label="max overlap / (r_i + r_j) at target")
    if tolerance is not None:
        ax.axhline(tolerance, color="C0", ls=":", lw=1, label=f"tolerance {tolerance:g}")
    ax2.plot(it, data["outer_scale"], "C1--", label="nominal / target diameter")
    twin_legend(ax, ax2, loc="upper right")
    return fig


def main(argv):
    return run("fba", argv, figure, argument("log_csv"),
               argument("tolerance", nargs="?", type=float, default=None))
