"""Lubachevsky-Stillinger growth history: volume fraction and reduced pressure against the
number of collisions (the ``ls_log.csv`` written by ``packlab generate ls``)."""

import argparse

from packlab.plot import new_figure, read_csv, save


def figure(log_csv):
    data = read_csv(log_csv)
    fig, ax = new_figure()
    ax.plot(data["collisions"], data["volume_fraction"], "C0-", label="volume fraction")
    ax.set_xlabel("collisions")
    ax.set_ylabel("volume fraction")
    ax2 = ax.twinx()
    ax2.semilogy(data["collisions"], data["reduced_pressure"], "C1--", label="reduced pressure PV/NkT")
    ax2.set_ylabel("reduced pressure")
    lines = ax.get_lines() + ax2.get_lines()
    ax.legend(lines, [line.get_label() for line in lines], loc="center right", fontsize=8)
    ax.set_title("Lubachevsky-Stillinger growth")
    return fig


def main(argv):
    parser = argparse.ArgumentParser(prog="packlab.plot ls")
    parser.add_argument("log_csv")
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    save(figure(args.log_csv), args.out)
    return 0
