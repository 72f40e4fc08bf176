"""Broken bonds against the sample strain, with the stress for reference (``curve.csv`` of
``packlab test compress``, or from Python a dict of its columns strain, stress, broken_bonds)."""

from packlab.plot._common import argument, new_twin_figure, read_csv, run, twin_legend


def figure(curve_csv):
    data = curve_csv if isinstance(curve_csv, dict) else read_csv(curve_csv)
    fig, ax, ax2 = new_twin_figure("strain [%]", "broken bonds", "stress [MPa]", "bond breakage")
    ax.plot(data["strain"] * 100, data["broken_bonds"], "C3", label="broken bonds")
    ax2.plot(data["strain"] * 100, data["stress"] * 1e-6, "C0--", lw=1, label="stress")
    twin_legend(ax, ax2, loc="upper left")
    return fig


def main(argv):
    return run("broken_bonds", argv, figure, argument("curve_csv"))
