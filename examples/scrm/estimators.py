"""The paper's estimators over the realizations of one case (scrm-bimodal-packs.txt §2, §4):
g from the K-function with the toroidal edge correction (packlab.Rdf), the contact value by the
right difference g+(2a) = [K(2a + dr) - K(2a)] / (4 pi (2a)^2 dr) (eq. 14_2) for several bin
widths dr, the maximum of g near contact and the first gap of the averaged curve, and the
window counts p(n_h) (R_h = 2.5).

Per realization and averaged: the paper averages its curves over P realizations; packlab's SD of
an averaged quantity is the standard error over the realizations (SD / sqrt(P)).

usage (a table for some case folders, each holding r*/packing.xyz):
  PYTHONPATH=build/python:python /usr/bin/python3 examples/scrm/estimators.py CASE_DIR...
"""

import glob
import math
import os
import sys

import numpy as np

BIN_WIDTHS = (0.001, 0.0025, 0.005, 0.01, 0.015)  # in units of a; the paper's is 0.01 a


def realizations(case):
    files = sorted(glob.glob(os.path.join(case, "r*", "packing.xyz")),
                   key=lambda p: int(os.path.basename(os.path.dirname(p))[1:]))
    if not files:
        raise SystemExit(f"{case}: no r*/packing.xyz")
    return files


def mean_se(values):
    values = np.asarray(values, dtype=float)
    if len(values) < 2:
        return float(values.mean()), float("nan")
    return float(values.mean()), float(values.std(ddof=1) / math.sqrt(len(values)))


def window_moments(rdf, k=-1):
    p = np.asarray(rdf.window_histogram(k), dtype=float)
    n = np.arange(len(p))
    mean = float((n * p).sum())
    return mean, float(((n - mean) ** 2 * p).sum())


def first_gap(r, g, lo, hi, smooth=5):
    """Position of the minimum of g (running mean over `smooth` bins) with lo <= r <= hi."""
    half = smooth // 2
    best, where = math.inf, float("nan")
    for q in range(half, len(r) - half):
        if lo <= r[q] <= hi:
            s = float(np.mean(g[q - half:q + half + 1]))
            if s < best:
                best, where = s, float(r[q])
    return where


def case_table(case, packlab, pairs=((-1, -1),), bin_widths=BIN_WIDTHS, r_max=6.0):
    """Rows (dicts) of one case: per pair of classes (k, m) (-1, -1 = all particles) and bin width,
    the contact value of the averaged curve and its standard error over realizations; at the
    paper's dr = 0.01 a also the maximum of the averaged g within 2.1 a, its position, the first
    gap and the window-count moments."""
    files = realizations(case)
    packings = [packlab.read(f) for f in files]
    rows = []
    for dr in bin_widths:
        averaged = packlab.Rdf(dr=dr, r_max=r_max if dr == 0.01 else 2.2)
        single = packlab.Rdf(dr=dr, r_max=2.2)
        per = {pair: [] for pair in pairs}
        windows = []
        for p in packings:
            averaged.accumulate(p)
            single.compute(p)
            for pair in pairs:
                per[pair].append(single.contact_value(*pair))
            windows.append(window_moments(single))
        for (k, m) in pairs:
            value = averaged.contact_value(k, m)
            _, se = mean_se(per[(k, m)])
            row = {"case": os.path.basename(os.path.normpath(case)), "k": k, "m": m, "realizations": len(files),
                   "particles": len(packings[0]), "dr": dr, "contact_value": value, "contact_value_se": se}
            if dr == 0.01:
                r = np.asarray(averaged.r)
                g = np.asarray(averaged.g(k, m))
                near = (r >= 1.99) & (r <= 2.1) if k < 0 or (k == m) else None
                if near is not None and near.any():
                    q = int(np.argmax(np.where(near, g, -np.inf)))
                    row["max_near_contact"], row["max_near_contact_R"] = float(g[q]), float(r[q])
                if k < 0:
                    row["gap_R"] = first_gap(r, g, 2.3, 3.2)
                    wm = [w[0] for w in windows]
                    wv = [w[1] for w in windows]
                    row["window_mean"], row["window_mean_se"] = mean_se(wm)
                    row["window_variance"], row["window_variance_se"] = mean_se(wv)
            rows.append(row)
    return rows


COLUMNS = ["case", "k", "m", "realizations", "particles", "dr", "contact_value", "contact_value_se",
           "max_near_contact", "max_near_contact_R", "gap_R", "window_mean", "window_mean_se", "window_variance",
           "window_variance_se"]


def format_rows(rows):
    lines = [",".join(COLUMNS)]
    for row in rows:
        cells = []
        for c in COLUMNS:
            v = row.get(c, "")
            cells.append(f"{v:.6g}" if isinstance(v, float) and not math.isnan(v) else ("" if isinstance(v, float)
                                                                                        else str(v)))
        lines.append(",".join(cells))
    return "\n".join(lines) + "\n"


def main(argv):
    import packlab
    rows = []
    for case in argv:
        rows += case_table(case, packlab)
    sys.stdout.write(format_rows(rows))


if __name__ == "__main__":
    main(sys.argv[1:])
