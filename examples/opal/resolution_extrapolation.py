#!/usr/bin/env python3
"""The resolution study of docs/opal.md ("Finer resolution", docs/data/opal_resolution.csv:
the FCC opal at D/d = 9.2-24.5, three packings each, the paper's bonds, static solver)
extrapolated to the paper's D/d = 51 (bpm-inverse-opals §2.1: pores of 762 nm, particles of
15 nm), for E, the strength and the bonds per particle (the paper's "average coordination
number of about 10.5" = 843,000 bonds / 80,000 particles per um^3, §2.1):

  DATA/opal_resolution_extrapolation.csv   one row per quantity and law: q(x) = q_inf + c f(x),
                                           x = D/d, f = 1/x, 1/x^2, 1/sqrt(x), least squares over
                                           every sample; q at D/d = 51 and its standard error;
                                           then a row "estimate" per quantity

Why 1/x: what resolution costs is the layer of particles at the pore walls (a strut loses
about one particle layer of its load-bearing section and bonds there have fewer partners), a
fraction d/D of the solid, so q(x) = q_inf + c/x to first order. The other two laws bracket it;
the estimate is the 1/x value with an uncertainty that adds the spread of the three laws at
x = 51 (half the range) to the fit's standard error in quadrature.

usage: resolution_extrapolation.py [DATA]   (DATA defaults to docs/data of this checkout)"""

import csv
import math
import os
import sys

import numpy as np

from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))
TARGET = 51.0  # the paper's D/d: 762 nm pores, 15 nm particles
LAWS = {"1/x": lambda x: 1.0 / x, "1/x^2": lambda x: 1.0 / x**2, "1/sqrt(x)": lambda x: 1.0 / np.sqrt(x)}
QUANTITIES = {
    "youngs_modulus_gpa": lambda r: float(r["youngs_modulus_gpa"]) if r["youngs_modulus_gpa"] else None,
    "strength_mpa": lambda r: float(r["strength_mpa"]) if r["strength_mpa"] else None,
    "bonds_per_particle": lambda r: float(r["bonds"]) / float(r["particles"]),
}


def fit(x, y, law):
    """Least squares of y = a + b f(x): (a, b, value at TARGET, its standard error, rms residual)."""
    f = LAWS[law]
    A = np.vstack([np.ones_like(x), f(x)]).T
    coef = np.linalg.lstsq(A, y, rcond=None)[0]
    residual = y - A @ coef
    s2 = float(residual @ residual) / (len(y) - 2)
    at = np.array([1.0, f(TARGET)])
    return coef[0], coef[1], float(at @ coef), math.sqrt(float(at @ (s2 * np.linalg.inv(A.T @ A)) @ at)), math.sqrt(s2)


def main():
    data = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "..", "docs", "data")
    with open(os.path.join(data, "opal_resolution.csv")) as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    out = {k: [] for k in ("quantity", "law", "intercept", "coefficient", "at_target", "standard_error", "rms",
                           "samples", "largest_d_over_d")}
    for quantity, read in QUANTITIES.items():
        pairs = [(float(r["pore_to_particle_diameter"]), read(r)) for r in rows]
        pairs = [(x, y) for x, y in pairs if y is not None]
        x = np.array([p[0] for p in pairs])
        y = np.array([p[1] for p in pairs])
        fits = {law: fit(x, y, law) for law in LAWS}
        for law, (a, b, value, se, rms) in fits.items():
            for k, v in zip(out, (quantity, law, a, b, value, se, rms, len(y), x.max())):
                out[k].append(v)
        values = [v[2] for v in fits.values()]
        first = fits["1/x"]
        spread = 0.5 * (max(values) - min(values))
        for k, v in zip(out, (quantity, "estimate", first[0], first[1], first[2], math.hypot(first[3], spread),
                              first[4], len(y), x.max())):
            out[k].append(v)
        print(f"{quantity}: at D/d = {TARGET:g}: {first[2]:.4g} +- {math.hypot(first[3], spread):.2g} "
              f"(laws {min(values):.4g}-{max(values):.4g}, fit SE {first[3]:.2g})")
    path = os.path.join(data, "opal_resolution_extrapolation.csv")
    write_table(path, out, f"opal_resolution.csv extrapolated to D/d = {TARGET:g} (examples/opal/resolution_extrapolation.py)")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
