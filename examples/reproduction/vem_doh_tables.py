#!/usr/bin/env python3
"""Collects the runs of examples/reproduction/vem_doh_ns8000.sh into DATA/vem_doh_ns8000.csv:
one row per run and end point (stage3, cmatched) with the VEM paper's numbers of the run (q_i,
CN_i, slope, Phi_T,i and beta, fitted on the curve up to the stage III row, as a default run
stopped there would report them) and the DOH paper's numbers of the structure (a, C, G'_p over six
orientations and its SD).

usage: vem_doh_tables.py OUT [DATA]   (DATA defaults to docs/data of this checkout; needs the
       packlab Python module: PYTHONPATH=python:build/python)"""

import csv
import glob
import json
import os
import sys

from packlab import _core
from packlab.tables import atomic_output

COLUMNS = ["seed", "n", "voids", "structural", "end", "cycle", "q_end", "vem_cn_end", "q_i", "cn_i", "slope", "q_n13",
           "slope_n13", "phi_total_i", "beta", "beta_r2", "a", "a_err", "coordination", "storage_modulus", "std",
           "storage_modulus_min", "storage_modulus_max", "relax_steps", "vem_steps", "vem_cpu_seconds"]


def curve_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def fits(rows, n, phi_s, analysis):
    """Inflection and beta on the given rows, with the options of the run's report."""
    q = [float(r["q"]) for r in rows]
    cn = [float(r["cn"]) for r in rows]
    phi = [float(r["phi_total"]) for r in rows]
    inf = _core.find_inflection(q, cn, window_widths=analysis["window_widths"])
    phi_i = phi_s * (1.0 + inf.x ** 3 * n)  # eq. 5
    pl = _core.fit_power_law(phi, cn, phi_i, inf.y, max_excess=analysis["power_law_max_excess"])
    return inf, phi_i, pl


def main(argv):
    out = argv[1] if len(argv) > 1 else "vem-doh"
    here = os.path.dirname(os.path.abspath(__file__))
    data = argv[2] if len(argv) > 2 else os.path.join(here, "..", "..", "docs", "data")
    table = []
    for run in sorted(glob.glob(os.path.join(out, "seed*", "nv*"))):
        report_path, ends_path = os.path.join(run, "vem", "report.json"), os.path.join(run, "ends.json")
        if not (os.path.isfile(report_path) and os.path.isfile(ends_path)):
            continue
        report = json.load(open(report_path))
        ends = json.load(open(ends_path))
        n = report["voids"] / report["structural"]
        rows = curve_rows(os.path.join(run, "vem", "cn_curve.csv"))
        head = [r for r in rows if int(r["cycle"]) <= ends["stage3_cycle"]]
        analysis = {"window_widths": 4.0, "power_law_max_excess": 1.0}
        inf, phi_i, pl = fits(head, n, report["phi_s"], analysis)
        # CPU seconds of the VEM run and its resumptions; nan when a part was killed before its
        # timer wrote (an empty file): the total would be too low.
        cpu, complete = 0.0, True
        for name in ("vem.time", "vem_resume.time"):
            p = os.path.join(run, name)
            if os.path.isfile(p):
                fields = open(p).read().split()[-3:]
                try:
                    cpu += float(fields[1]) + float(fields[2])
                except (IndexError, ValueError):
                    complete = False
        cpu = cpu if complete and cpu > 0.0 else float("nan")
        for end in ("stage3", "cmatched"):
            doh_path, shear_path = (os.path.join(run, end, "doh", "report.json"),
                                    os.path.join(run, end, "shear", "report.json"))
            if not (os.path.isfile(doh_path) and os.path.isfile(shear_path)):
                continue
            doh, shear = json.load(open(doh_path)), json.load(open(shear_path))
            cycle = ends[f"{end}_cycle"]
            row = next(r for r in rows if int(r["cycle"]) == cycle)
            per = [o["storage_modulus"] for o in shear["storage_modulus"]["per_orientation"]]
            table.append({
                "seed": run.split(os.sep)[-2][4:], "n": f"{n:g}", "voids": report["voids"],
                "structural": report["structural"], "end": end, "cycle": cycle, "q_end": f"{float(row['q']):.6g}",
                "vem_cn_end": f"{float(row['cn']):.6g}", "q_i": f"{inf.x:.6g}", "cn_i": f"{inf.y:.6g}",
                "slope": f"{inf.slope:.6g}", "q_n13": f"{inf.x * n ** (1 / 3):.6g}",
                "slope_n13": f"{inf.slope * n ** (1 / 3):.6g}", "phi_total_i": f"{phi_i:.6g}",
                "beta": f"{pl.beta:.6g}", "beta_r2": f"{pl.r2:.6g}",
                "a": f"{doh['doh']['a']:.6g}", "a_err": f"{doh['doh'].get('a_err', float('nan')):.3g}",
                "coordination": f"{doh['coordination']['mean']:.6g}",
                "storage_modulus": f"{shear['storage_modulus']['mean']:.6g}",
                "std": f"{shear['storage_modulus']['std']:.4g}", "storage_modulus_min": f"{min(per):.6g}",
                "storage_modulus_max": f"{max(per):.6g}",
                "relax_steps": shear["relaxation"]["steps"], "vem_steps": report["steps"],
                "vem_cpu_seconds": f"{cpu:.4g}"})
    path = os.path.join(data, "vem_doh_ns8000.csv")
    with atomic_output(path, ".vem_doh-") as tmp:
        with open(tmp, "w", newline="") as f:
            f.write("# examples/reproduction/vem_doh_ns8000.sh + vem_doh_tables.py: VEM N_S = 8000, Phi_S = 0.4, "
                    "max_q 2.2, one thread; end stage3 = where stage III stops the default run, cmatched = the first "
                    "row with CN >= the paper's C; q_i ... beta fitted on the curve up to the stage III row; a, C "
                    "(eps 0.01) and G'_p [Pa] (static solver, six orientations, SD over them) of the end structure\n")
            w = csv.DictWriter(f, fieldnames=COLUMNS)
            w.writeheader()
            w.writerows(table)
    print(f"wrote {path} ({len(table)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
