"""Table 2's BD rows at the paper's size (docs/bd.md): ``time`` (DOH parameter a, coordination
C and G'_p of the N = 8000 gels against the time simulated, from ``examples/bd/time_series.sh``,
with the paper's values), ``fig5`` (G'_p of the least and the most heterogeneous structure
against the particle normal stiffness k_n, the paper's Fig. 5, from ``examples/bd/fig5.sh``) and
``coordination`` (2 bonds / N against the time for every potential, with the paper's C, from
``examples/bd/coordination_series.sh``); the paper's values ``PAPER`` and :func:`crossing_time`
(when a BD log's coordination reaches the paper's C), which ``examples/bd/coordination_series.sh``,
``slip_matched.sh`` and ``fig6.py`` use."""

import csv
import os

from packlab.plot._common import UsageError, argument, read_csv, run, subplots

# doh-elastic-properties Table 2, BD rows: psi_0 [mV] -> (a, C, G'_p [MPa], its SD).
PAPER = {0: (0.373, 4.52, 0.480, 0.049), 12: (0.404, 4.84, 1.19, 0.141), 13: (0.410, 4.75, 1.05, 0.124),
         14: (0.472, 5.08, 1.46, 0.120), 15: (0.536, 4.97, 1.62, 0.213)}


def read_coordination_log(path):
    """The rows ``(reduced_time, mean_coordination)`` of a BD log ``bd_log.csv`` (time in a^2/D_0,
    2 bonds / N), in the file's order."""
    with open(path, newline="") as f:
        return [(float(r["reduced_time"]), float(r["mean_coordination"])) for r in csv.DictReader(f)]


def crossing_time(log, target):
    """The time at which the coordination of a BD log first reaches ``target`` (the paper's C).

    ``log`` is the path of a ``bd_log.csv`` (see :func:`read_coordination_log`) or a sequence of
    ``(time, coordination)`` rows in time order. The rule: the first pair of consecutive rows
    ``(t0, c0), (t1, c1)`` with ``c0 < target <= c1`` gives ``t0 + (target - c0) / (c1 - c0) *
    (t1 - t0)`` (linear interpolation between the two rows; a row that equals ``target`` after a
    row below it gives that row's time; the first row alone never counts, nor a fall through
    ``target``). Returns None when no pair crosses (the coordination stays below ``target``, or
    starts at or above it and never rises through it again)."""
    rows = read_coordination_log(log) if isinstance(log, (str, os.PathLike)) else list(log)
    for (t0, c0), (t1, c1) in zip(rows, rows[1:]):
        if c0 < target <= c1:
            return t0 + (target - c0) / (c1 - c0) * (t1 - t0)
    return None


def time_figure(csv_path):
    data = read_csv(csv_path)
    fig, axes = subplots(1, 3, width=11.0, height=3.4)
    columns = [("a", "DOH parameter a"), ("C", "coordination C (eps 0.01)"), ("storage_modulus_Pa", "G'_p [MPa]")]
    for k, mv in enumerate(sorted(set(data["surface_potential_mV"]))):
        rows = sorted(i for i, p in enumerate(data["surface_potential_mV"]) if p == mv)
        rows.sort(key=lambda i: data["time_diffusion_times"][i])
        t = [data["time_diffusion_times"][i] for i in rows]
        for ax, (name, label) in zip(axes, columns):
            scale = 1e-6 if name == "storage_modulus_Pa" else 1.0
            ax.plot(t, [scale * data[name][i] for i in rows], f"C{k}o-", ms=4, label=f"packlab, {mv:g} mV")
            paper = PAPER.get(int(round(mv)))
            if paper:
                value = {"a": paper[0], "C": paper[1], "storage_modulus_Pa": paper[2]}[name]
                ax.axhline(value, color=f"C{k}", ls="--", lw=1, label=f"paper, {mv:g} mV")
            ax.set_xscale("log")
            ax.set_xlabel("time simulated t D_0 / a^2")
            ax.set_ylabel(label)
    axes[0].legend(fontsize=7)
    fig.suptitle("BD gels, N = 8000, Phi = 0.4, central bonds, seed 1")
    return fig


def fig5_figure(csv_path):
    data = read_csv(csv_path)
    fig, ax = subplots()
    kn = data["k_n_N_per_m"]
    for k, (key, label) in enumerate([("G_HO", "0 mV (homogeneous)"), ("G_HE", "15 mV (heterogeneous)")]):
        ax.errorbar(kn, [1e-6 * g for g in data[f"{key}_Pa"]], yerr=[1e-6 * s for s in data[f"{key}_std_Pa"]],
                    fmt=f"C{k}o-", ms=4, capsize=2, label=f"packlab, {label}")
    for k, mv in enumerate((0, 15)):
        ax.errorbar([100.0], [PAPER[mv][2]], yerr=[PAPER[mv][3]], fmt=f"C{k}s", mfc="none", ms=7, capsize=3,
                    label=f"paper Table 2, {mv} mV")
    ratios = data["ratio_HE_HO"]
    ax.set_xlabel("particle normal stiffness k_n [N/m] (k_s = k_n / 10)")
    ax.set_ylabel("G'_p [MPa]")
    low, high = f"{min(ratios):.2f}", f"{max(ratios):.2f}"
    ax.set_title(f"Fig. 5: G'_HE / G'_HO = {low if low == high else low + '-' + high} (paper 3.4)")
    ax.legend(fontsize=7)
    return fig


def coordination_figure(csv_path):
    data = read_csv(csv_path)
    fig, ax = subplots()
    for k, mv in enumerate(sorted(set(data["surface_potential_mV"]))):
        rows = [i for i, p in enumerate(data["surface_potential_mV"]) if p == mv and data["time_diffusion_times"][i] > 0]
        rows.sort(key=lambda i: data["time_diffusion_times"][i])
        ax.plot([data["time_diffusion_times"][i] for i in rows], [data["mean_coordination_bonds"][i] for i in rows],
                f"C{k}-", label=f"{mv:g} mV")
        paper = PAPER.get(int(round(mv)))
        if paper:
            ax.axhline(paper[1], color=f"C{k}", ls="--", lw=0.8)
    ax.set_xscale("log")
    ax.set_xlabel("time simulated t D_0 / a^2")
    ax.set_ylabel("2 bonds / N")
    ax.set_title("BD gels, N = 8000, central bonds, seed 1 (dashed: paper's C)")
    ax.legend(fontsize=7)
    return fig


def figure(which, csv_path):
    if which == "time":
        return time_figure(csv_path)
    if which == "fig5":
        return fig5_figure(csv_path)
    if which == "coordination":
        return coordination_figure(csv_path)
    raise UsageError(f"unknown figure '{which}' (time, fig5, coordination)")


def main(argv):
    return run("bd_table2", argv, figure, argument("which"), argument("csv_path"))
