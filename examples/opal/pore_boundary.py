#!/usr/bin/env python3
"""Periodic against walled random pores (docs/reproduction.md, `opal.eq26_b`): the scale-0.6
samples of examples/study/opal_porosity_resolution.toml (pores periodic in z: they cut the
loaded top and bottom faces) and of examples/study/opal_porosity_walls.toml (the same packing,
pores wholly inside the region above the substrate). Writes

  DATA/opal_pore_boundary.csv   per geometry and pore fraction: the sample's porosity, its
                                pores and those with their centre in the bottom or top eighth
                                of the height the centres may take (per seed, "/"-separated),
                                E and strength (mean and SD over the seeds); then per geometry
                                (pore_fraction empty) eq. 25's m, eq. 24's b (E0 of eq. 25) and
                                eq. 26's b fitted per seed over the pore fractions both hold
                                (packlab.fit_porosity_law; eps the region's pore fraction), mean
                                and SD over the seeds

usage: pore_boundary.py RESOLUTION_OUT WALLS_OUT [DATA]   (the two studies' --out folders;
       needs the packlab Python module: PYTHONPATH=python:build/python)"""

import json
import os
import sys

import packlab
from packlab.reproduction import mean_sd
from packlab.studies import finished_tasks
from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))
SCALE = 0.6  # opal_porosity_walls.toml's samples: opal_porosity_resolution.toml's scale 0.6


def samples(out, scale):
    return {(float(t["opal.pore-fraction"]), int(t["seed"])): t for t in finished_tasks(out)
            if scale is None or float(t["scale"]) == scale}


def pores_at_the_ends(out, task):
    """(pores whose centre lies in the bottom or top eighth of the range the centres may take,
    pores): the crowding of walled pores against the walls, from the sample's pores.xyz."""
    with open(os.path.join(out, "runs", "compress-" + task["task"], "report.json")) as f:
        opal = os.path.dirname(json.load(f)["input"])
    with open(os.path.join(opal, "report.json")) as f:
        pores = json.load(f)["parameters"]["pores"]
    with open(os.path.join(opal, "pores.xyz")) as f:
        z = [float(line.split()[3]) for line in f.read().splitlines()[2:]]
    lo, height = pores["region_lo_m"][2], pores["region_length_m"][2]
    if pores["boundary"] == "walls":  # the packed spheres (spacing x D) stay inside the region
        half = 0.5 * pores["diameter_m"] * pores["spacing_ratio"]
        lo, height = lo + half, height - 2.0 * half
    inside = [(v - lo) / height for v in z if -1e-9 <= (v - lo) / height < 1.0 + 1e-9]  # periodic: images dropped
    return sum(1 for t in inside if t < 0.125 or t > 0.875), len(inside)


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    data = argv[3] if len(argv) > 3 else os.path.join(HERE, "..", "..", "docs", "data")
    outs = {"periodic": argv[1], "walls": argv[2]}
    geometries = {"periodic": samples(argv[1], SCALE), "walls": samples(argv[2], None)}
    common = set.intersection(*(set(s) for s in geometries.values()))
    fractions = sorted({f for f, _ in common})
    seeds = sorted({s for _, s in common})
    if len(fractions) < 3:
        sys.exit("pore_boundary: the two studies share fewer than three pore fractions")
    columns = ["geometry", "pore_fraction", "seeds", "porosity", "pores", "pores_at_the_ends", "youngs_modulus_mean",
               "youngs_modulus_sd", "strength_mean", "strength_sd", "law", "law_mean", "law_sd"]
    rows = []
    for name, found in geometries.items():
        for f in fractions:
            level = [found[(f, s)] for s in seeds if (f, s) in common]
            e = mean_sd(float(t["compress.youngs_modulus"]) for t in level)
            st = mean_sd(float(t["compress.strength"]) for t in level)
            ends = [pores_at_the_ends(outs[name], t) for t in level]
            rows.append({"geometry": name, "pore_fraction": f"{f:g}", "seeds": len(level),
                         "pores": "/".join(str(e[1]) for e in ends),
                         "pores_at_the_ends": "/".join(str(e[0]) for e in ends),
                         "porosity": f"{mean_sd(float(t['opal.results.porosity']) for t in level)[0]:.4f}",
                         "youngs_modulus_mean": f"{e[0]:.6g}", "youngs_modulus_sd": f"{e[1]:.3g}",
                         "strength_mean": f"{st[0]:.6g}", "strength_sd": f"{st[1]:.3g}"})
        laws = {"eq25_m": [], "eq24_b": [], "eq26_b": []}
        for s in seeds:
            if not all((f, s) in common for f in fractions):
                continue
            level = [found[(f, s)] for f in fractions]
            eps = [float(t["opal.parameters.pores.pore_fraction_of_region"]) for t in level]
            modulus = [float(t["compress.youngs_modulus"]) for t in level]
            power = packlab.fit_porosity_law("power", eps, modulus, 0.0)
            laws["eq25_m"].append(power.exponent)
            laws["eq24_b"].append(packlab.fit_porosity_law("exponential", eps, modulus, power.e0).exponent)
            laws["eq26_b"].append(packlab.fit_porosity_law(
                "exponential", eps, [float(t["compress.strength"]) for t in level], 0.0).exponent)
        for law, values in laws.items():
            m, sd = mean_sd(values)
            rows.append({"geometry": name, "seeds": len(values), "law": law, "law_mean": f"{m:.4g}",
                         "law_sd": f"{sd:.3g}"})
            print(f"{name} {law}: {m:.3g} +- {sd:.2g}")
    path = os.path.join(data, "opal_pore_boundary.csv")
    write_table(path, {k: [r.get(k, "") for r in rows] for k in columns},
                "examples/opal/pore_boundary.py: random pores at D/d = 5.12 (scale 0.6), periodic (cutting the loaded "
                "faces) against walled, same packing and seeds; E [Pa], strength [Pa]; laws over pore fractions "
                + ", ".join(f"{f:g}" for f in fractions))
    print(f"wrote {path} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
