#!/usr/bin/env python3
"""Which bonds eq. 16 may break, tested on the porosity study's samples (docs/reproduction.md,
`opal.porosity_strength_*` and `opal.eq26_*`): the same samples compressed with eq. 16 on
stretched bonds only (MUSEN's reading, packlab's default: examples/study/opal_porosity_paper.toml)
and on compressed bonds too (examples/study/opal_porosity_paper_compressive.toml). Writes

  DATA/opal_porosity_breakage_reading.csv   per reading and pore fraction: E and strength, mean
                                            and SD over the seeds; and per reading (pore_fraction
                                            empty) the exponent b of eq. 26, sigma = sigma0
                                            exp(-b eps), fitted per seed over the pore fractions
                                            both studies hold by porosity_tables.py's fit
                                            (packlab.fit_porosity_law, sigma0 free; eps: the box's
                                            pore fraction), mean and SD over the seeds

usage: breakage_reading.py TENSION_OUT COMPRESSIVE_OUT [DATA]   (the two studies' --out folders;
       needs the packlab Python module: PYTHONPATH=python:build/python)"""

import os
import sys

import packlab
from packlab.reproduction import mean_sd
from packlab.studies import finished_tasks
from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))


def samples(out):
    return {(float(t["opal.pore-fraction"]), int(t["seed"])): t for t in finished_tasks(out)}


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    data = argv[3] if len(argv) > 3 else os.path.join(HERE, "..", "..", "docs", "data")
    readings = {"tension_only": samples(argv[1]), "tension_and_compression": samples(argv[2])}
    common = set.intersection(*(set(s) for s in readings.values()))
    fractions = sorted({f for f, _ in common})
    seeds = sorted({s for _, s in common})
    if len(fractions) < 2:
        sys.exit("breakage_reading: the two studies share fewer than two pore fractions")
    rows = []
    for name, found in readings.items():
        for f in fractions:
            level = [found[(f, s)] for s in seeds if (f, s) in common]
            e_mean, e_sd = mean_sd(float(t["compress.youngs_modulus"]) for t in level)
            s_mean, s_sd = mean_sd(float(t["compress.strength"]) for t in level)
            b_mean, b_sd = mean_sd(float(t["compress.broken_bonds"]) for t in level)
            rows.append({"reading": name, "pore_fraction": f"{f:g}", "seeds": len(level),
                         "youngs_modulus_mean": f"{e_mean:.6g}", "youngs_modulus_sd": f"{e_sd:.3g}",
                         "strength_mean": f"{s_mean:.6g}", "strength_sd": f"{s_sd:.3g}",
                         "broken_bonds_mean": f"{b_mean:.6g}", "eq26_b_mean": "", "eq26_b_sd": ""})
        per_seed = []
        for s in seeds:
            level = [found[(f, s)] for f in fractions if (f, s) in common]
            if len(level) >= 3:  # sigma0 and b free
                per_seed.append(packlab.fit_porosity_law(
                    "exponential", [float(t["opal.parameters.pores.pore_fraction_of_region"]) for t in level],
                    [float(t["compress.strength"]) for t in level], 0.0).exponent)
        m, sd = mean_sd(per_seed)
        rows.append({"reading": name, "pore_fraction": "", "seeds": len(per_seed), "youngs_modulus_mean": "",
                     "youngs_modulus_sd": "", "strength_mean": "", "strength_sd": "", "broken_bonds_mean": "",
                     "eq26_b_mean": f"{m:.4g}", "eq26_b_sd": f"{sd:.3g}"})
    path = os.path.join(data, "opal_porosity_breakage_reading.csv")
    write_table(path, {k: [r[k] for r in rows] for k in rows[0]},
                "examples/opal/breakage_reading.py: eq. 16 on stretched bonds only against stretched and "
                "compressed bonds, same samples; E [Pa], strength [Pa]; eq26_b over pore fractions " +
                ", ".join(f"{f:g}" for f in fractions))
    print(f"wrote {path} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
