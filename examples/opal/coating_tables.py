#!/usr/bin/env python3
"""Tables of the coated FCC opal at four resolutions (examples/opal/coating_resolution.toml:
bpm-inverse-opals §4, Fig. 9, Fig. 15; titania coatings of 10, 20 and 34 nm scaled with the
pores, D/d = 9.2-24.5, FBA seeds 1-3, static solver) from the study's tasks.csv:

  DATA/opal_coating_resolution.csv      one row per sample: coating, D/d, seed, particles (of
                                        them titania), bonds, porosity, density, E, strength
                                        (empty where the run stopped before breaking: E only)
  DATA/opal_coating_extrapolation.csv   per coating and quantity (E [GPa], strength [MPa],
                                        density [kg/m^3]): q(x) = q_inf + c f(x), x = D/d,
                                        f = 1/x, 1/x^2, 1/sqrt(x), fitted to every sample, the
                                        value at the paper's D/d = 51 and its standard error; then
                                        the row "estimate": the 1/x value with the fit's error and
                                        half the spread of the three laws in quadrature
                                        (resolution_extrapolation.py's rule for the uncoated opal)

With --density, the tables of examples/opal/coating_density.toml instead (the 20 nm coating
thinned at each D/d to the paper's density of 668 kg/m^3): DATA/opal_coating_density.csv and
DATA/opal_coating_density_extrapolation.csv, the same columns (coating_nm is the nominal 20,
coating_m the thickness used).

With --merge, the study's samples are added to the per-sample table already in DATA (a sample of
the study replaces the table's of the same coating, D/d and seed; the others are kept), so that a
study run in parts (e.g. coating_resolution.toml's 34 nm at D/d = 14.3 alone, after the rest) adds
to what the table holds, and both tables regenerate from DATA.

usage: coating_tables.py STUDY_OUT [DATA] [--density] [--merge]
       (DATA defaults to docs/data of this checkout)"""

import math
import os
import sys

import numpy as np

from packlab.reproduction import read_table
from packlab.studies import finished_tasks
from packlab.tables import merged_rows, write_table

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from resolution_extrapolation import LAWS, TARGET, fit  # noqa: E402

SAMPLE_COLUMNS = ["coating_nm", "coating_m", "pore_to_particle_diameter", "seed", "particles", "titania_particles",
                  "bonds", "porosity", "density_kg_m3", "youngs_modulus_gpa", "strength_mpa", "strain_at_peak",
                  "broken_bonds", "seconds"]
QUANTITIES = ("youngs_modulus_gpa", "strength_mpa", "density_kg_m3")
INTEGER_COLUMNS = ("coating_nm", "seed", "particles", "titania_particles", "bonds", "broken_bonds")
OPTIONAL_COLUMNS = ("strength_mpa", "strain_at_peak")  # empty for E-only runs


def sample_key(row):
    """What identifies a sample: its coating, resolution and seed."""
    return row["coating_nm"], row["pore_to_particle_diameter"], row["seed"]


def table_samples(path):
    """The per-sample table `path` as rows of numbers ([] if missing)."""
    def value(column, text):
        if column in INTEGER_COLUMNS:
            return int(float(text))
        return "" if text == "" and column in OPTIONAL_COLUMNS else float(text)
    return [{c: value(c, r[c]) for c in SAMPLE_COLUMNS} for r in read_table(path)]


def main(argv):
    density = "--density" in argv
    merge = "--merge" in argv
    argv = [a for a in argv if a not in ("--density", "--merge")]
    if len(argv) < 2:
        sys.exit(__doc__)
    out = argv[1]
    data = argv[2] if len(argv) > 2 else os.path.join(HERE, "..", "..", "docs", "data")
    name, extrapolation_name, spec = (
        ("opal_coating_density", "opal_coating_density_extrapolation", "coating_density.toml") if density else
        ("opal_coating_resolution", "opal_coating_extrapolation", "coating_resolution.toml"))
    tasks = finished_tasks(out)
    if not tasks:
        sys.exit(f"coating_tables: no finished task in {out}/tasks.csv")
    samples = []
    for t in tasks:
        breaks = int(float(t["compress.broken_bonds"]))  # E-only runs (--max-strain 1e-6) break none
        samples.append({
            "coating_nm": int(float(t["coating_nm"])), "coating_m": float(t["opal.coating"]),
            "pore_to_particle_diameter": round(float(t["opal.parameters.pores.ratio_to_mean_particle_diameter"]), 3),
            "seed": int(t["seed"]), "particles": int(float(t["opal.results.particles"])),
            "titania_particles": int(float(t["opal.results.titania_particles"])),
            "bonds": int(float(t["opal.results.bonds"])), "porosity": float(t["opal.results.porosity"]),
            "density_kg_m3": float(t["opal.results.density_kg_m3"]),
            "youngs_modulus_gpa": float(t["compress.youngs_modulus"]) * 1e-9,
            "strength_mpa": float(t["compress.strength"]) * 1e-6 if breaks else "",
            "strain_at_peak": float(t["compress.strain_at_peak"]) if breaks else "", "broken_bonds": breaks,
            "seconds": float(t["compress.seconds"])})
    path = os.path.join(data, name + ".csv")
    samples = merged_rows(table_samples(path), samples, sample_key) if merge else sorted(samples, key=sample_key)
    write_table(path, {k: [r[k] for r in samples] for k in SAMPLE_COLUMNS},
                f"examples/opal/{spec}: FCC opal, titania coating c nm x D / 762 nm"
                + (" thinned at each D/d to the paper's density 668 kg/m^3 (coating_m: the thickness used)"
                   if density else "") + ", titania bonds of "
                "Table 1 (13.72 / 17.89 / 22.21 GPa, 834 MPa), silica 6.53 GPa / 94.3 MPa, static solver")
    print(f"wrote {path} ({len(samples)} rows)")

    rows = {k: [] for k in ("coating_nm", "quantity", "law", "intercept", "coefficient", "at_target", "standard_error",
                            "rms", "samples", "largest_d_over_d", "value_at_largest", "sd_at_largest")}

    def add(*values):
        for k, v in zip(rows, values):
            rows[k].append(v)

    for coating in sorted({r["coating_nm"] for r in samples}):
        for quantity in QUANTITIES:
            pairs = [(r["pore_to_particle_diameter"], r[quantity]) for r in samples
                     if r["coating_nm"] == coating and r[quantity] != ""]
            if len({p[0] for p in pairs}) < 2 or len(pairs) < 3:
                continue
            x = np.array([p[0] for p in pairs])
            y = np.array([p[1] for p in pairs])
            at_largest = y[x == x.max()]
            largest = (float(at_largest.mean()), float(at_largest.std(ddof=1)) if len(at_largest) > 1 else 0.0)
            fits = {law: fit(x, y, law) for law in LAWS}
            for law, (a, b, value, se, rms) in fits.items():
                add(coating, quantity, law, a, b, value, se, rms, len(y), x.max(), *largest)
            values = [v[2] for v in fits.values()]
            first = fits["1/x"]
            error = math.hypot(first[3], 0.5 * (max(values) - min(values)))
            add(coating, quantity, "estimate", first[0], first[1], first[2], error, first[4], len(y), x.max(), *largest)
            print(f"{coating} nm {quantity}: at D/d {x.max():g}: {largest[0]:.4g} +- {largest[1]:.2g}; "
                  f"at D/d {TARGET:g}: {first[2]:.4g} +- {error:.2g}")
    path = os.path.join(data, extrapolation_name + ".csv")
    write_table(path, rows, f"{name}.csv extrapolated to D/d = {TARGET:g} (examples/opal/coating_tables.py)")
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
