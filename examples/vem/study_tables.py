#!/usr/bin/env python3
"""Collects the runs of examples/vem/study.sh into the tables docs/vem.md and `make docs` use:

  DATA/vem_study.csv    one row per run: parameters, inflection point, beta, cost
  DATA/vem_curves.csv   every run's CN(q) curve (name, q, cn, phi_total), 6 digits
  DATA/vem_fig1_cn_curve.csv   the Fig. 1 run's cn_curve.csv as written (if it ran)

OUT is the folder of examples/vem/study.sh: one study folder per group (OUT/GROUP/tasks.csv,
docs/study.md); the runs keep the names of the script before the studies (n025, phi02,
stiffness_kns1e3_knv1e1, ...). A folder of that older layout (OUT/NAME/report.json) is read too.

usage: study_tables.py OUT [DATA] [TABLE]   (DATA defaults to docs/data of this checkout; TABLE,
default vem_study, names the tables DATA/TABLE.csv and, for another name than the default,
DATA/TABLE_curves.csv: `study_tables.py OUT/relax docs/data vem_relax_study` keeps the relaxation
study of docs/reproduction.md apart)"""

import csv
import json
import math
import os
import shutil
import sys


def main(argv):
    out = argv[1] if len(argv) > 1 else "vem-study"
    here = os.path.dirname(os.path.abspath(__file__))
    data = argv[2] if len(argv) > 2 else os.path.join(here, "..", "..", "docs", "data")
    table = argv[3] if len(argv) > 3 else "vem_study"
    curves_table = "vem_curves" if table == "vem_study" else f"{table}_curves"
    os.makedirs(data, exist_ok=True)
    folders = study_runs(out)
    folders.update({d: os.path.join(out, d) for d in os.listdir(out) if os.path.isfile(os.path.join(out, d, "report.json"))})
    runs = sorted(folders)
    study_rows, curve_rows = [], []
    for name in runs:
        with open(os.path.join(folders[name], "report.json")) as f:
            r = json.load(f)
        p = r["parameters"]
        i = r["inflection"]
        # Quoted uncertainty: fit error and window sensitivity together (docs/vem.md).
        q_unc = math.hypot(i.get("q_err", 0.0), i.get("q_window", 0.0))
        slope_unc = math.hypot(i.get("slope_err", 0.0), i.get("slope_window", 0.0))
        n = r["voids"] / r["structural"]
        kn_ratio = p["void_material"]["normal_stiffness_N_per_m"] / p["structural_material"]["normal_stiffness_N_per_m"]
        study_rows.append({
            "name": name, "structural": r["structural"], "voids": r["voids"], "n": f"{n:.6g}",
            "phi_s": f"{r['phi_s']:.6g}", "kn_ratio": f"{kn_ratio:.6g}",
            "kn_structural": f"{p['structural_material']['normal_stiffness_N_per_m']:.6g}",
            "void_mass_scaling": f"{p['void_mass_scaling']:.6g}",
            "time_step_rule": p.get("time_step_rule", "contacts"),
            "time_step_safety": f"{p['time_step_safety']:.6g}", "seed": p["seed"],
            "q_i": f"{i['q']:.6g}", "q_i_unc": f"{q_unc:.3g}", "cn_i": f"{i['cn']:.6g}",
            "slope": f"{i['slope']:.6g}", "slope_unc": f"{slope_unc:.3g}",
            "phi_total_i": f"{i['phi_total']:.6g}", "q_n13": f"{i['q'] * n ** (1 / 3):.6g}",
            "slope_n13": f"{i['slope'] * n ** (1 / 3):.6g}", "beta": f"{r['beta']:.6g}",
            "beta_r2": f"{r['beta_r2']:.6g}", "cycles": r["cycles"], "steps": r["steps"],
            "seconds": f"{r['seconds']:.4g}", "threads": r["threads"], "stop": r["stop_reason"],
        })
        relax = p.get("relax", {})
        if table != "vem_study":  # the relaxation per increment (vem_study.csv predates these columns)
            study_rows[-1].update({"relax_tolerance": relax.get("tolerance", ""), "relax_overlap": relax.get("overlap", ""),
                                   "relax_max_steps": relax.get("max_steps", "")})
        with open(os.path.join(folders[name], "cn_curve.csv")) as f:
            lines = [line for line in f if not line.startswith("#")]
        q, cn = [], []
        for row in csv.DictReader(lines):
            q.append(float(row["q"]))
            cn.append(float(row["cn"]))
            curve_rows.append({"name": name, "q": f"{q[-1]:.6g}", "cn": f"{cn[-1]:.6g}",
                               "phi_total": f"{float(row['phi_total']):.6g}"})
        # The paper writes the slope as a difference quotient dCN/dq|_i; on a curve sampled
        # every 0.2 in q (every 40th row) the largest one is (docs/vem.md, "slope").
        study_rows[-1]["slope_dq02_n13"] = f"{largest_difference_quotient(q, cn, 0.2) * n ** (1 / 3):.4g}"
    write(os.path.join(data, f"{table}.csv"), study_rows,
          "examples/vem/study.sh runs (examples/vem/study_tables.py); q_i_unc, slope_unc = "
          "sqrt(fit error^2 + window change^2); kn_ratio = k_n,V / k_n,S; seconds = wall time")
    write(os.path.join(data, f"{curves_table}.csv"), curve_rows,
          "CN(q) curves of examples/vem/study.sh (examples/vem/study_tables.py)")
    if "fig1" in folders and table == "vem_study":
        shutil.copyfile(os.path.join(folders["fig1"], "cn_curve.csv"), os.path.join(data, "vem_fig1_cn_curve.csv"))
        shutil.copyfile(os.path.join(folders["fig1"], "report.json"), os.path.join(data, "vem_fig1_report.json"))
    print(f"{len(study_rows)} runs -> {data}/{table}.csv, {curves_table}.csv ({len(curve_rows)} rows)")
    return 0


