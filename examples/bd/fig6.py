"""docs/bd.md "Fig. 6 with both structure sets": G'_p against the DOH parameter a of the VEM
structures (docs/shear.md, N_S = 8000) and of the BD gels (N = 8000, central bonds), each BD
potential at the time whose mean C over the seeds is nearest the paper's C (Table 2), with
the paper's eleven structures; the eq. 7 fit G' = C (a - a0)^beta over our eleven points, over
each set alone, and over the paper's eleven (the same fit, packlab.plot.storage_modulus).

usage: /usr/bin/python3 examples/bd/fig6.py BD_SEEDS_CSV VEM_CSV OUT_TABLE_CSV OUT_FIT_CSV
  (docs/data/bd_seeds_ns8000.csv docs/data/shear_table2_ns8000.csv docs/data/bd_fig6_ns8000.csv
   docs/data/bd_fig6_fit_ns8000.csv; docs/figures/make-bd-figures.sh draws the figure)
VEM_CSV may also be examples/reproduction/vem_doh_tables.py's docs/data/vem_doh_ns8000.csv (one row
per seed and end point): then the VEM points are the seed means of the end point END (environment,
default cmatched: the structures stopped at the paper's C), docs/reproduction.md.
"""

import os
import statistics
import sys

from packlab.plot.bd_table2 import PAPER
from packlab.plot.storage_modulus import fit_power_law
from packlab.reproduction import DOH_TABLE2_VEM, bd_at_paper_c
from packlab.tables import read_table

# doh-elastic-properties Table 2: psi_0 [mV] or N_V -> (a, C, G'_p [Pa], SD over six orientations [Pa]),
# from packlab.plot.bd_table2 and packlab.reproduction (G'_p in MPa there).
PAPER_BD = {mv: (a, c, g * 1e6, sd * 1e6) for mv, (a, c, g, sd) in PAPER.items()}
PAPER_VEM = {nv: (a, c, g * 1e6, sd * 1e6) for nv, (a, c, g, sd) in DOH_TABLE2_VEM.items()}
OURS_VEM, OURS_BD = "this work: VEM (N_S = 8000)", "this work: BD (N = 8000; C as the paper's)"
OURS_VEM_MATCHED = "this work: VEM (N_S = 8000; C as the paper's)"
PAPER_VEM_LABEL, PAPER_BD_LABEL = "paper: VEM", "paper: BD"


def bd_rows(seeds_csv):
    """Per potential, the seed means at the time whose mean C is nearest the paper's
    (packlab.reproduction.bd_at_paper_c)."""
    rows = []
    for mv, (time, chosen) in bd_at_paper_c(seeds_csv).items():
        mean = lambda name: statistics.mean(float(r[name]) for r in chosen)
        rows.append({"set": "BD", "source": OURS_BD, "structure": f"{mv} mV at t = {time:g} a^2/D_0 ({len(chosen)} seeds)",
                     "a": mean("a"), "C": mean("C"), "storage_modulus": mean("storage_modulus_Pa"),
                     "std": mean("storage_modulus_std_Pa")})
    return rows


def vem_rows(vem_csv):
    t = read_table(vem_csv)
    if "end" not in t:
        return [{"set": "VEM", "source": OURS_VEM, "structure": f"N_V = {int(t['voids'][k])}", "a": t["a"][k],
                 "C": t["coordination"][k], "storage_modulus": t["storage_modulus"][k], "std": t["std"][k]}
                for k in range(len(t["a"]))]
    end = os.environ.get("END", "cmatched")
    groups = {}
    for k in range(len(t["a"])):
        if t["end"][k] == end and int(t["voids"][k]) in PAPER_VEM:
            groups.setdefault(int(t["voids"][k]), []).append(k)
    mean = lambda name, idx: statistics.mean(float(t[name][k]) for k in idx)
    label = OURS_VEM_MATCHED if end == "cmatched" else f"this work: VEM {end} (N_S = 8000)"
    return [{"set": "VEM", "source": label, "structure": f"N_V = {nv} ({len(idx)} seeds)", "a": mean("a", idx),
             "C": mean("coordination", idx), "storage_modulus": mean("storage_modulus", idx), "std": mean("std", idx)}
            for nv, idx in sorted(groups.items())]


def paper_rows():
    rows = [{"set": "VEM", "source": PAPER_VEM_LABEL, "structure": f"N_V = {nv}", "a": v[0], "C": v[1],
             "storage_modulus": v[2], "std": v[3]} for nv, v in PAPER_VEM.items()]
    rows += [{"set": "BD", "source": PAPER_BD_LABEL, "structure": f"{mv} mV", "a": v[0], "C": v[1],
              "storage_modulus": v[2], "std": v[3]} for mv, v in PAPER_BD.items()]
    return rows


def main(seeds_csv, vem_csv, table_out, fit_out):
    rows = vem_rows(vem_csv) + bd_rows(seeds_csv) + paper_rows()
    with open(table_out, "w") as f:
        f.write("# examples/bd/fig6.py: Fig. 6 with both structure sets (docs/bd.md); G' and its SD over the six "
                "orientations in Pa; BD rows: means over the seeds\n")
        f.write("label,set,structure,a,coordination,storage_modulus,std\n")
        for r in rows:
            f.write(f"{r['source']},{r['set']},{r['structure']},{r['a']:.6g},{r['C']:.6g},"
                    f"{r['storage_modulus']:.6g},{r['std']:.6g}\n")
    vem_label = next((r["source"] for r in rows if r["set"] == "VEM" and r["source"].startswith("this work")), OURS_VEM)
    fits = [("this work: VEM + BD", [vem_label, OURS_BD]), ("this work: VEM", [vem_label]),
            ("this work: BD", [OURS_BD]), ("paper: VEM + BD", [PAPER_VEM_LABEL, PAPER_BD_LABEL]),
            ("paper: VEM", [PAPER_VEM_LABEL]), ("paper: BD", [PAPER_BD_LABEL])]
    with open(fit_out, "w") as f:
        f.write("# examples/bd/fig6.py: eq. 7 fit G' = prefactor (a - a0)^beta (packlab.plot.storage_modulus)\n")
        f.write("data,points,a0,beta,prefactor_Pa\n")
        for name, sources in fits:
            sel = [r for r in rows if r["source"] in sources]
            fit = fit_power_law([r["a"] for r in sel], [r["storage_modulus"] for r in sel])
            f.write(f"{name},{len(sel)},{fit['a0']:.4f},{fit['beta']:.3f},{fit['prefactor']:.4g}\n")
    print(open(table_out).read())
    print(open(fit_out).read())


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
