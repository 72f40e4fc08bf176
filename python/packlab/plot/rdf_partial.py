"""Partial RDFs g_km against the scaled R_km = (r - a_k)/a_m + 1, one panel per pair of size
classes, with the Willis-type curve of eq. (20) at the Percus-Yevick mixture contact value (the
``rdf_partial.csv`` written by ``packlab analyze rdf --partial``). Several CSV files are drawn
on the same axes, labelled by ``--labels``."""

from packlab.plot._common import argument, comma_list, read_csv, run, subplots


def figure(csvs, labels=None, r_max=None):
    import numpy as np

    if isinstance(csvs, str):
        csvs = [csvs]
    labels = labels or [None] * len(csvs)
    tables = [read_csv(p) for p in csvs]
    first = tables[0]
    pairs = sorted(set(zip(first["k"].astype(int), first["m"].astype(int))))
    fig, axes = subplots(1, len(pairs), width=4.2 * len(pairs), height=3.6, squeeze=False)
    for ax, (k, m) in zip(axes[0], pairs):
        for q, (data, label) in enumerate(zip(tables, labels)):
            sel = (data["k"].astype(int) == k) & (data["m"].astype(int) == m)
            x = np.asarray(data["R_km"])[sel]
            ax.plot(x, np.asarray(data["g"])[sel], f"C{q}-", lw=0.9, label=label or ("measured" if q == 0 else None))
            if q == 0:
                ax.plot(x, np.asarray(data["willis_partial"])[sel], "k--", lw=0.7, label="Willis (20), PY contact")
        ax.axhline(1.0, color="0.6", lw=0.5)
        ax.set_xlim(1.5, r_max or min(float(x.max()), 10.0))
        ax.set_ylim(0, 5)
        ax.set_xlabel(f"R_{k + 1}{m + 1} = (r - a_{k + 1})/a_{m + 1} + 1")
        ax.set_ylabel(f"g_{k + 1}{m + 1}")
        ax.set_title(f"g_{k + 1}{m + 1}")
    axes[0][0].legend(fontsize=7)
    return fig


def main(argv):
    return run("rdf_partial", argv, figure, argument("csv", nargs="+"),
               argument("--labels", type=comma_list, default=None), argument("--rmax", type=float, default=None))