def run_name(group, row):
    """The name examples/vem/study.sh gave a run before the studies, from its group and its row
    of tasks.csv."""
    if group == "dt":
        cfg = "" if row["cfg"] == "default" else f"_{row['cfg']}"
        return f"n050{cfg}_seed{row['seed']}"
    if group == "n":
        return f"n{int(row['voids']) // 10:03d}"
    if group == "size":
        return f"n050_ns{row['structural']}"
    if group == "phi":
        return "phi" + row["phi-s"].replace(".", "")
    if group == "mass":
        return "n050_mass025"
    if group == "stiffness_limit":
        return f"stiffness_kns1e3_knv{row['knv']}_limit{int(row['relax-max-steps']):05d}"
    if group == "kn_limit":
        return f"stiffness_kns1e3_knv1e-2_limit{int(row['relax-max-steps']):05d}"
    if group == "phi_ns4000":
        return "phi" + row["phi-s"].replace(".", "") + "_ns4000"
    if group == "relax_n":
        return f"n{int(row['voids']) // 10:03d}_relax00050_seed{row['seed']}"
    if group == "relax":
        return f"n050_relax{int(row['relax-max-steps']):05d}_seed{row['seed']}"
    if group == "stiffness":
        return f"stiffness_kns1e3_knv{row['knv']}"
    return group  # fig1


def study_runs(out):
    """name -> run folder of the finished runs of the studies OUT/GROUP (examples/study/vem_GROUP.toml)."""
    found = {}
    for group in sorted(os.listdir(out)):
        tasks = os.path.join(out, group, "tasks.csv")
        if not os.path.isfile(tasks):
            continue
        with open(tasks, newline="") as f:
            for row in csv.DictReader(f):
                folder = os.path.join(out, group, "runs", f"vem-{row['task']}")
                if row["status"] == "done" and os.path.isfile(os.path.join(folder, "report.json")):
                    found[run_name(group, row)] = folder
    return found


def largest_difference_quotient(q, cn, step):
    """Largest (cn[k+m] - cn[k]) / (q[k+m] - q[k]) over the rows m apart, m = step / (row spacing)."""
    if len(q) < 3:
        return float("nan")
    m = max(1, round(step / (q[1] - q[0])))
    return max((cn[k + m] - cn[k]) / (q[k + m] - q[k]) for k in range(len(q) - m))


def write(path, rows, comment):
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        f.write(f"# {comment}\n")
        if rows:
            w = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
            w.writeheader()
            w.writerows(rows)
    os.replace(tmp, path)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
