#!/usr/bin/env bash
# make docs: redraws the figures of the paper studies from the tables checked in under
# docs/data/ (the studies themselves take CPU-hours and run from examples/*/: their scripts
# write these tables). Figures whose tables are not checked in are listed in the pages.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
export PYTHONPATH="$ROOT/python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
PY=/usr/bin/python3
"$PY" -m packlab.plot storage_modulus "$ROOT/docs/data/shear_table2.csv" --fit-label "this work (N_S = 1000)" --out "$ROOT/docs/img/shear_fig6.png"
echo "wrote docs/img/shear_fig6.png from docs/data/shear_table2.csv"
# Table 2 at the paper's size: the N_S = 8000 points (static solver) with the N_S = 1000 ones and the
# paper's, fit over the N_S = 8000 points; the combined table is written to a temporary file only.
T=$(mktemp --suffix=.csv)
trap 'rm -f "$T"' EXIT
"$PY" - "$ROOT/docs/data/shear_table2_ns8000.csv" "$ROOT/docs/data/shear_table2.csv" "$T" <<'PY'
import sys
from packlab.tables import read_table
big, small, out = sys.argv[1:]
b, s = read_table(big), read_table(small)
with open(out, "w") as f:
    f.write("a,storage_modulus,std,label\n")
    for a, g, e in zip(b["a"], b["storage_modulus"], b["std"]):
        f.write(f"{a},{g},{e},this work (N_S = 8000; static)\n")
    for a, g, e, lab in zip(s["a"], s["storage_modulus"], s["std"], s["label"]):
        f.write(f"{a},{g},{e},{lab.replace('this work (N_S = 1000)', 'this work (N_S = 1000; dynamic)')}\n")
PY
"$PY" -m packlab.plot storage_modulus "$T" --fit-label "this work (N_S = 8000; static)" --out "$ROOT/docs/img/shear_fig6_ns8000.png"
echo "wrote docs/img/shear_fig6_ns8000.png from docs/data/shear_table2_ns8000.csv and docs/data/shear_table2.csv"
