"""Relaxation history: unbalanced force ratio and energies against the step
(the CSV written by ``packlab relax --log``)."""

import argparse

from packlab.plot import new_figure, read_csv, save


def figure(log_csv):
    data = read_csv(log_csv)
    fig, ax = new_figure()
    ax.semilogy(data["step"], data["unbalanced_force_ratio"], label="unbalanced force ratio")
    ax.set_xlabel("step")
    ax.set_ylabel("mean unbalanced / mean contact force")
    ax2 = ax.twinx()
    ax2.semilogy(data["step"], data["kinetic_energy"], "C1--", label="kinetic energy")
    ax2.set_ylabel("kinetic energy [J]")
    lines = ax.get_lines() + ax2.get_lines()
    ax.legend(lines, [line.get_label() for line in lines], loc="upper right", fontsize=8)
    ax.set_title("relaxation")
    return fig


def main(argv):
    parser = argparse.ArgumentParser(prog="packlab.plot relax")
    parser.add_argument("log_csv")
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    save(figure(args.log_csv), args.out)
    return 0
