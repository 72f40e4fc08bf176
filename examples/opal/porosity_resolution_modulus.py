#!/usr/bin/env python3
"""E of the porosity samples at three resolutions over the paper's whole range of porosities
(docs/reproduction.md, the `opal.porosity_E_*_dd51`, `opal.eq25_m_dd51` and `opal.eq24_b_dd51`
rows): the E-only samples of examples/study/opal_porosity_paper_modulus.toml (scale 1, pores 9.2
particle diameters across) and of examples/study/opal_porosity_resolution_modulus.toml (scales
0.6 and 0.75: D/d = 5.12 and 6.65), pore fractions 0.39-0.63, seeds 1-5. Writes

  DATA/opal_porosity_resolution_modulus.csv   per scale and pore fraction: D/d, particles, E (mean
                                              and SD over the seeds); per scale (pore_fraction
                                              empty) eq. 25's E0 and m (E0 free) and eq. 24's b
                                              (E0 of eq. 25) fitted per seed over the pore
                                              fractions every scale holds (the paper's six), mean
                                              and SD over the seeds; then rows scale = "D/d=51":
                                              each taken to the paper's D/d = 51 as
                                              porosity_resolution.py does (q = q_inf + c d/D over
                                              every sample or per-seed fit; uncertainty: the fit's
                                              standard error and half the spread of the laws 1/x,
                                              1/x^2, 1/sqrt(x))

The strength needs the compression to its peak (porosity_resolution.py, over 0.49-0.63, the
range the compressed samples share at every scale).

usage: porosity_resolution_modulus.py SCALE1_OUT RESOLUTION_OUT [DATA]   (the two E-only studies'
       --out folders; needs the packlab Python module: PYTHONPATH=python:build/python)"""

import os
import sys

import packlab
from packlab.reproduction import mean_sd
from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from porosity_resolution import extrapolate, samples, shared_levels  # noqa: E402
from resolution_extrapolation import TARGET  # noqa: E402


def modulus_laws(level):
    """Eq. 25 (E0 free) and eq. 24 (E0 of eq. 25) fitted to one seed's samples over the pore
    fractions (eps: the box's pore fraction, as porosity_tables.py)."""
    eps = [float(t["opal.parameters.pores.pore_fraction_of_region"]) for t in level]
    modulus = [float(t["compress.youngs_modulus"]) for t in level]
    power = packlab.fit_porosity_law("power", eps, modulus, 0.0)
    shared = packlab.fit_porosity_law("exponential", eps, modulus, power.e0)
    return {"eq25_E0": power.e0, "eq25_m": power.exponent, "eq24_b": shared.exponent}


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    data = argv[3] if len(argv) > 3 else os.path.join(HERE, "..", "..", "docs", "data")
    found = samples(argv[1], False) | samples(argv[2], True)
    scales, fractions, seeds = shared_levels(found, "porosity_resolution_modulus")
    columns = ["scale", "d_over_d", "pore_fraction", "seeds", "particles", "youngs_modulus_mean", "youngs_modulus_sd",
               "law", "fitted_over", "law_mean", "law_sd"]
    rows = []

    def row(**kw):
        rows.append({c: kw.get(c, "") for c in columns})

    over = f"{fractions[0]:g}-{fractions[-1]:g}"
    per_sample, per_seed_law = {}, {}  # pore fraction / law -> [(D/d, value)]
    for s in scales:
        ratio = next(found[k][0] for k in found if k[0] == s)
        for f in fractions:
            level = [found[(s, f, seed)][1] for seed in seeds if (s, f, seed) in found]
            e = [float(t["compress.youngs_modulus"]) for t in level]
            per_sample.setdefault(f, []).extend((ratio, v) for v in e)
            m, sd = mean_sd(e)
            row(scale=f"{s:g}", d_over_d=f"{ratio:.4g}", pore_fraction=f"{f:g}", seeds=len(level),
                particles=f"{mean_sd([float(t['opal.results.particles']) for t in level])[0]:.0f}",
                youngs_modulus_mean=f"{m:.6g}", youngs_modulus_sd=f"{sd:.3g}")
        laws = [modulus_laws([found[(s, f, seed)][1] for f in fractions]) for seed in seeds
                if all((s, f, seed) in found for f in fractions)]
        for name in laws[0] if laws else []:
            values = [law[name] for law in laws]
            per_seed_law.setdefault(name, []).extend((ratio, v) for v in values)
            m, sd = mean_sd(values)
            row(scale=f"{s:g}", d_over_d=f"{ratio:.4g}", seeds=len(values), law=name, fitted_over=over,
                law_mean=f"{m:.5g}", law_sd=f"{sd:.3g}")
    target = f"D/d={TARGET:g}"
    for f, pairs in sorted(per_sample.items()):
        at_target = extrapolate([p[0] for p in pairs], [p[1] for p in pairs])
        if at_target is not None:
            row(scale=target, d_over_d=f"{TARGET:g}", pore_fraction=f"{f:g}", seeds=len(pairs),
                youngs_modulus_mean=f"{at_target[0]:.6g}", youngs_modulus_sd=f"{at_target[1]:.3g}")
    for name, pairs in per_seed_law.items():
        at_target = extrapolate([p[0] for p in pairs], [p[1] for p in pairs])
        if at_target is None:
            continue
        row(scale=target, d_over_d=f"{TARGET:g}", seeds=len(pairs), law=name, fitted_over=over,
            law_mean=f"{at_target[0]:.5g}", law_sd=f"{at_target[1]:.3g}")
        print(f"{name}: " + ", ".join(f"D/d {r['d_over_d']}: {r['law_mean']} +- {r['law_sd']}"
                                      for r in rows if r["law"] == name))
    path = os.path.join(data, "opal_porosity_resolution_modulus.csv")
    write_table(path, {k: [r[k] for r in rows] for k in columns},
                "examples/opal/porosity_resolution_modulus.py: E-only random-pore porosity samples at scales "
                + ", ".join(f"{s:g}" for s in scales) + "; E [Pa]; laws over pore fractions "
                + ", ".join(f"{f:g}" for f in fractions) + f", seeds {', '.join(map(str, seeds))}")
    print(f"wrote {path} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
