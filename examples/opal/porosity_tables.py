#!/usr/bin/env python3
"""Tables of the porosity study over the paper's range (examples/study/opal_porosity_paper.toml,
bpm-inverse-opals §4, Fig. 14, eq. 24-26):

  DATA/opal_porosity_paper.csv         one row per compressed sample (pore fraction, seed, pores,
                                       the porosity eq. 1 removes, particles, bonds, E, strength),
                                       from that study's tasks.csv (--strength)
  DATA/opal_porosity_paper_modulus.csv the same for the E-only samples of
                                       examples/study/opal_porosity_paper_modulus.toml (all six
                                       porosities, five seeds; --modulus)
  DATA/opal_porosity_paper_levels.csv  mean and SD over the seeds of each pore fraction (E over
                                       the E-only samples where there are any, strength over the
                                       compressed ones)
  DATA/opal_porosity_paper_fits.csv    eq. 22/24 (E0 exp(-b eps)), eq. 23/25 (E0 (1 - eps)^m) over
                                       the E-only samples (else the compressed ones) and eq. 26
                                       (sigma0 exp(-b eps)) over the compressed samples, with eps the
                                       pore fraction (the paper's: "porosity" set by the number of
                                       pores, 74 % for its touching FCC pores) and with eps the
                                       porosity eq. 1 removes; E0 held at the pore-free sample's
                                       modulus (docs/data/opal_runs.csv, run bulk) or at the bulk
                                       study's (opal_bulk_study.csv, 300 nm), fitted, or (eq. 24)
                                       held at eq. 25's; over all samples and per seed (columns
                                       samples, pore_fractions: what each fit is over)

The per-sample tables change only with the study folders given, whose samples are added to them
(a sample replaces the table's of the same pore fraction and seed: a study run in parts adds
up); the levels and fits are always computed from the per-sample tables in DATA, so they can be
regenerated from the repository alone. The samples both studies ran must agree (the same pores, particles, bonds and
E): the script stops otherwise.

usage: porosity_tables.py [--strength STUDY_OUT] [--modulus MODULUS_OUT] [DATA]
       (DATA defaults to docs/data of this checkout; needs the packlab Python module for the fits:
       PYTHONPATH=python:build/python)"""

import argparse
import csv
import math
import os
import sys

import packlab
from packlab.reproduction import mean_sd, read_table
from packlab.studies import finished_tasks
from packlab.tables import merged_rows, write_table

HERE = os.path.dirname(os.path.abspath(__file__))
PAPER_EQ26_B = 3.85  # bpm-inverse-opals eq. 26: strength = 576.3 exp(-3.85 eps) MPa
INTEGER_COLUMNS = ("pores", "particles", "bonds", "broken_bonds")
SAMPLE_COLUMNS = ["pore_fraction", "seed", "pores", "pore_fraction_of_box", "porosity", "particles", "bonds",
                  "youngs_modulus", "strength", "broken_bonds", "seconds"]
FIELDS = {"pores": "opal.parameters.pores.count", "pore_fraction_of_box": "opal.parameters.pores.pore_fraction_of_region",
          "porosity": "opal.results.porosity", "particles": "opal.results.particles", "bonds": "opal.results.bonds",
          "youngs_modulus": "compress.youngs_modulus", "strength": "compress.strength",
          "broken_bonds": "compress.broken_bonds", "seconds": "compress.seconds"}
EXTRA_FIELDS = {"scale": "scale", "d_over_d": "opal.parameters.pores.ratio_to_mean_particle_diameter"}


def write(path, header, rows, comment):
    write_table(path, {k: [r[k] for r in rows] for k in header}, comment)
    print(f"wrote {path} ({len(rows)} rows)")


def pore_free_modulus(data):
    with open(os.path.join(data, "opal_runs.csv")) as f:
        for r in csv.DictReader(f):
            if r["run"] == "bulk":
                return float(r["youngs_modulus"])
    sys.exit("porosity_tables: no bulk run in opal_runs.csv")


def bulk_study_modulus(data):
    """The bulk study's E at its largest sample (opal_bulk_study.csv, mean over its packings)."""
    with open(os.path.join(data, "opal_bulk_study.csv")) as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#")) if r["seed"] == "mean"]
    if not rows:
        sys.exit("porosity_tables: no mean row in opal_bulk_study.csv")
    return 1e9 * float(max(rows, key=lambda r: float(r["side_nm"]))["youngs_modulus_gpa"])


def sample_key(row, identity=()):
    """What identifies a sample: its pore fraction and seed, after the `identity` columns (the
    scale of a study over resolutions)."""
    return tuple(row[c] for c in identity) + (row["pore_fraction"], row["seed"])


