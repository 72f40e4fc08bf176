"""Window histogram p(n_h): the fraction of windows (radius R_h a around each centre) holding n_h
other centres, like the paper's Fig. 4 (the ``windows.csv`` written by ``packlab analyze rdf``).
Several CSV files are drawn on the same axes, labelled by ``--labels``."""

from packlab.plot._common import argument, comma_list, new_figure, read_csv, run


def figure(csvs, labels=None):
    if isinstance(csvs, str):
        csvs = [csvs]
    labels = labels or [None] * len(csvs)
    fig, ax = new_figure()
    for q, (path, label) in enumerate(zip(csvs, labels)):
        data = read_csv(path)
        ax.plot(data["n"], data["p_all"], f"C{q}o-", ms=3, lw=1.0, label=label or path)
    ax.set_xlabel("number of other centres in the window")
    ax.set_ylabel("fraction of windows")
    ax.legend(fontsize=7)
    return fig


def main(argv):
    return run("windows", argv, figure, argument("csv", nargs="+"), argument("--labels", type=comma_list, default=None))
