#!/usr/bin/env bash
# docs/reproduction.md "a of the loose structures": Table 1's two structural stiffnesses of the VEM
# paper (k_n,S = 1e3, k_s,S = 1e-2 N/m, packlab's default, and k_n,S = 1e2, k_s,S = 1e-3 N/m; the
# DOH paper states only the void stiffnesses) at N_S = 1000, n = 0.5 and 2 (N_V = 500, 2000), seeds
# 1 and 2, through examples/reproduction/vem_doh_ns8000.sh (NS = 1000; each structure at stage III
# and where CN first reaches the target C: 4.69 for N_V = 500, 4.71 for N_V = 2000, the script's
# lookup by N_V), then one table docs/data/vem_kns_variation_ns1000.csv (vem_doh_tables.py's
# columns and the structural normal stiffness). ~15 CPU-min.
# usage: examples/reproduction/kns_variation.sh OUT [PACKLAB]
set -euo pipefail
OUT=${1:?usage: kns_variation.sh OUT [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
export PYTHON=${PYTHON:-python3} NS=1000
VEM_OPTIONS="" "$HERE/vem_doh_ns8000.sh" "$OUT/k1e3" "$B" "1 2" 2000 500
VEM_OPTIONS="--structural-material-normal-stiffness 100 --structural-material-shear-stiffness 1e-3" \
  "$HERE/vem_doh_ns8000.sh" "$OUT/k1e2" "$B" "1 2" 2000 500
for k in k1e3 k1e2; do
  mkdir -p "$OUT/$k/table"
  "$PYTHON" "$HERE/vem_doh_tables.py" "$OUT/$k" "$OUT/$k/table"
done
"$PYTHON" - "$OUT" "$HERE/../../docs/data/vem_kns_variation_ns1000.csv" <<'PY'
import os, sys
out, dest = sys.argv[1], sys.argv[2]
lines = ["# examples/reproduction/kns_variation.sh: VEM N_S = 1000, Phi_S = 0.4, N_V = 500 and 2000, seeds 1 and 2, "
         "k_n,S = 1e3 (k_s,S = 1e-2) and 1e2 (k_s,S = 1e-3) N/m; columns of vem_doh_tables.py\n"]
for k, value in (("k1e3", "1000"), ("k1e2", "100")):
    rows = [l for l in open(os.path.join(out, k, "table", "vem_doh_ns8000.csv")) if not l.startswith("#")]
    if len(lines) == 1:
        lines.append("structural_normal_stiffness," + rows[0])
    lines += [f"{value},{l}" for l in rows[1:]]
tmp = dest + ".tmp"
open(tmp, "w").writelines(lines)
os.replace(tmp, dest)
print("wrote", dest)
PY
