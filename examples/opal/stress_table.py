#!/usr/bin/env python3
"""Table 2 of bpm-inverse-opals (eq. 21) from examples/opal/stress_table.toml's study: the
particle stresses per material at the applied stress of 31.3 MPa, uncoated and 20 nm coated,
FCC opal at D/d = 19.4, FBA seeds 1-3.

  DATA/opal_stress_table_samples.csv  one row per sample and material: coating, seed, material
                                      (silica, titania), particles, the snapshot's strain and
                                      stress, mean and SD of sigma_xx and sigma_zz [MPa],
                                      compression positive as in the paper's table
  DATA/opal_stress_table.csv          per coating and material: the paper's four values, ours
                                      as the mean over the seeds of each sample's mean and SD
                                      (with the SD over the seeds of the means), and the ratio
                                      axial / vertical

The substrate (type 4) is left out: the paper's sample has none. Types follow core/packing.hpp:
0 structural (silica), 3 coating (titania).

usage: stress_table.py STUDY_OUT [DATA]   (DATA defaults to docs/data of this checkout)"""

import csv
import os
import statistics
import sys

from packlab.studies import study_table_arguments
from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))
MATERIALS = {0: "silica", 3: "titania"}
# bpm-inverse-opals Table 2 [MPa]: mean and SD of sigma_xx, mean and SD of sigma_zz (compression
# positive), at 31.3 MPa.
PAPER = {(0, "silica"): (44.5, 63.2, 162.8, 135.3),
         (20, "silica"): (18.1, 14.9, 88.9, 44.32),
         (20, "titania"): (40.88, 42.0, 158.0, 121.2)}
SAMPLE_COLUMNS = ["coating_nm", "seed", "material", "particles", "strain", "stress_mpa", "mean_xx_mpa", "sd_xx_mpa",
                  "mean_zz_mpa", "sd_zz_mpa"]
TABLE_COLUMNS = ["coating_nm", "material", "samples", "paper_mean_xx", "paper_sd_xx", "paper_mean_zz", "paper_sd_zz",
                 "mean_xx", "sd_xx", "mean_xx_seed_sd", "mean_zz", "sd_zz", "mean_zz_seed_sd", "axial_to_vertical",
                 "paper_axial_to_vertical"]


def read_snapshot(run_dir, requested):
    """Rows of particle_stress.csv of the snapshot requested at this applied stress [Pa]."""
    with open(os.path.join(run_dir, "particle_stress.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    if rows and "requested_stress" in rows[0]:
        rows = [r for r in rows if r["requested_stress"] and float(r["requested_stress"]) == requested]
    else:  # written before the column: the static solver's snapshot carries the requested stress
        rows = [r for r in rows if abs(float(r["stress"]) - requested) <= 1e-9 * requested]
    if not rows:
        sys.exit(f"stress_table: no snapshot at {requested:g} Pa in {run_dir}/particle_stress.csv")
    return rows


def main(argv):
    out, data, tasks = study_table_arguments(argv, __doc__, os.path.join(HERE, "..", "..", "docs", "data"))
    samples = []
    for t in tasks:
        coating = int(float(t["coating_nm"]))
        for r in read_snapshot(os.path.join(out, "runs", "compress-" + t["task"]), 31.3e6):
            material = MATERIALS.get(int(r["type"]))
            if material is None:
                continue
            samples.append({"coating_nm": coating, "seed": int(t["seed"]), "material": material,
                            "particles": int(r["particles"]), "strain": float(r["strain"]),
                            "stress_mpa": float(r["stress"]) / 1e6,
                            # compression positive, as the paper's table
                            "mean_xx_mpa": -float(r["mean_xx"]) / 1e6, "sd_xx_mpa": float(r["sd_xx"]) / 1e6,
                            "mean_zz_mpa": -float(r["mean_zz"]) / 1e6, "sd_zz_mpa": float(r["sd_zz"]) / 1e6})
    samples.sort(key=lambda s: (s["coating_nm"], s["material"], s["seed"]))
    write_table(os.path.join(data, "opal_stress_table_samples.csv"),
                {k: [s[k] for s in samples] for k in SAMPLE_COLUMNS},
                comment="examples/opal/stress_table.toml -> examples/opal/stress_table.py: particle stresses "
                        "(eq. 21) at 31.3 MPa, compression positive, FCC opal D/d 19.4")
    table = []
    for (coating, material), paper in PAPER.items():
        group = [s for s in samples if s["coating_nm"] == coating and s["material"] == material]
        if not group:
            continue

        def mean(key):
            return statistics.fmean(s[key] for s in group)

        def seed_sd(key):
            return statistics.stdev(s[key] for s in group) if len(group) > 1 else float("nan")

        table.append({"coating_nm": coating, "material": material, "samples": len(group),
                      "paper_mean_xx": paper[0], "paper_sd_xx": paper[1], "paper_mean_zz": paper[2],
                      "paper_sd_zz": paper[3], "mean_xx": mean("mean_xx_mpa"), "sd_xx": mean("sd_xx_mpa"),
                      "mean_xx_seed_sd": seed_sd("mean_xx_mpa"), "mean_zz": mean("mean_zz_mpa"),
                      "sd_zz": mean("sd_zz_mpa"), "mean_zz_seed_sd": seed_sd("mean_zz_mpa"),
                      "axial_to_vertical": mean("mean_xx_mpa") / mean("mean_zz_mpa"),
                      "paper_axial_to_vertical": paper[0] / paper[2]})
    write_table(os.path.join(data, "opal_stress_table.csv"), {k: [r[k] for r in table] for k in TABLE_COLUMNS},
                comment="examples/opal/stress_table.py: Table 2 at 31.3 MPa [MPa], compression positive; ours = "
                        "mean over FBA seeds 1-3 of each sample's mean and SD, *_seed_sd = SD of the means")
    for row in table:
        print(f"{row['coating_nm']:>2} nm {row['material']:8s} xx {row['mean_xx']:6.1f} +- {row['sd_xx']:6.1f} "
              f"(paper {row['paper_mean_xx']} +- {row['paper_sd_xx']}), zz {row['mean_zz']:6.1f} +- "
              f"{row['sd_zz']:6.1f} (paper {row['paper_mean_zz']} +- {row['paper_sd_zz']})")


if __name__ == "__main__":
    main(sys.argv)
