#!/usr/bin/env bash
# Where the FCC opal breaks (bpm-inverse-opals §3, Fig. 8; docs/opal.md "Fracture pattern"): the
# opal of docs/opal.md (15 nm particles, pores 138 nm at 150 nm, [111] along z, D/d = 9.2) four
# lattice periods wide in x and two in y (the paper's 8.05 um^2 at its scale), with the paper's
# Fig. 8 height of four pore layers (16,355 particles) and with three (13,463), compressed by the
# quasi-static solver with the paper's bonds to half its peak stress, once with periodic and
# once with open sides; then examples/opal/fracture_pattern.py turns the break records into
# docs/data/opal_fracture_pattern.csv, opal_fracture_layers.csv and
# docs/img/opal_fracture_pattern.png (the four-layer sample). About 8 minutes.
#   examples/opal/fracture_pattern.sh [OUT] [PACKLAB]
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${1:-opal-fracture}
PACKLAB=${2:-packlab}
BIN=$(command -v "$PACKLAB" || true)
PY_BUILD=${BIN:+$(dirname "$BIN")/python}
export PYTHONPATH="$HERE/../../python${PY_BUILD:+:$PY_BUILD}${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
mkdir -p "$OUT"
# Height: 2 d of substrate + (layers - 1) [111] layer spacings (122.47 nm) + D.
for layers in 3 4; do
  height=$([ $layers = 3 ] && echo 412.95e-9 || echo 535.42e-9)
  dir="$OUT/layers$layers"
  $PACKLAB generate fba --box 600e-9,519.62e-9,$height --diameter 15e-9 --porosity 0.38 --periodic xy \
    --seed 2 --quiet --no-plots --out "$dir/packing"
  $PACKLAB build opal "$dir/packing/packing.vtu" --pores fcc --pore-diameter 138e-9 --pore-spacing 1.087 \
    --orientation 111 --quiet --out "$dir/opal"
  for sides in periodic open; do
    $PACKLAB test compress "$dir/opal/opal.vtu" --config "$HERE/silica.toml" --solver static --sides $sides \
      --stop-drop 0.5 --no-plots --quiet --out "$dir/$sides"
  done
done
/usr/bin/python3 "$HERE/fracture_pattern.py" "$OUT"
