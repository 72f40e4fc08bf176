#!/usr/bin/env python3
"""Table of the force-biased packings behind the opal studies (bpm-inverse-opals §2.1: the
initial random packings of 15 nm spheres at porosity 0.38): one row per packing of the studies
given (every `runs/packing-*` folder of each STUDY_OUT), read from the packing's report.json:

  DATA/opal_fba_packings.csv   study, box [nm], seed, particles, target and reached porosity,
                               largest overlap left (fraction of the diameter; the FBA's
                               tolerance is 1e-3), iterations, contacts per particle within
                               0.01 d, seconds

usage: fba_tables.py STUDY_OUT [STUDY_OUT ...] [--data DATA]   (DATA defaults to docs/data)"""

import glob
import json
import os
import sys

from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))
COLUMNS = ["study", "box_x_nm", "box_y_nm", "box_z_nm", "seed", "particles", "target_porosity", "porosity",
           "max_overlap", "iterations", "contacts_per_particle", "seconds"]


def main(argv):
    args = argv[1:]
    data = os.path.join(HERE, "..", "..", "docs", "data")
    if "--data" in args:
        at = args.index("--data")
        if at + 1 >= len(args):
            sys.exit(__doc__)
        data = args[at + 1]
        del args[at:at + 2]
    if not args:
        sys.exit(__doc__)
    rows = []
    for out in args:
        for report in sorted(glob.glob(os.path.join(out, "runs", "packing-*", "report.json"))):
            with open(report) as f:
                r = json.load(f)
            p, res = r["parameters"], r["results"]
            rows.append({"study": os.path.basename(os.path.normpath(out)),
                         **{f"box_{a}_nm": round(v * 1e9, 6) for a, v in zip("xyz", p["box_m"])},
                         "seed": p["seed"], "particles": p["particles"], "target_porosity": p["target_porosity"],
                         "porosity": res["porosity"], "max_overlap": res["verified_max_overlap"],
                         "iterations": res["iterations"], "contacts_per_particle": res["mean_coordination_eps_0.01"],
                         "seconds": res["fba_seconds"]})
    if not rows:
        sys.exit(f"fba_tables: no packing report under {', '.join(args)}")
    rows.sort(key=lambda r: (r["study"], r["particles"], r["seed"]))
    path = os.path.join(data, "opal_fba_packings.csv")
    write_table(path, {k: [r[k] for r in rows] for k in COLUMNS},
                "examples/opal/fba_tables.py: the force-biased packings (15 nm spheres, porosity 0.38) of the opal "
                "studies named in the column study")
    print(f"wrote {path} ({len(rows)} packings, {min(r['particles'] for r in rows)}-"
          f"{max(r['particles'] for r in rows)} particles)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
