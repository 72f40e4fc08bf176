#!/usr/bin/env bash
# docs/bd.md "Fig. 5": G'_p of the least and the most heterogeneous BD structure (psi_0 = 0 and
# 15 mV, made by examples/bd/table2_small.sh) against the particle normal stiffness k_n, with
# k_n / k_s = 10 as in the paper's calibration (§3.1), by the quasi-static solver in six
# orientations (examples/shear/table2_small.toml otherwise). Writes OUTDIR/bd_fig5.csv:
# structure, k_n, G' mean and SD, and the ratio G'(15 mV) / G'(0 mV) at each k_n (the paper:
# 3.4, experiment 3.6).
# usage: examples/bd/fig5.sh HOMOGENEOUS_DIR HETEROGENEOUS_DIR OUTDIR [PACKLAB]
#   (each DIR holds bonded.vtu, as table2_small.sh's OUT/psiN folders do); env: KN ("50 75 100 125 150")
set -euo pipefail
HO=${1:?usage: fig5.sh HOMOGENEOUS_DIR HETEROGENEOUS_DIR OUTDIR [PACKLAB]}
HE=${2:?usage}
OUT=${3:?usage}
B=${4:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
KN=${KN:-"50 75 100 125 150"}
mkdir -p "$OUT"
for s in HO HE; do
  dir=${!s}
  for kn in $KN; do
    d="$OUT/$s/kn$kn"
    ks=$(/usr/bin/python3 -c "print($kn / 10)")
    [ -f "$d/report.json" ] ||
      "$B" test shear "$dir/bonded.vtu" --config "$HERE/../shear/table2_small.toml" --solver static --threads 1 \
        --normal-stiffness "$kn" --shear-stiffness "$ks" --relax-max-steps 100000 --no-plots --quiet --out "$d"
  done
done
/usr/bin/python3 - "$OUT" "$KN" "$HO" "$HE" <<'PY'
import json, sys
out, kns, ho, he = sys.argv[1], sys.argv[2].split(), sys.argv[3], sys.argv[4]
rows = [f"# HO = {ho}, HE = {he}", "k_n_N_per_m,G_HO_Pa,G_HO_std_Pa,G_HE_Pa,G_HE_std_Pa,ratio_HE_HO"]
for kn in kns:
    g = {s: json.load(open(f"{out}/{s}/kn{kn}/report.json"))["storage_modulus"] for s in ("HO", "HE")}
    rows.append(",".join(str(v) for v in [kn, g["HO"]["mean"], g["HO"]["std"], g["HE"]["mean"], g["HE"]["std"],
                                          g["HE"]["mean"] / g["HO"]["mean"]]))
open(f"{out}/bd_fig5.csv", "w").write("\n".join(rows) + "\n")
print("\n".join(rows))
PY
