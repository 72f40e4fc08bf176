"""Oscillatory shear test (doh-elastic-properties Fig. 4): shear stress (left scale) and shear
strain (right scale) against the oscillation cycle, from the ``stress_strain.csv`` written by
``packlab test shear`` (one orientation: the first, or ``--orientation z:x``)."""

import numpy as np

from packlab.plot._common import argument, new_twin_figure, read_csv, run, twin_legend


def figure(stress_strain_csv, orientation=None):
    data = read_csv(stress_strain_csv)
    names = data["orientation"]
    if orientation is None:
        orientation = names[0]
    mask = np.array([n == orientation for n in names])
    if not mask.any():
        raise SystemExit(f"packlab.plot shear: no orientation '{orientation}' in {stress_strain_csv}")
    cycle = data["cycle"][mask] - 1 + data["phase"][mask] / (2 * np.pi)
    fig, ax, ax2 = new_twin_figure("oscillation cycle", "$\\sigma_{12}$ [Pa]", "$\\gamma_{12}$ [%]",
                                   f"oscillatory shear, plate normal : shear = {orientation}", width=5.5)
    ax.plot(cycle, data["stress"][mask], "s", mfc="none", ms=3.5, color="C0", label="stress $\\sigma_{12}$")
    ax2.plot(cycle, 100 * data["strain"][mask], "o", ms=2.5, color="C1", label="strain $\\gamma_{12}$")
    # Same zero on both axes.
    s = max(abs(v) for v in ax.get_ylim())
    g = max(abs(v) for v in ax2.get_ylim())
    ax.set_ylim(-s, s)
    ax2.set_ylim(-g, g)
    twin_legend(ax, ax2, loc="upper left")
    return fig


def main(argv):
    return run("shear", argv, figure, argument("stress_strain_csv"), argument("--orientation", default=None))
