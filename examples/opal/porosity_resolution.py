#!/usr/bin/env python3
"""The porosity study at three resolutions (docs/reproduction.md, the `_dd51` rows of
`opal.porosity_*`, `opal.eq24_b`, `opal.eq25_*`, `opal.eq26_*`): the samples of
examples/study/opal_porosity_paper.toml (scale 1, pores 9.2 particle diameters across; its
per-sample table DATA/opal_porosity_paper.csv, porosity_tables.py) and of
examples/study/opal_porosity_resolution.toml (the samples scaled by 0.6 and 0.75: D/d = 5.12 and
6.65, the same pore count and box in units of the pore spacing), with the paper's bonds and the
static solver; with --modulus their E-only samples (opal_porosity_paper_modulus.toml,
DATA/opal_porosity_paper_modulus.csv, and opal_porosity_resolution_modulus.toml: the compression
stopped after its first linear solve). Writes

  DATA/opal_porosity_resolution_samples.csv   one row per sample of the scaled study (scale, D/d
  (--modulus: _modulus_samples.csv)           and porosity_tables.py's columns); --study adds a
                                              study folder's samples to it (a sample replaces the
                                              table's of the same scale, pore fraction and seed),
                                              so the tables below regenerate from DATA alone
  DATA/opal_porosity_resolution.csv           per scale and pore fraction: D/d, particles, E and
  (--modulus: _modulus.csv, E only)           strength (mean and SD over the seeds every scale
                                              holds); then per scale (pore_fraction empty) the
                                              laws fitted per seed over the pore fractions all
                                              scales hold, (where a scale has more) over all of
                                              its pore fractions and (not with --modulus, where
                                              the shared ones reach beyond it) over
                                              COMPARISON_RANGE, 0.49-0.63 (column fitted_over), as
                                              porosity_tables.py fits them
                                              (packlab.fit_porosity_law; eps the box's pore
                                              fraction): eq. 25 E0 and m (E0 free), eq. 24 b (E0 of
                                              eq. 25), eq. 26 sigma0 and b (sigma0 free; not with
                                              --modulus); mean and SD over the seeds; then rows
                                              scale = "D/d=51" (seeds: the samples behind it; _sd:
                                              the extrapolation's uncertainty): each quantity's
                                              trend over the resolution taken at the paper's
                                              D/d = 51 as resolution_extrapolation.py does (q =
                                              q_inf + c d/D over every sample or per-seed fit;
                                              uncertainty: the fit's standard error and half the
                                              spread of the laws 1/x, 1/x^2, 1/sqrt(x)), those over
                                              the shared pore fractions first

usage: porosity_resolution.py [--modulus] [--study RESOLUTION_OUT] [DATA]
       (DATA defaults to docs/data of this checkout; needs the packlab Python module:
       PYTHONPATH=python:build/python)"""

import argparse
import math
import os
import sys

import numpy as np

import packlab
from packlab.reproduction import mean_sd

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from porosity_tables import SAMPLE_COLUMNS, merged, study_samples, table_samples, write  # noqa: E402
from resolution_extrapolation import LAWS, TARGET, fit as fit_law  # noqa: E402

PARTICLE_DIAMETER = 15e-9
SCALE1_PORE_DIAMETER = 138e-9  # opal_porosity_paper.toml


SCALED_COLUMNS = ("scale", "d_over_d")
# The pore fractions of the first compressed study (0.49-0.63): the laws over them beside those
# over the paper's six show how the range of the fit moves them (docs/reproduction.md, eq. 26).
COMPARISON_RANGE = (0.49, 0.63)
TABLES = {False: ("opal_porosity_paper.csv", "opal_porosity_resolution_samples.csv", "opal_porosity_resolution.csv"),
          True: ("opal_porosity_paper_modulus.csv", "opal_porosity_resolution_modulus_samples.csv",
                 "opal_porosity_resolution_modulus.csv")}  # scale 1, the scaled samples, the output


