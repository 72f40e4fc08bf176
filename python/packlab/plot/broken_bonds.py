"""Broken bonds against the sample strain, with the stress for reference (``curve.csv`` of
``packlab test compress``, or from Python a dict of its columns strain, stress, broken_bonds)."""

import argparse

from packlab.plot import new_figure, read_csv, save


def figure(curve_csv):
    data = curve_csv if isinstance(curve_csv, dict) else read_csv(curve_csv)
    fig, ax = new_figure()
    ax.plot(data["strain"] * 100, data["broken_bonds"], "C3", label="broken bonds")
    ax.set_xlabel("strain [%]")
    ax.set_ylabel("broken bonds")
    ax2 = ax.twinx()
    ax2.plot(data["strain"] * 100, data["stress"] * 1e-6, "C0--", lw=1, label="stress")
    ax2.set_ylabel("stress [MPa]")
    lines = ax.get_lines() + ax2.get_lines()
    ax.legend(lines, [line.get_label() for line in lines], loc="upper left", fontsize=8)
    ax.set_title("bond breakage")
    return fig


def main(argv):
    parser = argparse.ArgumentParser(prog="packlab.plot broken_bonds")
    parser.add_argument("curve_csv")
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    save(figure(args.curve_csv), args.out)
    return 0
