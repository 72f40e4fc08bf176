"""What the figure modules of ``packlab.plot`` share: reading the CSV tables, setting up a
figure, the legend of a plot with two scales, saving a PNG atomically, and the command line
``python3 -m packlab.plot KIND ARGS... --out FILE.png`` (the one ``io/plot.cpp`` runs) that
each module's ``main(argv)`` declares with :func:`run`."""

import argparse

from packlab.tables import atomic_output
from packlab.tables import read_table as read_csv  # noqa: F401 (re-exported as packlab.plot.read_csv)


def save(fig, path):
    """Saves atomically (temporary name, then rename) at 150 dpi."""
    with atomic_output(path, ".plot-") as tmp:
        fig.savefig(tmp, dpi=150, bbox_inches="tight")


def pyplot():
    """``matplotlib.pyplot`` on the Agg backend (the figures are written to files, never shown)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def subplots(nrows=1, ncols=1, width=5.0, height=3.8, layout="constrained", **kwargs):
    """A new figure of ``width`` x ``height`` inches with a grid of axes (``pyplot.subplots``)."""
    return pyplot().subplots(nrows, ncols, figsize=(width, height), layout=layout, **kwargs)


def new_figure(width=5.0, height=3.8):
    """A new figure with one pair of axes: ``fig, ax``."""
    return subplots(width=width, height=height)


def new_twin_figure(xlabel, ylabel, twin_ylabel, title, width=5.0, height=3.8):
    """A new figure with two y scales on one x axis: ``fig, ax, twin`` (``twin`` shares the x
    axis of ``ax`` and has its scale on the right), labelled and titled."""
    fig, ax = new_figure(width, height)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    twin = ax.twinx()
    twin.set_ylabel(twin_ylabel)
    return fig, ax, twin


def twin_legend(ax, twin, loc, fontsize=8):
    """One legend on ``ax`` for the lines of ``ax`` and of its ``twin`` (the second scale)."""
    lines = ax.get_lines() + twin.get_lines()
    ax.legend(lines, [line.get_label() for line in lines], loc=loc, fontsize=fontsize)


def argument(*flags, **options):
    """One argument of a figure's command line, as ``argparse``'s ``add_argument`` takes it."""
    return flags, options


def comma_list(text):
    """The value of ``--labels a,b,c``: ``["a", "b", "c"]``, or None when empty."""
    return text.split(",") if text else None


class UsageError(Exception):
    """Raised by a ``draw`` function of :func:`run` for arguments that do not go together;
    reported like argparse's own errors (usage line, exit status 2)."""


def run(kind, argv, draw, *arguments):
    """The command line of figure ``kind``: parses ``argv`` against the ``arguments`` (made with
    :func:`argument`) and the required ``--out FILE.png``, calls ``draw`` with the arguments'
    values in the order they are declared, saves the figure it returns to ``--out`` and returns
    the exit status 0."""
    parser = argparse.ArgumentParser(prog=f"packlab.plot {kind}")
    names = [parser.add_argument(*flags, **options).dest for flags, options in arguments]
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    try:
        fig = draw(*(getattr(args, name) for name in names))
    except UsageError as error:
        parser.error(str(error))
    save(fig, args.out)
    return 0
