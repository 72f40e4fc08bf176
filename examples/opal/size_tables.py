#!/usr/bin/env python3
"""Tables of the sample-size study (examples/opal/size_study.toml: bpm-inverse-opals §3.1.1,
Figs. 4-5; FCC opal at D/d = 9.2, cross-sections 2-16 um^2 at the paper's scale, 3 or 4 pore
layers, FBA seeds 1-3, static solver, paper's bonds) from the study's tasks.csv:

  DATA/opal_size_study.csv         one row per sample: periods, pore layers, cross-section,
                                   seed, particles, bonds, porosity, E, strength, strain at the
                                   peak, breaks, seconds
  DATA/opal_size_study_levels.csv  per size: mean and SD over the seeds of E and strength, and
                                   the relative deviation of the mean from that of the paper's
                                   size (4x2 periods, 3 layers: 8.05 um^2 x 2.01 um), the
                                   paper's estimator for its Fig. 5 statement (below 0.12 % for E
                                   and 4 % for the strength above 4 um^2)

usage: size_tables.py STUDY_OUT [DATA]   (DATA defaults to docs/data of this checkout)"""

import os
import sys

from packlab.reproduction import mean_sd
from packlab.studies import study_table_arguments
from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))
SAMPLE_COLUMNS = ["periods", "pore_layers", "cross_section_um2", "seed", "particles", "bonds", "porosity",
                  "youngs_modulus_gpa", "strength_mpa", "strain_at_peak", "broken_bonds", "seconds"]
REFERENCE = ("4x2", 3)  # the paper's sample: 8.05 um^2, 3 pore layers (2.01 um)


def main(argv):
    _, data, tasks = study_table_arguments(argv, __doc__, os.path.join(HERE, "..", "..", "docs", "data"))
    samples = []
    for t in tasks:
        samples.append({
            "periods": t["periods"], "pore_layers": int(float(t["pore_layers"])),
            "cross_section_um2": float(t["cross_section_um2"]), "seed": int(t["seed"]),
            "particles": int(float(t["opal.results.particles"])), "bonds": int(float(t["opal.results.bonds"])),
            "porosity": float(t["opal.results.porosity"]),
            "youngs_modulus_gpa": float(t["compress.youngs_modulus"]) / 1e9,
            "strength_mpa": float(t["compress.strength"]) / 1e6,
            "strain_at_peak": float(t["compress.strain_at_peak"]),
            "broken_bonds": int(float(t["compress.broken_bonds"])), "seconds": float(t["compress.seconds"])})
    samples.sort(key=lambda s: (s["pore_layers"], s["cross_section_um2"], s["seed"]))
    comment = ("examples/opal/size_study.toml: FCC opal, pores 138 nm at 150 nm, D/d 9.2, periodic sides, static "
               "solver, paper's bonds (6.53 GPa, 94.3 MPa); cross-section at the paper's scale (762/150)^2")
    write_table(os.path.join(data, "opal_size_study.csv"), {k: [s[k] for s in samples] for k in SAMPLE_COLUMNS},
                comment)
    levels = []
    for key in sorted({(s["periods"], s["pore_layers"]) for s in samples},
                      key=lambda k: (k[1], [s["cross_section_um2"] for s in samples if s["periods"] == k[0]][0])):
        group = [s for s in samples if (s["periods"], s["pore_layers"]) == key]
        row = {"periods": key[0], "pore_layers": key[1], "cross_section_um2": group[0]["cross_section_um2"],
               "samples": len(group), "particles": sum(s["particles"] for s in group) / len(group)}
        for q in ("youngs_modulus_gpa", "strength_mpa"):
            row[q], row[q + "_sd"] = mean_sd([s[q] for s in group])
        levels.append(row)
    reference = [r for r in levels if (r["periods"], r["pore_layers"]) == REFERENCE]
    for r in levels:
        for q in ("youngs_modulus_gpa", "strength_mpa"):
            r[q + "_deviation"] = r[q] / reference[0][q] - 1.0 if reference else float("nan")
    columns = ["periods", "pore_layers", "cross_section_um2", "samples", "particles", "youngs_modulus_gpa",
               "youngs_modulus_gpa_sd", "youngs_modulus_gpa_deviation", "strength_mpa", "strength_mpa_sd",
               "strength_mpa_deviation"]
    write_table(os.path.join(data, "opal_size_study_levels.csv"), {k: [r[k] for r in levels] for k in columns},
                comment + "; mean and SD over the seeds; deviation = mean / mean of 4x2 periods, 3 layers - 1")
    for r in levels:
        print(f"{r['periods']:>4} x {r['pore_layers']} layers ({r['cross_section_um2']:5.2f} um^2, "
              f"{r['particles']:7.0f} particles): E {r['youngs_modulus_gpa']:.3f} +- {r['youngs_modulus_gpa_sd']:.3f} "
              f"GPa ({100 * r['youngs_modulus_gpa_deviation']:+.2f} %), strength {r['strength_mpa']:.1f} +- "
              f"{r['strength_mpa_sd']:.1f} MPa ({100 * r['strength_mpa_deviation']:+.1f} %)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
