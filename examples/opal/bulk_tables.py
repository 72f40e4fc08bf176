#!/usr/bin/env python3
"""Table of the pore-free silica samples (examples/opal/bulk_study.toml: bpm-inverse-opals §3,
Table 1, eq. 20) from the study's tasks.csv:

  DATA/opal_bulk_study.csv   one row per sample (side, height, seed, particles, bonds, E, K_E = E / E_b,
                             strength; strength empty for the E-only runs), then one row per side
                             (seed "mean"): mean and SD over the packings

usage: bulk_tables.py STUDY_OUT [DATA]   (DATA defaults to docs/data of this checkout)"""

import os
import sys

from packlab.reproduction import mean_sd
from packlab.studies import finished_tasks
from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))
BOND_YOUNGS_MODULUS = 6.53e9  # silica.toml, Table 1
COLUMNS = ["side_nm", "height_nm", "seed", "particles", "bonds", "youngs_modulus_gpa", "youngs_modulus_gpa_sd", "bulk_factor",
           "bulk_factor_sd", "strength_mpa", "strength_mpa_sd", "strain_at_peak", "seconds"]


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    data = argv[2] if len(argv) > 2 else os.path.join(HERE, "..", "..", "docs", "data")
    tasks = finished_tasks(argv[1])
    if not tasks:
        sys.exit(f"bulk_tables: no finished task in {argv[1]}/tasks.csv")
    rows = []
    for t in tasks:
        broke = float(t["compress.broken_bonds"]) > 0  # the E-only runs stop at 1e-6 strain, before any break
        e = float(t["compress.youngs_modulus"])
        height_nm = float(t["packing.box"].split(",")[2]) * 1e9  # the box's z edge
        rows.append({"side_nm": int(float(t["side_nm"])), "height_nm": round(height_nm, 6), "seed": int(t["seed"]),
                     "particles": int(float(t["compress.particles"])), "bonds": int(float(t["compress.bonds"])),
                     "youngs_modulus_gpa": e * 1e-9, "youngs_modulus_gpa_sd": "", "bulk_factor": e / BOND_YOUNGS_MODULUS,
                     "bulk_factor_sd": "", "strength_mpa": float(t["compress.strength"]) * 1e-6 if broke else "",
                     "strength_mpa_sd": "", "strain_at_peak": float(t["compress.strain_at_peak"]) if broke else "",
                     "seconds": float(t["compress.seconds"])})
    rows.sort(key=lambda r: (r["side_nm"], r["seed"]))
    for side in sorted({r["side_nm"] for r in rows}):
        level = [r for r in rows if r["side_nm"] == side]
        summary = {"side_nm": side, "height_nm": level[0]["height_nm"], "seed": "mean", "seconds": ""}
        for name in ("particles", "bonds", "youngs_modulus_gpa", "bulk_factor", "strength_mpa", "strain_at_peak"):
            values = [r[name] for r in level if r[name] != ""]
            m, sd = mean_sd(values) if values else ("", "")
            summary[name] = m
            if name + "_sd" in COLUMNS:
                summary[name + "_sd"] = sd
        rows.append(summary)
        print(f"side {side} nm: {len(level)} samples, K_E {summary['bulk_factor']:.4g} +- {summary['bulk_factor_sd']:.2g}"
              + (f", strength {summary['strength_mpa']:.4g} +- {summary['strength_mpa_sd']:.2g} MPa"
                 if summary["strength_mpa"] != "" else ""))
    path = os.path.join(data, "opal_bulk_study.csv")
    write_table(path, {k: [r.get(k, "") for r in rows] for k in COLUMNS},
                "examples/opal/bulk_study.toml: pore-free FBA silica (porosity 0.38, d = 15 nm, periodic sides), "
                "E_b 6.53 GPa, sigma_max 94.3 MPa, static solver; K_E = E / E_b (eq. 20)")
    print(f"wrote {path} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
