"""Relaxation history: unbalanced force ratio and energies against the step
(the CSV written by ``packlab relax --log``)."""

from packlab.plot._common import argument, new_twin_figure, read_csv, run, twin_legend


def figure(log_csv):
    data = read_csv(log_csv)
    fig, ax, ax2 = new_twin_figure("step", "mean unbalanced / mean contact force", "kinetic energy [J]", "relaxation")
    ax.semilogy(data["step"], data["unbalanced_force_ratio"], label="unbalanced force ratio")
    ax2.semilogy(data["step"], data["kinetic_energy"], "C1--", label="kinetic energy")
    twin_legend(ax, ax2, loc="upper right")
    return fig


def main(argv):
    return run("relax", argv, figure, argument("log_csv"))
