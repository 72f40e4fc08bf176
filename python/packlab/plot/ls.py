"""Lubachevsky-Stillinger growth history: volume fraction and reduced pressure against the
number of collisions (the ``ls_log.csv`` written by ``packlab generate ls``)."""

from packlab.plot._common import argument, new_twin_figure, read_csv, run, twin_legend


def figure(log_csv):
    data = read_csv(log_csv)
    fig, ax, ax2 = new_twin_figure("collisions", "volume fraction", "reduced pressure", "Lubachevsky-Stillinger growth")
    ax.plot(data["collisions"], data["volume_fraction"], "C0-", label="volume fraction")
    ax2.semilogy(data["collisions"], data["reduced_pressure"], "C1--", label="reduced pressure PV/NkT")
    twin_legend(ax, ax2, loc="center right")
    return fig


def main(argv):
    return run("ls", argv, figure, argument("log_csv"))
