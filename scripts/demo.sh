#!/usr/bin/env bash
# make demo: the main job on a built-in default — the void expansion method (a small version
# of the paper's Fig. 1 case: 500 structural and 250 void particles at Phi_S = 0.4, about a
# minute), then the microstructure analysis of the structure it made, its bonded model and
# the oscillatory shear test of that model (storage modulus G', doh-elastic-properties §2.4).
set -euo pipefail
BUILD=${1:-build}
OUT=${DEMO_OUT:-demo-output}
P="$BUILD/packlab"
rm -rf "$OUT/vem" "$OUT/analysis" "$OUT/shear" "$OUT/bonded.vtu"
mkdir -p "$OUT"
echo "== packlab demo 1/3: void expansion method (examples/vem/demo.toml) =="
"$P" generate vem --config examples/vem/demo.toml --out "$OUT/vem"
echo
echo "== packlab demo 2/3: microstructure of the structure (coordination, pore sizes, degree of heterogeneity) =="
"$P" analyze "$OUT/vem/packing.xyz" --what cn,doh,fabric --out "$OUT/analysis"
echo
echo "== packlab demo 3/3: contact bonds and the oscillatory shear test (plate normal z, both shear directions) =="
"$P" bond "$OUT/vem/packing.xyz" --model contact --eps 0.01 --out "$OUT/bonded.vtu"
"$P" test shear "$OUT/bonded.vtu" --orientations z --cycles 4 --steps-per-cycle 8000 --relax-max-steps 20000 \
  --out "$OUT/shear"
echo
echo "Results:"
echo "  $OUT/vem/cn_curve.png       CN(q) with its inflection point (cn_curve.csv: the table)"
echo "  $OUT/vem/report.json        inflection q_i, CN_i, slope, Phi_T,i, beta"
echo "  $OUT/vem/packing.vtu        the structure, for ParaView (packing.xyz for OVITO)"
echo "  $OUT/analysis/pore_size.png pore-size distribution with the erf fit (degree of heterogeneity)"
echo "  $OUT/analysis/report.json   mean coordination, rattlers, a, b, volume fraction"
echo "  $OUT/bonded.vtu             the bonded model (bonds as lines in ParaView)"
echo "  $OUT/shear/report.json      storage modulus G' per orientation, phase angle"
echo "  $OUT/shear/shear.png        stress and strain per cycle (Fig. 4 of the paper)"
