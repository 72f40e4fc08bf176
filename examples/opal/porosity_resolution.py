#!/usr/bin/env python3
"""The porosity study at three resolutions (docs/reproduction.md, `opal.porosity_*`,
`opal.eq24_b`, `opal.eq25_*`, `opal.eq26_*`): the samples of examples/study/opal_porosity_paper.toml
(scale 1, pores 9.2 particle diameters across) and of examples/study/opal_porosity_resolution.toml
(the samples scaled by 0.6 and 0.75: D/d = 5.12 and 6.65, the same pore count and box in
units of the pore spacing), with the paper's bonds and the static solver. Writes

  DATA/opal_porosity_resolution.csv   per scale and pore fraction: D/d, particles, E and strength
                                      (mean and SD over the seeds); then per scale (pore_fraction
                                      empty) the laws fitted per seed over the pore fractions all
                                      scales hold and (where a scale has more) over all of its
                                      pore fractions (column fitted_over), as porosity_tables.py
                                      fits them
                                      (packlab.fit_porosity_law; eps the box's pore fraction):
                                      eq. 25 E0 and m (E0 free), eq. 24 b (E0 of eq. 25), eq. 26
                                      sigma0 and b (sigma0 free); mean and SD over the seeds; then
                                      rows scale = "D/d=51" (seeds: the samples behind it; _sd:
                                      the extrapolation's uncertainty): each quantity's trend over the
                                      resolution taken at the paper's D/d = 51 as
                                      resolution_extrapolation.py does (q = q_inf + c d/D over every
                                      sample or per-seed fit; uncertainty: the fit's standard error
                                      and half the spread of the laws 1/x, 1/x^2, 1/sqrt(x))

usage: porosity_resolution.py SCALE1_OUT RESOLUTION_OUT [DATA]   (the two studies' --out folders;
       needs the packlab Python module: PYTHONPATH=python:build/python)"""

import math
import os
import sys

import numpy as np

import packlab
from packlab.reproduction import mean_sd
from packlab.studies import finished_tasks
from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from resolution_extrapolation import LAWS, TARGET, fit as fit_law  # noqa: E402

PARTICLE_DIAMETER = 15e-9
SCALE1_PORE_DIAMETER = 138e-9  # opal_porosity_paper.toml


def samples(out, scaled):
    """{(scale, pore fraction, seed): (D/d, task)} of a study's finished tasks."""
    found = {}
    for t in finished_tasks(out):
        scale = float(t["scale"]) if scaled else 1.0
        ratio = (float(t["opal.parameters.pores.ratio_to_mean_particle_diameter"]) if scaled
                 else SCALE1_PORE_DIAMETER / PARTICLE_DIAMETER)
        found[(scale, float(t["opal.pore-fraction"]), int(t["seed"]))] = (ratio, t)
    return found


def shared_levels(found, script):
    """The scales of `found` (samples()), and the pore fractions and seeds every scale holds: the
    laws are fitted over the same levels at each. Exits (naming `script`) unless two scales share
    three pore fractions."""
    scales = sorted({k[0] for k in found})
    if len(scales) < 2:
        sys.exit(f"{script}: need finished samples at two scales")
    fractions = sorted(set.intersection(*({k[1] for k in found if k[0] == s} for s in scales)))
    seeds = sorted(set.intersection(*({k[2] for k in found if k[0] == s} for s in scales)))
    if len(fractions) < 3:
        sys.exit(f"{script}: need two scales sharing three pore fractions")
    return scales, fractions, seeds


