"""The paper's estimators over the realizations of one case (scrm-bimodal-packs.txt §2, §4).

g comes from the K-function with the toroidal edge correction (packlab.Rdf: every periodic image
counts), the contact value from the right difference g+(sigma) = [K(sigma + dr) - K(sigma)] /
(4 pi sigma^2 dr) (eq. 14_2), for several bin widths dr (the paper's is 0.01 a; its claim: any dr
from 1e-4 a to 1e-2 a gives almost the same). The paper averages its curves over P realizations
("smoothed by averaging over P = 80 realizations"); here the averaged curve is the mean of the
realizations' g (same N and volume in each), and the uncertainty of anything read off it (a
contact value, a peak or gap position) is its bootstrap standard error over the realizations:
the SD of that quantity among curves averaged over P realizations drawn with replacement.

usage (a table for some case folders, each holding r*/packing.xyz):
  PYTHONPATH=build/python:python /usr/bin/python3 examples/scrm/estimators.py CASE_DIR...
"""

import glob
import math
import os
import sys

import numpy as np

BIN_WIDTHS = (0.001, 0.0025, 0.005, 0.01, 0.015)  # in units of a; the paper's is 0.01 a
PAPER_DR = 0.01
BOOTSTRAP = 200


def mean_se(values):
    """Mean over the realizations and its standard error (SD / sqrt(P))."""
    v = np.asarray(values, dtype=float)
    return float(v.mean()), float(v.std(ddof=1) / math.sqrt(len(v)))


def realizations(case):
    files = sorted(glob.glob(os.path.join(case, "r*", "packing.xyz")),
                   key=lambda p: int(os.path.basename(os.path.dirname(p))[1:]))
    if not files:
        raise SystemExit(f"{case}: no r*/packing.xyz")
    return files