def study_samples(out, name, extra=()):
    """One row per finished task of a study folder (SAMPLE_COLUMNS, then the columns `extra` names
    from EXTRA_FIELDS: the scale and D/d of a study over resolutions)."""
    tasks = finished_tasks(out)
    if not tasks:
        sys.exit(f"porosity_tables: no finished task in {out}/tasks.csv ({name})")
    rows = []
    for t in tasks:
        row = {"pore_fraction": float(t["opal.pore-fraction"]), "seed": int(t["seed"])}
        for column, field in FIELDS.items():
            v = float(t[field])
            row[column] = int(v) if column in INTEGER_COLUMNS else v
        row |= {column: float(t[EXTRA_FIELDS[column]]) for column in extra}
        rows.append(row)
    return sorted(rows, key=lambda r: sample_key(r, extra))


def table_samples(path, extra=()):
    """The per-sample table `path` under DATA as rows of numbers ([] if missing)."""
    rows = []
    for r in read_table(path):
        row = {c: (int(float(r[c])) if c in INTEGER_COLUMNS or c == "seed" else float(r[c]))
               for c in list(extra) + SAMPLE_COLUMNS}
        rows.append(row)
    return rows


def merged(table, study, identity=()):
    """The per-sample table with a study folder's samples added: a sample of the folder replaces
    the table's with the same key (sample_key: pore fraction and seed, after the `identity`
    columns, the scale; a study run in parts, e.g. seeds 4-5 later, adds to what the table
    holds)."""
    return merged_rows(table, study, lambda r: sample_key(r, identity))


