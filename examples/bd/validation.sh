#!/usr/bin/env bash
# docs/bd.md "Validation": the runs behind docs/data/bd_*.csv and the figures.
#  1. Free diffusion (no DLVO force, dilute): msd.csv against 6 D_0 t (Stokes-Einstein).
#  2. The DLVO potential of the default parameter set at psi_0 = 0, 12, 13, 14, 15 mV.
#  3. Diffusion-limited cluster aggregation of a dilute suspension (psi_0 = 0, Phi = 0.03):
#     the clusters' radius of gyration against their size gives the fractal dimension.
# usage: examples/bd/validation.sh OUTDIR [PACKLAB]   (about 10 min of one core)
set -euo pipefail
OUT=${1:?usage: validation.sh OUTDIR [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
PY=/usr/bin/python3
mkdir -p "$OUT"
# 1. Free diffusion: 4000 spheres, Phi = 0.002, A = 0; any step is exact without forces.
[ -f "$OUT/free/report.json" ] ||
  "$B" generate bd --particles 4000 --phi 0.002 --hamaker-constant 0 --bond-separation 1e-12 \
    --time-step 6.4e-4 --duration 1 --samples 50 --msd --seed 1 --quiet --no-plots --out "$OUT/free"
# 2. Potentials (duration: one step; only potential.csv and report.json's potential are used).
for mv in 0 12 13 14 15; do
  [ -f "$OUT/potential_$mv/report.json" ] ||
    "$B" generate bd --particles 200 --surface-potential "${mv}e-3" --time-step 1e-9 --duration 1e-8 \
      --quench-steps 0 --seed 1 --quiet --no-plots --out "$OUT/potential_$mv"
done
# 3. DLCA: 3000 spheres at Phi = 0.03, psi_0 = 0, rms step 0.05 a (capture on contact).
[ -f "$OUT/dla/report.json" ] ||
  "$B" generate bd --particles 3000 --phi 0.03 --surface-potential 0 --time-step 8e-5 \
    --bond-separation 5e-9 --duration 200 --samples 100 --seed 1 --quiet --no-plots --out "$OUT/dla"
"$PY" "$HERE/validation_tables.py" "$OUT" "$ROOT/docs/data"
