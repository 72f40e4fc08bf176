"""The data tables and figures of docs/opal.md, in two steps so that the figures never need the
simulations:

    python3 study_figures.py tables STUDY DATA    # STUDY = the output folder of run.sh:
                                                  # writes DATA/opal_*.csv (small, checked in
                                                  # under docs/data/)
    python3 study_figures.py figures DATA FIGS    # draws FIGS/opal-*.png from DATA/opal_*.csv only

`make docs` runs the second step on docs/data/ (docs/figures/make-opal-figures.sh); run.sh runs
both on its own output (STUDY/docs-data, STUDY/figures). To refresh the docs after a new study:
    cp STUDY/docs-data/opal_*.csv docs/data/ && make docs

Tables (SI units, one header line):
  opal_runs.csv           one row per compression run: the FCC opal with the paper's bonds, twice
                          the rate, calibrated, coated, with touching pores; the pore-free bulk
                          sample (periodic, open sides, compressive breakage): model, bond
                          values, rate, E, strength, strain and broken bonds at the peak, ...
                          (porosity: the macro-porosity of `build opal`, 0 for the bulk sample)
  opal_fcc_curves.csv     run,strain,stress,broken_bonds: the stress-strain curves of those runs
                          (thinned to at most 150 points per run; the peak and the last point kept)
  opal_fcc_bond_strain.csv  bond strain histograms at 0.5/1/1.5/2 % (paper's bonds; Fig. 7)
  opal_particle_stress.csv  per-type particle stresses at those strains, uncoated and coated
                          (Table 2; no figure, the numbers of docs/opal.md)
  opal_porosity.csv       one row per random-pore sample: porosity, E, strength, ...
  opal_porosity_fits.csv  the fits of eq. 22-26 (packlab.fit_porosity_law); `figures` refits them
                          when the compiled module is importable and stops if they disagree
"""

import argparse
import csv
import json
import math
import os
import sys

# run name -> folder of the study with its curve.csv, in the order of the tables
RUNS = [
    ("paper", "fcc-paper"),
    ("fast", "fcc-fast"),
    ("calibrated", "fcc-calibration/final"),
    ("coated", "fcc-coated-paper"),
]
# the built model of each run (porosity, density)
MODELS = {"paper": "fcc", "fast": "fcc", "calibrated": "fcc", "coated": "fcc-coated", "touching": "fcc-touching"}
# pore-free bulk sample runs of `calibrate compress --bulk-factor`
BULK = [("bulk", "bulk"), ("bulk_open", "bulk-open"), ("bulk_compressive", "bulk-compressive")]
RUN_COLUMNS = ["run", "particles", "bonds", "porosity", "density", "bond_youngs_modulus", "bond_strength",
               "strain_rate", "youngs_modulus", "strength", "strain_at_peak", "broken_at_peak", "broken_bonds",
               "fit_begin", "fit_end", "iterations", "simulations"]
MAX_POINTS = 150


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if line.strip() and not line.startswith("#")))


def write_rows(path, header, rows, digits=8):
    def fmt(v):
        if isinstance(v, float):
            return f"{v:.{digits}g}" if math.isfinite(v) else "nan"
        return str(v)

    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        f.write(",".join(header) + "\n")
        for row in rows:
            f.write(",".join(fmt(row[k]) for k in header) + "\n")
    os.replace(tmp, path)
    print(f"wrote {path} ({len(rows)} rows)")


def thin(points, n=MAX_POINTS):
    """At most about n points, evenly in index; the first, the peak and the last are kept."""
    if len(points) <= n:
        return points
    peak = max(range(len(points)), key=lambda k: points[k]["stress"])
    step = math.ceil(len(points) / n)
    keep = set(range(0, len(points), step)) | {peak, len(points) - 1}
    return [points[k] for k in sorted(keep)]


def model_row(study, name):
    built = json.load(open(os.path.join(study, MODELS[name], "report.json")))["results"]
    return {"porosity": built["porosity"], "density": built["density_kg_m3"]}


def curve_points(study, folder, run):
    return [{"run": run, "strain": float(r["strain"]), "stress": float(r["stress"]),
             "broken_bonds": int(r["broken_bonds"])} for r in read_rows(os.path.join(study, folder, "curve.csv"))]


def test_row(rep, points):
    """The columns of opal_runs.csv from a `test compress` report (or a bulk report's "compression")
    and the run's curve."""
    fit = rep["modulus_fit"]
    return {"particles": rep["particles"], "bonds": rep["bonds"], "strain_rate": rep["strain_rate"],
            "youngs_modulus": rep["youngs_modulus"], "strength": rep["strength"],
            "strain_at_peak": rep["strain_at_peak"], "broken_bonds": rep["broken_bonds"],
            "fit_begin": fit["strain_begin"], "fit_end": fit["strain_end"],
            "broken_at_peak": max(points, key=lambda p: p["stress"])["broken_bonds"], "iterations": 0,
            "simulations": 1}


