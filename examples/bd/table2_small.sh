#!/usr/bin/env bash
# docs/bd.md "Reduced-size runs of Table 2's BD rows": BD structures (N = 1000, Phi = 0.4, the
# default DLVO parameters) for psi_0 = 0 and 15 mV (set PSI="0 12 13 14 15" for all rows), their
# DOH parameter a and coordination C (analyze --what cn,doh: eq. 6 fit, contact eps 0.01),
# contact bonds at (1 + 0.01) 2 r0, and G' in six orientations with the quasi-static solver at
# k_n = 100 N/m (examples/shear/table2_small.toml, as docs/shear.md's VEM rows).
# Writes OUTDIR/bd_table2_small.csv (copied to docs/data/ by hand after a run).
# usage: examples/bd/table2_small.sh OUTDIR [PACKLAB]
#   env: N (1000), DURATION (in a^2/D_0; 1 for 0 mV, 3 for the others), BONDS ("" or "--central-bonds"),
#        SEED (1), THREADS (1: the BD run's threads; the result does not depend on them)
set -euo pipefail
OUT=${1:?usage: table2_small.sh OUTDIR [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
N=${N:-1000}
PSI=${PSI:-"0 15"}
BONDS=${BONDS:-}
SEED=${SEED:-1}
THREADS=${THREADS:-1}
mkdir -p "$OUT"
for mv in $PSI; do
  d="$OUT/psi$mv"
  mkdir -p "$d"
  dur=${DURATION:-$([ "$mv" = 0 ] && echo 1 || echo 3)}
  [ -f "$d/bd/report.json" ] ||
    "$B" generate bd --particles "$N" --phi 0.4 --surface-potential "${mv}e-3" --duration "$dur" $BONDS \
      --seed "$SEED" --threads "$THREADS" --quiet --out "$d/bd"
  [ -f "$d/doh/report.json" ] ||
    "$B" analyze "$d/bd/packing.xyz" --what cn,doh --threads 1 --quiet --no-plots --out "$d/doh"
  [ -f "$d/bonded.vtu" ] ||
    "$B" bond "$d/bd/packing.xyz" --model contact --eps 0.01 --threads 1 --out "$d/bonded.vtu" --quiet
  [ -f "$d/shear/report.json" ] ||
    "$B" test shear "$d/bonded.vtu" --config "$HERE/../shear/table2_small.toml" --solver static --threads 1 \
      --relax-max-steps 100000 --no-plots --quiet --out "$d/shear"
done
/usr/bin/python3 - "$OUT" "$PSI" <<'PY'
import json, sys
out, psis = sys.argv[1], sys.argv[2].split()
rows = ["surface_potential_mV,particles,time_diffusion_times,bonds_bd,largest_cluster_fraction,a,b,C,storage_modulus_Pa,storage_modulus_std_Pa"]
for mv in psis:
    bd = json.load(open(f"{out}/psi{mv}/bd/report.json"))
    doh = json.load(open(f"{out}/psi{mv}/doh/report.json"))
    sh = json.load(open(f"{out}/psi{mv}/shear/report.json"))
    rows.append(",".join(str(v) for v in [mv, bd["parameters"]["particles"], bd["results"]["time_simulated_diffusion_times"],
        bd["results"]["bonds"], bd["results"]["largest_cluster_fraction"], doh["doh"]["a"], doh["doh"]["b"],
        doh["mean_coordination"], sh["storage_modulus"]["mean"], sh["storage_modulus"]["std"]]))
open(f"{out}/bd_table2_small.csv", "w").write("\n".join(rows) + "\n")
print("\n".join(rows))
PY