def seed_laws(level):
    """Eq. 25, 24 and 26 fitted to one seed's samples (a list of tasks over the pore fractions)."""
    eps = [float(t["opal.parameters.pores.pore_fraction_of_region"]) for t in level]
    modulus = [float(t["compress.youngs_modulus"]) for t in level]
    strength = [float(t["compress.strength"]) for t in level]
    power = packlab.fit_porosity_law("power", eps, modulus, 0.0)
    shared = packlab.fit_porosity_law("exponential", eps, modulus, power.e0)
    eq26 = packlab.fit_porosity_law("exponential", eps, strength, 0.0)
    return {"eq25_E0": power.e0, "eq25_m": power.exponent, "eq24_b": shared.exponent, "eq26_sigma0": eq26.e0,
            "eq26_b": eq26.exponent}


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
    if len(argv) < 3:
        sys.exit(__doc__)
    data = argv[3] if len(argv) > 3 else os.path.join(HERE, "..", "..", "docs", "data")
    found = samples(argv[1], False) | samples(argv[2], True)
    scales, fractions, seeds = shared_levels(found, "porosity_resolution")
    columns = ["scale", "d_over_d", "pore_fraction", "seeds", "particles", "youngs_modulus_mean", "youngs_modulus_sd",
               "strength_mean", "strength_sd", "law", "fitted_over", "law_mean", "law_sd"]
    rows = []

    def row(**kw):
        rows.append({c: kw.get(c, "") for c in columns})

    per_sample = {}  # (pore fraction, quantity) -> [(D/d, value)]
    per_seed_law = {}  # law -> [(D/d, value)]
    for s in scales:
        ratio = next(found[k][0] for k in found if k[0] == s)
        own = sorted({k[1] for k in found if k[0] == s})
        for f in own:
            level = [found[(s, f, seed)][1] for seed in seeds if (s, f, seed) in found]
            e = [float(t["compress.youngs_modulus"]) for t in level]
            st = [float(t["compress.strength"]) for t in level]
            n = [float(t["opal.results.particles"]) for t in level]
            if f in fractions:
                per_sample.setdefault((f, "youngs_modulus"), []).extend((ratio, v) for v in e)
                per_sample.setdefault((f, "strength"), []).extend((ratio, v) for v in st)
            row(scale=f"{s:g}", d_over_d=f"{ratio:.4g}", pore_fraction=f"{f:g}", seeds=len(level),
                particles=f"{mean_sd(n)[0]:.0f}", youngs_modulus_mean=f"{mean_sd(e)[0]:.6g}",
                youngs_modulus_sd=f"{mean_sd(e)[1]:.3g}", strength_mean=f"{mean_sd(st)[0]:.6g}",
                strength_sd=f"{mean_sd(st)[1]:.3g}")
        # The laws over the pore fractions every scale holds (the trend below), and over all of
        # this scale's where it holds more (the paper's six, 0.39-0.63).
        for over in ([fractions, own] if own != fractions else [fractions]):
            laws = [seed_laws([found[(s, f, seed)][1] for f in over]) for seed in seeds
                    if all((s, f, seed) in found for f in over)]
            if not laws:  # no seed holds every pore fraction of the range yet
                continue
            for name in laws[0]:
                values = [law[name] for law in laws]
                if over is fractions:
                    per_seed_law.setdefault(name, []).extend((ratio, v) for v in values)
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
    for name, pairs in per_seed_law.items():
        at_target = extrapolate([p[0] for p in pairs], [p[1] for p in pairs])
        if at_target is None:
            continue
        value, err = at_target
        row(scale=target, d_over_d=f"{TARGET:g}", seeds=len(pairs), law=name,
            fitted_over=f"{fractions[0]:g}-{fractions[-1]:g}", law_mean=f"{value:.5g}", law_sd=f"{err:.3g}")
        print(f"{name}: " + ", ".join(f"D/d {r['d_over_d']} over {r['fitted_over']}: {r['law_mean']} +- {r['law_sd']}"
                                      for r in rows if r["law"] == name))
    path = os.path.join(data, "opal_porosity_resolution.csv")
    write_table(path, {k: [r[k] for r in rows] for k in columns},
                "examples/opal/porosity_resolution.py: the random-pore porosity samples at scales "
                + ", ".join(f"{s:g}" for s in scales) + "; E [Pa], strength [Pa]; laws over pore fractions "
                + ", ".join(f"{f:g}" for f in fractions) + f", seeds {', '.join(map(str, seeds))}")
    print(f"wrote {path} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
