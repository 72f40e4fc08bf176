#!/usr/bin/env bash
# make demo: the main job on a built-in default. Until the void expansion method lands this
# generates a random overlapping packing, relaxes it with the DEM engine and writes a VTU file
# for ParaView, an XYZ file for OVITO, the relaxation log and its plot.
set -euo pipefail
BUILD=${1:-build}
OUT=${DEMO_OUT:-demo-output}
mkdir -p "$OUT"
P="$BUILD/packlab"
echo "== packlab demo: random packing of 4000 spheres (r = 0.25 um) relaxed with the DEM engine =="
"$P" generate random --particles 4000 --radius 0.25e-6 --phi 0.68 --seed 1 --out "$OUT/start.xyz"
"$P" relax "$OUT/start.xyz" "$OUT/relaxed.vtu" --normal-stiffness 1000 --shear-stiffness 10 --friction 0.1 \
  --damping 0.7 --density 3690 --stiffness-rule contact --tolerance 1e-3 --steps 100000 --log "$OUT/relax.csv"
"$P" convert "$OUT/relaxed.vtu" "$OUT/relaxed.xyz" --quiet
"$P" info "$OUT/relaxed.xyz"
echo
echo "Results in $OUT/:"
echo "  relaxed.vtu  open in ParaView (points with radius, type, velocity)"
echo "  relaxed.xyz  open in OVITO (extended XYZ with box and radii)"
echo "  relax.csv    kinetic/strain energy, unbalanced force ratio, coordination per check"
if [ -f "$OUT/relax.png" ]; then echo "  relax.png    the relaxation history plot"; fi
