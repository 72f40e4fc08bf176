#!/usr/bin/env bash
# The phase angle of the oscillatory shear test at the paper's size (docs/reproduction.md, row
# doh.phase_angle; doh-elastic-properties §3.1: delta < 1e-4 pi = 3.1e-4 rad at 1 Hz): the
# N_S = 8000, N_V = 2000 VEM structure (examples/shear/data/vem_ns8000_nv2000.xyz), contact
# bonds, examples/shear/table2_small.toml, orientation z:x, the dynamic test with 3 cycles of
# 20,000, 60,000 and 200,000 steps (a 1 Hz cycle would be ~2e9 steps; delta falls as 1/T).
# Resumable (a finished rate is skipped); OUT/phase_angle.csv collects the rates.
# usage: examples/reproduction/phase_angle.sh OUT [PACKLAB]   (about 25 min of one core)
set -euo pipefail
OUT=${1:?usage: phase_angle.sh OUT [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
[ -f "$OUT/bonded.vtu" ] ||
  "$B" bond "$HERE/../shear/data/vem_ns8000_nv2000.xyz" --model contact --eps 0.01 --threads 1 --quiet \
    --out "$OUT/bonded.vtu"
for steps in 20000 60000 200000; do
  [ -f "$OUT/steps$steps/report.json" ] ||
    "$B" test shear "$OUT/bonded.vtu" --config "$HERE/../shear/table2_small.toml" --orientations z:x \
      --cycles 3 --steps-per-cycle "$steps" --threads 1 --no-plots --quiet --out "$OUT/steps$steps"
done
python3 - "$OUT" <<'PY'
import json, os, sys
out = sys.argv[1]
rows = ["steps_per_cycle,storage_modulus,phase_angle,phase_angle_max_abs,plate_storage_modulus,seconds"]
for steps in (20000, 60000, 200000):
    r = json.load(open(os.path.join(out, f"steps{steps}", "report.json")))
    o = r["storage_modulus"]["per_orientation"][0]
    rows.append(f"{steps},{o['storage_modulus']:.6g},{r['phase_angle']:.4g},{r['phase_angle_max_abs']:.4g},"
                f"{o['plate_storage_modulus']:.6g},{r['seconds']:.4g}")
with open(os.path.join(out, "phase_angle.csv.tmp"), "w") as f:
    f.write("# examples/reproduction/phase_angle.sh: N_S = 8000, N_V = 2000 VEM structure, z:x, 3 cycles per rate; "
            "G' in Pa, phase angles in rad (mean over the cycles and largest |delta|)\n" + "\n".join(rows) + "\n")
os.replace(os.path.join(out, "phase_angle.csv.tmp"), os.path.join(out, "phase_angle.csv"))
print("\n".join(rows))
PY
