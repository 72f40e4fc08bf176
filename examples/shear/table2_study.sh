#!/usr/bin/env bash
# The Table 2 / Fig. 6 study scaled down (docs/shear.md): examples/study/shear_table2.toml run by
# `packlab study` (docs/study.md): VEM structures with N_S = 1000 at the paper's ratios
# n = N_V / N_S = 0.125 ... 2, Phi_S = 0.4; their degree of heterogeneity a (eq. 6) and
# coordination C; contact bonds at (1 + 0.01) 2r; the oscillatory shear test with Table 1
# parameters in six orientations; then OUTDIR/table2.csv and G' against a with the fit of eq. 7.
# Resumable: a rerun skips the finished runs.
# usage: [JOBS=1] examples/shear/table2_study.sh OUTDIR [PACKLAB]   (about 40 min of one core)
set -euo pipefail
OUT=${1:?usage: table2_study.sh OUTDIR [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
"$B" study "$HERE/../study/shear_table2.toml" --out "$OUT" --workers "${JOBS:-1}"
/usr/bin/python3 - "$OUT" <<'PY'
import csv, sys
out = sys.argv[1]
with open(f"{out}/tasks.csv", newline="") as f:
    rows = [r for r in csv.DictReader(f) if r["status"] == "done"]
with open(f"{out}/table2.csv", "w") as f:
    f.write("name,n,voids,a,a_err,coordination,storage_modulus,std,phase_angle\n")
    for r in rows:
        f.write(f"nv{int(r['vem.voids']):04d},{r['n']},{r['vem.voids']},{r['doh.doh.a']},{r['doh.doh.a_err']},"
                f"{r['doh.mean_coordination']},{r['shear.storage_modulus.mean']},{r['shear.storage_modulus.std']},"
                f"{r['shear.phase_angle']}\n")
PY
PYTHONPATH="$HERE/../../python${PYTHONPATH:+:$PYTHONPATH}" /usr/bin/python3 -m packlab.plot storage_modulus \
  "$OUT/table2.csv" --out "$OUT/storage_modulus.png"
cat "$OUT/table2.csv"