def check_same_samples(strength, modulus):
    """The samples both studies ran are the same samples: pores, particles and bonds equal, E
    equal to round-off (the static solver's E is its first solve's, the same with or without the
    breaks after it). Returns how many were compared and the largest relative E difference."""
    by_key = {(r["pore_fraction"], r["seed"]): r for r in modulus}
    compared, worst = 0, 0.0
    for r in strength:
        m = by_key.get((r["pore_fraction"], r["seed"]))
        if m is None:
            continue
        for column in ("pores", "particles", "bonds"):
            if r[column] != m[column]:
                sys.exit(f"porosity_tables: pore fraction {r['pore_fraction']:g}, seed {r['seed']}: {column} "
                         f"{r[column]} (compressed) against {m[column]} (E only): not the same sample")
        diff = abs(r["youngs_modulus"] - m["youngs_modulus"]) / r["youngs_modulus"]
        if diff > 1e-9:
            sys.exit(f"porosity_tables: pore fraction {r['pore_fraction']:g}, seed {r['seed']}: E "
                     f"{r['youngs_modulus']:.10g} (compressed) against {m['youngs_modulus']:.10g} (E only)")
        compared, worst = compared + 1, max(worst, diff)
    return compared, worst


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", nargs="?", default=os.path.join(HERE, "..", "..", "docs", "data"))
    parser.add_argument("--strength", help="the --out folder of examples/study/opal_porosity_paper.toml")
    parser.add_argument("--modulus", help="the --out folder of examples/study/opal_porosity_paper_modulus.toml")
    args = parser.parse_args(argv[1:])
    data = args.data
    strength_path = os.path.join(data, "opal_porosity_paper.csv")
    modulus_path = os.path.join(data, "opal_porosity_paper_modulus.csv")
    comment = ("examples/study/opal_porosity_paper.toml: the paper's sample (8.05 um^2 x 2.01 um) scaled by 150/762; "
               "particles 15 nm; pores 138 nm packed at 150 nm; periodic random pores; static solver; paper's bonds")
    if args.strength:
        write(strength_path, SAMPLE_COLUMNS, merged(table_samples(strength_path), study_samples(args.strength, "--strength")),
              comment)
    if args.modulus:
        write(modulus_path, SAMPLE_COLUMNS, merged(table_samples(modulus_path), study_samples(args.modulus, "--modulus")),
              comment.replace("opal_porosity_paper.toml", "opal_porosity_paper_modulus.toml") +
              "; E only (max-strain 1e-6: the first linear solve, no break)")
    samples = table_samples(strength_path)
    moduli = table_samples(modulus_path)
    if not samples:
        sys.exit(f"porosity_tables: no samples in {strength_path} (run with --strength STUDY_OUT)")
    if moduli:
        compared, worst = check_same_samples(samples, moduli)
        print(f"{compared} samples in both studies: the same pores, particles and bonds; E within {worst:.1e}")
    else:
        moduli = samples

    levels = []
    for f in sorted({r["pore_fraction"] for r in samples + moduli}):
        rs = [r for r in samples if r["pore_fraction"] == f]
        ms = [r for r in moduli if r["pore_fraction"] == f]
        row = {"pore_fraction": f, "samples": len(rs), "modulus_samples": len(ms)}
        for name in ("pore_fraction_of_box", "porosity", "particles"):
            row[name], row[name + "_sd"] = mean_sd([r[name] for r in ms])
        row["youngs_modulus"], row["youngs_modulus_sd"] = mean_sd([r["youngs_modulus"] for r in ms])
        row["strength"], row["strength_sd"] = mean_sd([r["strength"] for r in rs]) if rs else ("", "")
        levels.append(row)
    write(os.path.join(data, "opal_porosity_paper_levels.csv"), list(levels[0].keys()), levels,
          comment + "; mean and SD over the seeds: E over modulus_samples (the E-only samples where there are any), "
          "strength over samples (the compressed ones)")

    e0_bulk = pore_free_modulus(data)
    e0_study = bulk_study_modulus(data)
    fits = []

    def span(rows):
        fractions = sorted({r["pore_fraction"] for r in rows})
        return f"{fractions[0]:g}-{fractions[-1]:g} ({len(fractions)})"

    def fit(measure, quantity, law, held, seed, rows, e0):
        g = packlab.fit_porosity_law(law, [r[measure] for r in rows], [r[quantity] for r in rows], e0)
        fits.append({"eps": measure, "quantity": quantity, "law": law, "e0_held": held, "seed": seed, "e0": g.e0,
                     "e0_err": g.e0_err, "exponent": g.exponent, "exponent_err": g.exponent_err,
                     "rms_relative": g.rms_relative, "samples": len(rows), "pore_fractions": span(rows)})
        return g

    # Over all samples, and per seed (each seed is one realization of the porosities, so the SD
    # of a law's parameters over the seeds is the SD over realizations). E over the E-only
    # samples (six porosities, five seeds: the paper's), the strength over the compressed ones.
    # Each seed's fit spans the pore fractions every seed holds, so that the seeds are
    # realizations of the same estimator (a study run in parts may hold a pore fraction for some
    # seeds only: its samples enter the levels, not the laws).
    def at_common_fractions(rows):
        seeds = {r["seed"] for r in rows}
        common = {f for f in {r["pore_fraction"] for r in rows}
                  if {r["seed"] for r in rows if r["pore_fraction"] == f} == seeds}
        return [r for r in rows if r["pore_fraction"] in common]

    def of_seed(rows, seed):
        return rows if seed == "all" else [r for r in rows if r["seed"] == seed]

    law_moduli, law_samples = at_common_fractions(moduli), at_common_fractions(samples)
    for measure in ("pore_fraction_of_box", "porosity"):
        for seed in ["all"] + sorted({r["seed"] for r in law_moduli}):
            rows = of_seed(law_moduli, seed)
            if len(rows) < 3:
                continue
            fit(measure, "youngs_modulus", "exponential", "1", seed, rows, e0_bulk)
            fit(measure, "youngs_modulus", "exponential", "0", seed, rows, 0.0)
            fit(measure, "youngs_modulus", "power", "1", seed, rows, e0_bulk)
            # E0 of the bulk study's five packings (300 nm; 4 % above run.sh's one sample): how
            # much the held laws depend on which pore-free modulus is held.
            fit(measure, "youngs_modulus", "exponential", "bulk_study", seed, rows, e0_study)
            fit(measure, "youngs_modulus", "power", "bulk_study", seed, rows, e0_study)
            power = fit(measure, "youngs_modulus", "power", "0", seed, rows, 0.0)
            # The paper's eq. 24 and 25 share E0 = 22.06 GPa: eq. 24 with eq. 25's E0.
            fit(measure, "youngs_modulus", "exponential", "shared", seed, rows, power.e0)
        for seed in ["all"] + sorted({r["seed"] for r in law_samples}):
            rows = of_seed(law_samples, seed)
            if len(rows) < 3:
                continue
            fit(measure, "strength", "exponential", "0", seed, rows, 0.0)
            # eq. 26 with b held at the paper's 3.85: the sigma0 that the level of the strengths
            # alone gives (relative least squares, as the fits above), to tell how much of the
            # sigma0 miss follows from the b miss.
            g = [math.exp(-PAPER_EQ26_B * r[measure]) for r in rows]
            s = [r["strength"] for r in rows]
            sigma0 = sum(gi / si for gi, si in zip(g, s)) / sum((gi / si) ** 2 for gi, si in zip(g, s))
            rms = math.sqrt(sum(((sigma0 * gi - si) / si) ** 2 for gi, si in zip(g, s)) / len(s))
            fits.append({"eps": measure, "quantity": "strength", "law": "exponential", "e0_held": "b_paper",
                         "seed": seed, "e0": sigma0, "e0_err": 0.0, "exponent": PAPER_EQ26_B, "exponent_err": 0.0,
                         "rms_relative": rms, "samples": len(rows), "pore_fractions": span(rows)})
    write(os.path.join(data, "opal_porosity_paper_fits.csv"), list(fits[0].keys()), fits,
          comment + f"; fits over all samples and per seed; e0_held 1: at the pore-free sample's {e0_bulk:.4g} Pa "
          f"(opal_runs.csv bulk), bulk_study: at the bulk study's {e0_study:.4g} Pa (opal_bulk_study.csv, 300 nm), "
          "0: fitted, shared: at the E0 of the power law fitted to the same samples; b_paper: the strength's "
          "sigma0 with b held at the paper's 3.85")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
