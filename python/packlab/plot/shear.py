"""Oscillatory shear test (doh-elastic-properties Fig. 4): shear stress (left scale) and shear
strain (right scale) against the oscillation cycle, from the ``stress_strain.csv`` written by
``packlab test shear`` (one orientation: the first, or ``--orientation z:x``)."""

import argparse

import numpy as np

from packlab.plot import new_figure, read_csv, save


def figure(stress_strain_csv, orientation=None):
    data = read_csv(stress_strain_csv)
    names = data["orientation"]
    if orientation is None:
        orientation = names[0]
    mask = np.array([n == orientation for n in names])
    if not mask.any():
        raise SystemExit(f"packlab.plot shear: no orientation '{orientation}' in {stress_strain_csv}")
    cycle = data["cycle"][mask] - 1 + data["phase"][mask] / (2 * np.pi)
    fig, ax = new_figure(5.5, 3.8)
    ax.plot(cycle, data["stress"][mask], "s", mfc="none", ms=3.5, color="C0", label="stress $\\sigma_{12}$")
    ax.set_xlabel("oscillation cycle")
    ax.set_ylabel("$\\sigma_{12}$ [Pa]")
    ax2 = ax.twinx()
    ax2.plot(cycle, 100 * data["strain"][mask], "o", ms=2.5, color="C1", label="strain $\\gamma_{12}$")
    ax2.set_ylabel("$\\gamma_{12}$ [%]")
    # Same zero on both axes.
    s = max(abs(v) for v in ax.get_ylim())
    g = max(abs(v) for v in ax2.get_ylim())
    ax.set_ylim(-s, s)
    ax2.set_ylim(-g, g)
    lines = ax.get_lines() + ax2.get_lines()
    ax.legend(lines, [line.get_label() for line in lines], loc="upper left", fontsize=8)
    ax.set_title(f"oscillatory shear, plate normal : shear = {orientation}")
    return fig


def main(argv):
    parser = argparse.ArgumentParser(prog="packlab.plot shear")
    parser.add_argument("stress_strain_csv")
    parser.add_argument("--orientation", default=None)
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    save(figure(args.stress_strain_csv, args.orientation), args.out)
    return 0
