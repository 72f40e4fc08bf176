#!/usr/bin/env bash
# make demo: the main job on a built-in default — the void expansion method (a small version
# of the paper's Fig. 1 case: 500 structural and 250 void particles at Phi_S = 0.4, about a
# minute), then the microstructure analysis of the structure it made.
set -euo pipefail
BUILD=${1:-build}
OUT=${DEMO_OUT:-demo-output}
P="$BUILD/packlab"
rm -rf "$OUT/vem" "$OUT/analysis"
mkdir -p "$OUT"
echo "== packlab demo 1/2: void expansion method (examples/vem/demo.toml) =="
"$P" generate vem --config examples/vem/demo.toml --out "$OUT/vem"
echo
echo "== packlab demo 2/2: microstructure of the structure (coordination, pore sizes, degree of heterogeneity) =="
"$P" analyze "$OUT/vem/packing.xyz" --what cn,doh,fabric --out "$OUT/analysis"
echo
echo "Results:"
echo "  $OUT/vem/cn_curve.png       CN(q) with its inflection point (cn_curve.csv: the table)"
echo "  $OUT/vem/report.json        inflection q_i, CN_i, slope, Phi_T,i, beta"
echo "  $OUT/vem/packing.vtu        the structure, for ParaView (packing.xyz for OVITO)"
echo "  $OUT/analysis/pore_size.png pore-size distribution with the erf fit (degree of heterogeneity)"
echo "  $OUT/analysis/report.json   mean coordination, rattlers, a, b, volume fraction"
