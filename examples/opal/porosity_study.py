"""Porosity study of bpm-inverse-opals §4 at reduced resolution: random pores (placed by the
force-biased algorithm) at several pore fractions, several realizations each, a compression test
of each sample, and the fits of eq. 22 (E0 exp(-b eps)), eq. 23 (E0 (1 - eps)^m) and eq. 26
(sigma0 exp(-b eps)) with packlab.fit_porosity_law. E0 is held at the pore-free modulus
K_E x E_b (eq. 20, from the bulk-factor run) as in the paper's eq. 24-25, and also fitted.

    python3 porosity_study.py --out DIR [--packlab packlab] [--config silica.toml]
        [--bond-youngs-modulus E] [--bond-strength S] [--bulk-report bulk/report.json]
        [--fractions 0.3,0.4,0.5 | --counts 2,3,4] [--seeds 1,2] [--box 250e-9,250e-9,300e-9] [--quasi-static 1e-4]
        [--pore-boundary walls|periodic]

--pore-boundary periodic places the pores periodically over the whole box (they cut its top and
bottom faces), which reaches the paper's pore fractions 0.39-0.63; walls (the default) keeps every
pore inside the box above the substrate, which stops at 5 pores (0.41) in the default box and
between 0.54 and 0.59 in the paper's sample shape (docs/opal-build.md).

Writes DIR/samples.csv (one row per sample), DIR/fits.json and DIR/porosity.png.
"""

import argparse
import csv
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def run(cmd):
    print("+", " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", required=True)
    p.add_argument("--packlab", default="packlab")
    p.add_argument("--config", default=os.path.join(HERE, "silica.toml"))
    p.add_argument("--bond-youngs-modulus", type=float, default=6.53e9)
    p.add_argument("--bond-strength", type=float, default=94.3e6)
    p.add_argument("--bulk-report", help="report.json of `calibrate compress --bulk-factor` (gives K_E)")
    p.add_argument("--fractions", default="0.3,0.4,0.5", help="pore volume fractions of the region above the substrate")
    p.add_argument("--counts", help="numbers of pores instead of --fractions (e.g. 2,3,4)")
    p.add_argument("--seeds", default="1,2", help="one realization of the random pores per seed")
    p.add_argument("--box", default="250e-9,250e-9,300e-9")
    p.add_argument("--pore-diameter", default="138e-9")
    p.add_argument("--pore-boundary", default="walls", choices=("walls", "periodic"))
    p.add_argument("--stop-drop", default="0.85")
    p.add_argument("--quasi-static", default="1e-4", help="strain per wave transit (automatic rate)")
    args = p.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    packing = os.path.join(args.out, "packing")
    if not os.path.exists(os.path.join(packing, "packing.vtu")):
        run([args.packlab, "generate", "fba", "--box", args.box, "--diameter", "15e-9", "--porosity", "0.38",
             "--periodic", "xy", "--seed", "11", "--quiet", "--no-plots", "--out", packing])
    rows = []
    levels = [("c", c, "--pore-count") for c in args.counts.split(",")] if args.counts else \
        [("f", f, "--pore-fraction") for f in args.fractions.split(",")]
    for prefix, level, option in levels:
        for seed in args.seeds.split(","):
            name = f"{prefix}{level}-s{seed}"
            model = os.path.join(args.out, name)
            if not os.path.exists(os.path.join(model, "opal.vtu")):
                run([args.packlab, "build", "opal", os.path.join(packing, "packing.vtu"), "--pores", "random",
                     "--pore-diameter", args.pore_diameter, "--pore-boundary", args.pore_boundary, option, level, "--seed", seed, "--quiet", "--out", model])
            test = os.path.join(args.out, name + "-test")
            if not os.path.exists(os.path.join(test, "report.json")):
                run([args.packlab, "test", "compress", os.path.join(model, "opal.vtu"), "--config", args.config,
                     "--bond-youngs-modulus", repr(args.bond_youngs_modulus), "--bond-strength",
                     repr(args.bond_strength), "--stop-drop", args.stop_drop, "--quasi-static", args.quasi_static, "--no-vtu", "--no-plots", "--quiet",
                     "--out", test])
            built = json.load(open(os.path.join(model, "report.json")))
            summary = built.get("summary", built.get("results", built))
            tested = json.load(open(os.path.join(test, "report.json")))
            rows.append({"sample": name, "pores": summary["pores"], "seed": int(seed),
                         "porosity": summary["porosity"], "particles": summary["particles"],
                         "bonds": summary["bonds"], "youngs_modulus": tested["youngs_modulus"],
                         "strength": tested["strength"], "broken_bonds": tested["broken_bonds"]})
    samples = os.path.join(args.out, "samples.csv")
    with open(samples, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    import packlab

    eps = [r["porosity"] for r in rows]
    e = [r["youngs_modulus"] for r in rows]
    s = [r["strength"] for r in rows]
    e0 = 0.0
    if args.bulk_report:
        bulk = json.load(open(args.bulk_report))
        e0 = bulk["bulk_factor"] * args.bond_youngs_modulus  # eq. 20: E_macro = K_E E_b
    fits = {}
    for law in ("exponential", "power"):
        if e0 > 0:
            f = packlab.fit_porosity_law(law, eps, e, e0)
            fits[f"E_{law}_E0_fixed"] = {"E0": f.e0, "exponent": f.exponent, "exponent_err": f.exponent_err,
                                         "rms_relative": f.rms_relative, "rss": f.rss}
        if len(eps) >= 3:
            f = packlab.fit_porosity_law(law, eps, e)
            fits[f"E_{law}_E0_free"] = {"E0": f.e0, "E0_err": f.e0_err, "exponent": f.exponent,
                                        "exponent_err": f.exponent_err, "rms_relative": f.rms_relative, "rss": f.rss}
    if len(eps) < 3:
        sys.exit("porosity_study: at least 3 samples are needed for the free fits")
    f = packlab.fit_porosity_law("exponential", eps, s)
    fits["strength_exponential"] = {"sigma0": f.e0, "sigma0_err": f.e0_err, "b": f.exponent,
                                    "b_err": f.exponent_err, "rms_relative": f.rms_relative}
    fits["E0_bulk"] = e0
    with open(os.path.join(args.out, "fits.json"), "w") as out:
        json.dump(fits, out, indent=2)
    print(json.dumps(fits, indent=2))
    key = "E_power_E0_fixed" if e0 > 0 else "E_power_E0_free"
    keyb = "E_exponential_E0_fixed" if e0 > 0 else "E_exponential_E0_free"
    subprocess.run([sys.executable, "-m", "packlab.plot", "porosity", samples, "--e0", repr(fits[key]["E0"]),
                    "--b", repr(fits[keyb]["exponent"]), "--m", repr(fits[key]["exponent"]), "--s0",
                    repr(fits["strength_exponential"]["sigma0"]), "--bs", repr(fits["strength_exponential"]["b"]),
                    "--out", os.path.join(args.out, "porosity.png")], check=False)
    return 0


if __name__ == "__main__":
    sys.exit(main())