def silica_bond(rep):
    """The silica bonds' Young's modulus and strength [Pa] of a `test compress` report."""
    silica = rep["parameters"]["silica"]
    return silica["youngs_modulus_Pa"], silica["strength_Pa"]


def tables(study, data):
    os.makedirs(data, exist_ok=True)
    runs, curves = [], []
    for name, folder in RUNS:
        points = curve_points(study, folder, name)
        if name == "calibrated":
            # calibrate compress writes no test report for its result: the curve and the
            # calibration report; its automatic rate is that of its starting (config) values,
            # which are the paper run's
            cal = json.load(open(os.path.join(study, "fcc-calibration", "report.json")))
            row = test_row(json.load(open(os.path.join(study, "fcc-paper", "report.json"))), points)
            peak = max(points, key=lambda p: p["stress"])
            row.update({"youngs_modulus": cal["youngs_modulus"], "strength": cal["strength"],
                        "strain_at_peak": peak["strain"], "broken_bonds": points[-1]["broken_bonds"],
                        "fit_begin": float("nan"), "fit_end": float("nan"), "iterations": cal["iterations"],
                        "simulations": cal["simulations"]})
            e_b, s_max = cal["bond_youngs_modulus"], cal["bond_strength"]
        else:
            rep = json.load(open(os.path.join(study, folder, "report.json")))
            row = test_row(rep, points)
            e_b, s_max = silica_bond(rep)
        runs.append({"run": name, "bond_youngs_modulus": e_b, "bond_strength": s_max, **row,
                     **model_row(study, name)})
        curves += thin(points)
    rep = json.load(open(os.path.join(study, "fcc-touching-test", "report.json")))
    e_b, s_max = silica_bond(rep)
    runs.append({"run": "touching", "bond_youngs_modulus": e_b, "bond_strength": s_max,
                 **test_row(rep, curve_points(study, "fcc-touching-test", "touching")), **model_row(study, "touching")})
    for name, folder in BULK:
        bulk = json.load(open(os.path.join(study, folder, "report.json")))
        runs.append({"run": name, "bond_youngs_modulus": bulk["bond_youngs_modulus"],
                     "bond_strength": bulk["bond_strength"],
                     **test_row(bulk["compression"], curve_points(study, folder + "/final", name)), "porosity": 0.0,
                     "density": float("nan")})
    write_rows(os.path.join(data, "opal_runs.csv"), RUN_COLUMNS, runs)
    write_rows(os.path.join(data, "opal_fcc_curves.csv"), ["run", "strain", "stress", "broken_bonds"], curves, 6)

    stress = []
    for name, folder in (("paper", "fcc-paper"), ("coated", "fcc-coated-paper")):
        for r in read_rows(os.path.join(study, folder, "particle_stress.csv")):
            values = {k: (int(v) if k in ("type", "particles") else float(v)) for k, v in r.items()
                      if not k.startswith("requested_")}
            stress.append({"run": name, **values})
    write_rows(os.path.join(data, "opal_particle_stress.csv"), list(stress[0].keys()), stress, 6)

    hist = read_rows(os.path.join(study, "fcc-paper", "bond_strain.csv"))
    header = list(hist[0].keys())
    write_rows(os.path.join(data, "opal_fcc_bond_strain.csv"), header,
               [{k: float(r[k]) for k in header} for r in hist], 6)

    porosity = os.path.join(study, "porosity")
    samples = read_rows(os.path.join(porosity, "samples.csv"))
    header = list(samples[0].keys())
    write_rows(os.path.join(data, "opal_porosity.csv"), header,
               [{k: (r[k] if k == "sample" else float(r[k]) if "." in r[k] or "e" in r[k] else int(r[k]))
                 for k in header} for r in samples])
    fits = json.load(open(os.path.join(porosity, "fits.json")))
    rows = []
    for key, value in fits.items():
        if not isinstance(value, dict):
            continue
        if key.startswith("strength"):
            quantity, law = "strength", "exponential"
        else:
            quantity, law = "youngs_modulus", key.split("_")[1]
        rows.append({"quantity": quantity, "law": law, "e0_held": int(key.endswith("E0_fixed")),
                     "e0": value.get("E0", value.get("sigma0")),
                     "e0_err": value.get("E0_err", value.get("sigma0_err", 0.0)),
                     "exponent": value.get("exponent", value.get("b")),
                     "exponent_err": value.get("exponent_err", value.get("b_err")),
                     "rms_relative": value["rms_relative"]})
    write_rows(os.path.join(data, "opal_porosity_fits.csv"),
               ["quantity", "law", "e0_held", "e0", "e0_err", "exponent", "exponent_err", "rms_relative"], rows)


