"""Force-biased algorithm convergence: the largest relative overlap at the target diameters and
the nominal (outer) diameter against the iteration (the ``fba_log.csv`` written by
``packlab generate fba``); the dashed line is the stop tolerance."""

import argparse

from packlab.plot import new_figure, read_csv, save


def figure(log_csv, tolerance=None):
    data = read_csv(log_csv)
    fig, ax = new_figure()
    it = data["iteration"]
    overlap = [max(v, 1e-16) for v in data["max_overlap"]]
    ax.semilogy(it, overlap, "C0-", label="max overlap / (r_i + r_j) at target")
    if tolerance is not None:
        ax.axhline(tolerance, color="C0", ls=":", lw=1, label=f"tolerance {tolerance:g}")
    ax.set_xlabel("iteration")
    ax.set_ylabel("max relative overlap")
    ax2 = ax.twinx()
    ax2.plot(it, data["outer_scale"], "C1--", label="nominal / target diameter")
    ax2.set_ylabel("nominal / target diameter")
    lines = ax.get_lines() + ax2.get_lines()
    ax.legend(lines, [line.get_label() for line in lines], loc="upper right", fontsize=8)
    ax.set_title("Force-biased algorithm")
    return fig


def main(argv):
    parser = argparse.ArgumentParser(prog="packlab.plot fba")
    parser.add_argument("log_csv")
    parser.add_argument("tolerance", nargs="?", type=float, default=None)
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    save(figure(args.log_csv, args.tolerance), args.out)
    return 0