def samples(data, modulus, study=None):
    """{(scale, pore fraction, seed): (D/d, sample)} of the scale-1 per-sample table and of the
    scaled one, to which `study` (a --out folder), if given, is first added (and written)."""
    scale1, scaled, _ = TABLES[modulus]
    path = os.path.join(data, scaled)
    table = table_samples(path, SCALED_COLUMNS)
    if study:
        table = merged(table, study_samples(study, "--study", SCALED_COLUMNS), ("scale",))
        write(path, list(SCALED_COLUMNS) + SAMPLE_COLUMNS, table,
              "examples/study/opal_porosity_resolution" + ("_modulus" if modulus else "") + ".toml: the samples of "
              "opal_porosity_paper.toml scaled by 0.6 and 0.75; particles 15 nm; periodic random pores; static solver; "
              "paper's bonds" + ("; E only (max-strain 1e-6: the first linear solve, no break)" if modulus else ""))
    found = {(r["scale"], r["pore_fraction"], r["seed"]): (r["d_over_d"], r) for r in table}
    found |= {(1.0, r["pore_fraction"], r["seed"]): (SCALE1_PORE_DIAMETER / PARTICLE_DIAMETER, r)
              for r in table_samples(os.path.join(data, scale1))}
    return found


def shared_levels(found, script):
    """The scales of `found` (samples()), and the pore fractions and seeds every scale holds: the
    laws are fitted over the same levels at each. Exits (naming `script`) unless two scales share
    three pore fractions."""
    scales = sorted({k[0] for k in found})
    if len(scales) < 2:
        sys.exit(f"{script}: need samples at two scales (the scaled ones: run with --study RESOLUTION_OUT)")
    fractions = sorted(set.intersection(*({k[1] for k in found if k[0] == s} for s in scales)))
    seeds = sorted(set.intersection(*({k[2] for k in found if k[0] == s} for s in scales)))
    if len(fractions) < 3:
        sys.exit(f"{script}: need two scales sharing three pore fractions")
    return scales, fractions, seeds


def seed_laws(level, modulus=False):
    """Eq. 25, 24 and (unless `modulus`: E only) 26 fitted to one seed's samples (a list of
    samples over the pore fractions)."""
    eps = [r["pore_fraction_of_box"] for r in level]
    moduli = [r["youngs_modulus"] for r in level]
    power = packlab.fit_porosity_law("power", eps, moduli, 0.0)
    shared = packlab.fit_porosity_law("exponential", eps, moduli, power.e0)
    laws = {"eq25_E0": power.e0, "eq25_m": power.exponent, "eq24_b": shared.exponent}
    if not modulus:
        eq26 = packlab.fit_porosity_law("exponential", eps, [r["strength"] for r in level], 0.0)
        laws |= {"eq26_sigma0": eq26.e0, "eq26_b": eq26.exponent}
    return laws