class Case:
    """The realizations of one case, measured once: per pair of classes (k, m) (-1, -1 = all
    particles) the contact value of each realization at each bin width and the g(r) of each
    realization at the paper's dr; per realization the mean and variance of the window counts."""

    def __init__(self, case, packlab, pairs=((-1, -1),), r_max=6.0, bin_widths=BIN_WIDTHS):
        self.name = os.path.basename(os.path.normpath(case))
        files = realizations(case)
        self.realizations = len(files)
        self.pairs = pairs
        self.contact = {(pair, dr): [] for pair in pairs for dr in bin_widths}
        self.curves = {pair: [] for pair in pairs}
        self.window_mean, self.window_variance = [], []
        fine = {dr: packlab.Rdf(dr=dr, r_max=2.2) for dr in bin_widths if dr != PAPER_DR}
        paper = packlab.Rdf(dr=PAPER_DR, r_max=r_max)
        for f in files:
            p = packlab.read(f)
            self.particles = len(p)
            paper.compute(p)
            for pair in pairs:
                self.contact[(pair, PAPER_DR)].append(paper.contact_value(*pair))
                self.curves[pair].append(np.asarray(paper.g(*pair), dtype=float))
            hist = np.asarray(paper.window_histogram(-1), dtype=float)
            n = np.arange(len(hist))
            mean = float((n * hist).sum())
            self.window_mean.append(mean)
            self.window_variance.append(float(((n - mean) ** 2 * hist).sum()))
            for dr, rdf in fine.items():
                rdf.compute(p)
                for pair in pairs:
                    self.contact[(pair, dr)].append(rdf.contact_value(*pair))
        self.r = np.asarray(paper.r, dtype=float)
        radii = np.asarray(paper.class_radius, dtype=float)
        self.class_radius = radii / radii[0]  # in units of a, the largest
        self.curves = {pair: np.vstack(c) for pair, c in self.curves.items()}
        self._draws = np.random.default_rng(12345).integers(0, self.realizations,
                                                            size=(BOOTSTRAP, self.realizations))

    def axis(self, pair=(-1, -1)):
        """The curve's abscissa: R = r/a for all particles, R_km = (r - a_k)/a_m + 1 for a pair of
        classes (the paper's normalization of the partial RDFs, contact at R_km = 2)."""
        k, m = pair
        if k < 0:
            return self.r
        return (self.r - self.class_radius[k]) / self.class_radius[m] + 1.0

    def curve(self, pair=(-1, -1)):
        return self.curves[pair].mean(axis=0)

    def _bootstrap(self, values, statistic):
        """statistic of the mean over realizations and its bootstrap SE; values: per realization.
        Draws where the statistic is undefined (NaN: a peak or gap not found in that resample)
        are left out of the SE."""
        values = np.asarray(values)
        value = statistic(values.mean(axis=0))
        if self.realizations < 2:
            return value, float("nan")
        draws = [statistic(values[d].mean(axis=0)) for d in self._draws]
        draws = [d for d in draws if not math.isnan(d)]
        return value, (float(np.std(draws, ddof=1)) if len(draws) > 1 else float("nan"))

    def contact_value(self, pair=(-1, -1), dr=PAPER_DR):
        return self._bootstrap(self.contact[(pair, dr)], float)

    def ratio(self, other, pair=(-1, -1), dr=PAPER_DR, paired=False):
        """g+(this) / g+(other) with its SE: independent realizations add their relative errors in
        quadrature; paired ones (the same seeds, grown alike and differing only in the final
        shakes) are resampled together."""
        a, b = np.asarray(self.contact[(pair, dr)]), np.asarray(other.contact[(pair, dr)])
        value = a.mean() / b.mean()
        if paired:
            draws = [a[d].mean() / b[d].mean() for d in self._draws]
            return float(value), float(np.std(draws, ddof=1))
        (ma, sa), (mb, sb) = mean_se(a), mean_se(b)
        return float(value), float(value * math.hypot(sa / ma, sb / mb))

    def extremum(self, pair, lo, hi, kind="min", smooth=5):
        """Position (R = r/a) of the minimum or maximum of the averaged g, smoothed by a running
        mean over `smooth` bins, in [lo, hi], with its bootstrap SE; NaN when the extremum found
        is at an end of the interval (no minimum or maximum inside: not resolved)."""
        half = smooth // 2
        x = self.axis(pair)
        inside = np.nonzero((x >= lo) & (x <= hi))[0]

        def where(g):
            s = np.convolve(g, np.ones(smooth) / smooth, mode="same")[inside]
            best = s.min() if kind == "min" else s.max()
            # A plateau of equal values (a lattice's single shell spread by the running mean): its middle.
            tied = np.nonzero(np.abs(s - best) <= 1e-12 * max(1.0, abs(best)))[0]
            q = inside[tied[len(tied) // 2]]
            if q - inside[0] < half or inside[-1] - q < half:
                return float("nan")
            return float(x[q])

        return self._bootstrap(self.curves[pair], where)

    def near_contact_max(self, pair=(-1, -1), hi=2.1):
        """The largest value of the averaged g with 1.99 <= R <= hi, its position, and the
        bootstrap standard error of that value."""
        g, x = self.curve(pair), self.axis(pair)
        near = np.nonzero((x >= 1.99) & (x <= hi))[0]
        q = near[np.argmax(g[near])]
        _, se = self._bootstrap(self.curves[pair], lambda curve: float(curve[near].max()))
        return float(g[q]), float(x[q]), se

    def window_variance_se(self):
        return mean_se(self.window_variance)

    def window_mean_se(self):
        return mean_se(self.window_mean)


def fmt(v):
    if isinstance(v, float):
        return "" if math.isnan(v) else f"{v:.6g}"
    return str(v)


def main(argv):
    import packlab
    print("case,realizations,particles,dr,contact_value,contact_value_se")
    for path in argv:
        c = Case(path, packlab)
        for dr in BIN_WIDTHS:
            v, se = c.contact_value(dr=dr)
            print(",".join(fmt(x) for x in (c.name, c.realizations, c.particles, dr, v, se)))


if __name__ == "__main__":
    main(sys.argv[1:])
