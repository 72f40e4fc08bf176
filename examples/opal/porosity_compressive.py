#!/usr/bin/env python3
"""The reading of eq. 16 against the porosity laws (docs/reproduction.md, `opal.eq26_*`): the
D/d = 5.12 random-pore samples (scale 0.6 of examples/study/opal_porosity_resolution.toml, pore
fractions 0.39-0.63, seeds 1-3) compressed with eq. 16 on stretched bonds only (MUSEN's default,
the rows' setting) and on every bond (examples/study/opal_porosity_compressive.toml). Writes

  DATA/opal_porosity_compressive.csv   per reading and pore fraction: E and strength (mean and
                                       SD over the seeds), bonds broken by the peak's end; then per
                                       reading (pore_fraction empty) the laws fitted per seed over
                                       the six pore fractions as porosity_resolution.py fits them
                                       (eq. 25 m, eq. 24 b, eq. 26 sigma0 and b): mean and SD

usage: porosity_compressive.py RESOLUTION_OUT COMPRESSIVE_OUT [DATA]
       (needs the packlab Python module: PYTHONPATH=python:build/python)"""

import os
import sys

from packlab.reproduction import mean_sd
from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from porosity_resolution import SCALED_COLUMNS, seed_laws  # noqa: E402
from porosity_tables import study_samples  # noqa: E402

SCALE = 0.6  # D/d = 5.12
COLUMNS = ["eq16_applies_to", "pore_fraction", "seeds", "youngs_modulus_mean", "youngs_modulus_sd", "strength_mean",
           "strength_sd", "broken_bonds_mean", "law", "law_mean", "law_sd"]


def by_level(out):
    """{pore fraction: {seed: sample}} of the scale-0.6 samples of a study."""
    found = {}
    for r in study_samples(out, "porosity_compressive", SCALED_COLUMNS):
        if r["scale"] == SCALE:
            found.setdefault(r["pore_fraction"], {})[r["seed"]] = r
    return found


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    data = argv[3] if len(argv) > 3 else os.path.join(HERE, "..", "..", "docs", "data")
    rows = []
    for reading, out in (("stretched bonds", argv[1]), ("every bond", argv[2])):
        levels = by_level(out)
        if not levels:
            sys.exit(f"porosity_compressive: no finished scale-{SCALE} task in {out}/tasks.csv")
        for fraction in sorted(levels):
            level = list(levels[fraction].values())
            e = mean_sd([r["youngs_modulus"] for r in level])
            s = mean_sd([r["strength"] for r in level])
            b = mean_sd([r["broken_bonds"] for r in level])
            rows.append({"eq16_applies_to": reading, "pore_fraction": fraction, "seeds": len(level),
                         "youngs_modulus_mean": e[0], "youngs_modulus_sd": e[1], "strength_mean": s[0],
                         "strength_sd": s[1], "broken_bonds_mean": b[0]})
        # The laws per seed over the pore fractions that seed has at every level.
        seeds = sorted(set.intersection(*(set(v) for v in levels.values())))
        laws = [seed_laws([levels[f][seed] for f in sorted(levels)]) for seed in seeds]
        for law in ("eq25_m", "eq24_b", "eq26_sigma0", "eq26_b"):
            m, sd = mean_sd([x[law] for x in laws]) if laws else ("", "")
            rows.append({"eq16_applies_to": reading, "pore_fraction": "", "seeds": len(laws), "law": law,
                         "law_mean": m, "law_sd": sd})
            print(f"{reading}: {law} = {m:.4g} +- {sd:.2g} ({len(laws)} seeds over {len(levels)} pore fractions)")
    path = os.path.join(data, "opal_porosity_compressive.csv")
    write_table(path, {k: [r.get(k, "") for r in rows] for k in COLUMNS},
                "examples/opal/porosity_compressive.py: random-pore samples at D/d = 5.12, paper's bonds, static "
                "solver, eq. 16 on stretched bonds only or on every bond; E, strength [Pa]")
    print(f"wrote {path} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
