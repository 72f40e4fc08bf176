#!/usr/bin/env bash
# The Table 2 / Fig. 6 study scaled down (docs/shear.md): VEM structures with N_S = 1000 at the
# paper's ratios n = N_V / N_S = 0.125 ... 2 (the paper: N_S = 8000, N_V = 1000 ... 16000),
# Phi_S = 0.4, the VEM defaults of examples/vem (threads 1, max_q 2.2); their degree of
# heterogeneity a (eq. 6) and coordination C; contact bonds at (1 + 0.01) 2r; the oscillatory
# shear test with Table 1 parameters in six orientations; G' against a with the fit of eq. 7.
# usage: examples/shear/table2_study.sh OUTDIR [PACKLAB]   (about 40 min of one core)
set -euo pipefail
OUT=${1:?usage: table2_study.sh OUTDIR [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
echo "name,n,voids,a,a_err,coordination,storage_modulus,std,phase_angle" > "$OUT/table2.csv"
for nv in 125 250 500 1000 1625 2000; do
  name=$(printf "nv%04d" "$nv")
  [ -f "$OUT/$name/vem/packing.xyz" ] ||
    "$B" generate vem --structural 1000 --voids "$nv" --phi-s 0.4 --seed 1 --threads 1 --max-q 2.2 --quiet \
      --out "$OUT/$name/vem"
  "$B" analyze "$OUT/$name/vem/packing.xyz" --what cn,doh --threads 1 --quiet --no-plots --out "$OUT/$name/doh"
  "$B" bond "$OUT/$name/vem/packing.xyz" --model contact --eps 0.01 --out "$OUT/$name/bonded.vtu" --quiet
  # The loose structures (C ~ 4) need slower cycles to be quasi-static (docs/shear.md, "Rate").
  slow=""
  [ "$nv" -ge 1625 ] && slow="--steps-per-cycle 40000 --cycles 4 --relax-max-steps 100000"
  "$B" test shear "$OUT/$name/bonded.vtu" --config "$HERE/table2_small.toml" $slow --quiet --out "$OUT/$name/shear"
  python3 - "$OUT" "$name" "$nv" <<'PY'
import json, sys
out, name, nv = sys.argv[1], sys.argv[2], int(sys.argv[3])
d = json.load(open(f"{out}/{name}/doh/report.json"))
s = json.load(open(f"{out}/{name}/shear/report.json"))
g = s["storage_modulus"]
with open(f"{out}/table2.csv", "a") as f:
    f.write(f"{name},{nv / 1000},{nv},{d['doh']['a']},{d['doh']['a_err']},{d['mean_coordination']},"
            f"{g['mean']},{g['std']},{s['phase_angle']}\n")
PY
done
python3 -m packlab.plot storage_modulus "$OUT/table2.csv" --out "$OUT/storage_modulus.png"
cat "$OUT/table2.csv"