def columns(rows, names):
    import numpy as np

    return {k: np.array([float(r[k]) for r in rows]) for k in names}


def check_fits(samples, fits):
    """Refits the porosity laws from the sample table when the compiled module is there."""
    try:
        import packlab

        fit = packlab.fit_porosity_law
    except (ImportError, AttributeError):
        print("study_figures: packlab._core not importable, porosity fits taken from the table unchecked")
        return
    eps = [float(r["porosity"]) for r in samples]
    for f in fits:
        values = [float(r[f["quantity"]]) for r in samples]
        g = fit(f["law"], eps, values, float(f["e0"]) if f["e0_held"] == "1" else 0.0)
        for name, got in (("e0", g.e0), ("exponent", g.exponent)):
            if abs(got - float(f[name])) > 1e-5 * abs(float(f[name])):
                sys.exit(f"study_figures: opal_porosity_fits.csv {f['quantity']} {f['law']} {name} = {f[name]} "
                         f"but the samples give {got:.8g}: rewrite the tables (study_figures.py tables)")


def figures(data, out):
    import matplotlib

    matplotlib.use("Agg")
    from packlab.plot import bond_strain, broken_bonds, porosity, save, stress_strain

    os.makedirs(out, exist_ok=True)
    runs = {r["run"]: r for r in read_rows(os.path.join(data, "opal_runs.csv"))}
    rows = read_rows(os.path.join(data, "opal_fcc_curves.csv"))
    curve = {name: columns([r for r in rows if r["run"] == name], ["strain", "stress", "broken_bonds"])
             for name, _ in RUNS}

    def bonds(run):
        r = runs[run]
        return f"{float(r['bond_youngs_modulus']) * 1e-9:.2f} GPa, {float(r['bond_strength']) * 1e-6:.1f} MPa"

    def written(path):
        print(f"wrote {path}")

    path = os.path.join(out, "opal-curves.png")
    save(stress_strain.figure([curve["paper"], curve["calibrated"], curve["coated"]],
                              labels=[f"uncoated, paper's bonds ({bonds('paper')})",
                                      f"uncoated, calibrated ({bonds('calibrated')})",
                                      f"titania-coated, paper's bonds ({bonds('coated')})"]), path)
    written(path)
    path = os.path.join(out, "opal-rate.png")
    def rate(run):  # 5.4e5 1/s
        return f"{float(runs[run]['strain_rate']):.2g}".replace("e+0", "e") + " 1/s"

    quasi = float(runs["fast"]["strain_rate"]) / float(runs["paper"]["strain_rate"])
    save(stress_strain.figure([curve["paper"], curve["fast"]],
                              labels=[f"quasi-static 1e-4 ({rate('paper')})",
                                      f"quasi-static {quasi:.3g}e-4 ({rate('fast')})"]),
         path)
    written(path)
    path = os.path.join(out, "opal-fcc-bond-strain.png")
    save(bond_strain.figure(os.path.join(data, "opal_fcc_bond_strain.csv")), path)
    written(path)
    path = os.path.join(out, "opal-fcc-broken-bonds.png")
    save(broken_bonds.figure(curve["paper"]), path)
    written(path)

    samples_csv = os.path.join(data, "opal_porosity.csv")
    fits = read_rows(os.path.join(data, "opal_porosity_fits.csv"))
    check_fits(read_rows(samples_csv), fits)

    def pick(quantity, law, held):
        for f in fits:
            if f["quantity"] == quantity and f["law"] == law and f["e0_held"] == held:
                return float(f["e0"]), float(f["exponent"])
        return 0.0, 0.0

    held = "1" if any(f["e0_held"] == "1" for f in fits) else "0"
    e0, m = pick("youngs_modulus", "power", held)
    _, b = pick("youngs_modulus", "exponential", held)
    s0, bs = pick("strength", "exponential", "0")
    path = os.path.join(out, "opal-porosity.png")
    save(porosity.figure(samples_csv, e0=e0, b=b, m=m, s0=s0, bs=bs), path)
    written(path)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="step", required=True)
    t = sub.add_parser("tables", help="STUDY (run.sh output) -> DATA/opal_*.csv")
    t.add_argument("study")
    t.add_argument("data")
    f = sub.add_parser("figures", help="DATA/opal_*.csv -> FIGS/opal-*.png")
    f.add_argument("data")
    f.add_argument("figs")
    args = p.parse_args(argv)
    if args.step == "tables":
        tables(args.study, args.data)
    else:
        figures(args.data, args.figs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