def extrapolate(x, y):
    """The value at D/d = 51 of q = q_inf + c d/D and its uncertainty (resolution_extrapolation.py);
    None with fewer than three points or two resolutions."""
    x, y = np.array(x), np.array(y)
    if len(y) < 3 or len(set(x)) < 2:
        return None
    fits = {law: fit_law(x, y, law) for law in LAWS}
    values = [f[2] for f in fits.values()]
    first = fits["1/x"]
    return first[2], math.hypot(first[3], 0.5 * (max(values) - min(values)))


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", nargs="?", default=os.path.join(HERE, "..", "..", "docs", "data"))
    parser.add_argument("--study", help="the --out folder of examples/study/opal_porosity_resolution.toml "
                        "(--modulus: opal_porosity_resolution_modulus.toml)")
    parser.add_argument("--modulus", action="store_true", help="the E-only samples: E and eq. 24-25 only")
    args = parser.parse_args(argv[1:])
    found = samples(args.data, args.modulus, args.study)
    scales, fractions, seeds = shared_levels(found, "porosity_resolution")
    quantities = ["youngs_modulus"] + ([] if args.modulus else ["strength"])
    columns = (["scale", "d_over_d", "pore_fraction", "seeds", "particles"]
               + [q + s for q in quantities for s in ("_mean", "_sd")] + ["law", "fitted_over", "law_mean", "law_sd"])
    rows = []

    def row(**kw):
        rows.append({c: kw.get(c, "") for c in columns})

    per_sample = {}  # (pore fraction, quantity) -> [(D/d, value)]
    narrow = [f for f in fractions if COMPARISON_RANGE[0] <= f <= COMPARISON_RANGE[1]]
    if args.modulus or len(narrow) < 3 or narrow == fractions:
        narrow = None
    per_seed_law = {}  # (fitted over, law) -> [(D/d, value)], the shared pore fractions first
    for s in scales:
        ratio = next(found[k][0] for k in found if k[0] == s)
        own = sorted({k[1] for k in found if k[0] == s})
        for f in own:
            level = [found[(s, f, seed)][1] for seed in seeds if (s, f, seed) in found]
            values = {}
            for q in quantities:
                measured = [r[q] for r in level]
                if f in fractions:
                    per_sample.setdefault((f, q), []).extend((ratio, v) for v in measured)
                m, sd = mean_sd(measured)
                values |= {q + "_mean": f"{m:.6g}", q + "_sd": f"{sd:.3g}"}
            row(scale=f"{s:g}", d_over_d=f"{ratio:.4g}", pore_fraction=f"{f:g}", seeds=len(level),
                particles=f"{mean_sd([r['particles'] for r in level])[0]:.0f}", **values)
        # The laws over the pore fractions every scale holds (the trend below), and over all of
        # this scale's where it holds more (the paper's six, 0.39-0.63).
        for over in [fractions] + ([own] if own != fractions else []) + ([narrow] if narrow else []):
            laws = [seed_laws([found[(s, f, seed)][1] for f in over], args.modulus) for seed in seeds
                    if all((s, f, seed) in found for f in over)]
            if not laws:  # no seed holds every pore fraction of the range yet
                continue
            for name in laws[0]:
                values = [law[name] for law in laws]
                if over is fractions or over is narrow:
                    per_seed_law.setdefault((over is narrow, name), []).extend((ratio, v) for v in values)
                m, sd = mean_sd(values)
                row(scale=f"{s:g}", d_over_d=f"{ratio:.4g}", seeds=len(values), law=name,
                    fitted_over=f"{over[0]:g}-{over[-1]:g}", law_mean=f"{m:.5g}", law_sd=f"{sd:.3g}")
    target = f"D/d={TARGET:g}"
    for (f, quantity), pairs in sorted(per_sample.items()):
        at_target = extrapolate([p[0] for p in pairs], [p[1] for p in pairs])
        if at_target is None:
            continue
        value, err = at_target
        row(scale=target, d_over_d=f"{TARGET:g}", pore_fraction=f"{f:g}", seeds=len(pairs),
            **{quantity + "_mean": f"{value:.6g}", quantity + "_sd": f"{err:.3g}"})
    for (is_narrow, name), pairs in sorted(per_seed_law.items(), key=lambda item: item[0][0]):
        at_target = extrapolate([p[0] for p in pairs], [p[1] for p in pairs])
        if at_target is None:
            continue
        value, err = at_target
        over = narrow if is_narrow else fractions
        span = f"{over[0]:g}-{over[-1]:g}"
        row(scale=target, d_over_d=f"{TARGET:g}", seeds=len(pairs), law=name, fitted_over=span,
            law_mean=f"{value:.5g}", law_sd=f"{err:.3g}")
        print(f"{name}: " + ", ".join(f"D/d {r['d_over_d']} over {r['fitted_over']}: {r['law_mean']} +- {r['law_sd']}"
                                      for r in rows if r["law"] == name and r["fitted_over"] == span))
    write(os.path.join(args.data, TABLES[args.modulus][2]), columns, rows,
          "examples/opal/porosity_resolution.py" + (" --modulus: E-only" if args.modulus else ": the")
          + " random-pore porosity samples at scales " + ", ".join(f"{s:g}" for s in scales)
          + ("; E [Pa]" if args.modulus else "; E [Pa], strength [Pa]") + "; laws over pore fractions "
          + ", ".join(f"{f:g}" for f in fractions) + f", seeds {', '.join(map(str, seeds))}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
