#!/usr/bin/env bash
# Where the FCC opal breaks (bpm-inverse-opals §3, Fig. 8; docs/opal.md "Fracture pattern"): the
# opal of docs/opal.md (15 nm particles, pores 138 nm at 150 nm, [111] along z, 3 pore layers,
# D/d = 9.2) four lattice periods wide in x and two in y (13,463 particles), compressed by the
# quasi-static solver with the paper's bonds to half its peak stress, once with periodic and
# once with open sides; then examples/opal/fracture_pattern.py turns the break records into
# docs/data/opal_fracture_pattern.csv and docs/img/opal_fracture_pattern.png. About 3 minutes.
#   examples/opal/fracture_pattern.sh [OUT] [PACKLAB]
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${1:-opal-fracture}
PACKLAB=${2:-packlab}
BIN=$(command -v "$PACKLAB" || true)
PY_BUILD=${BIN:+$(dirname "$BIN")/python}
export PYTHONPATH="$HERE/../../python${PY_BUILD:+:$PY_BUILD}${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
mkdir -p "$OUT"
$PACKLAB generate fba --box 600e-9,519.62e-9,412.95e-9 --diameter 15e-9 --porosity 0.38 --periodic xy \
  --seed 2 --quiet --no-plots --out "$OUT/packing"
$PACKLAB build opal "$OUT/packing/packing.vtu" --pores fcc --pore-diameter 138e-9 --pore-spacing 1.087 \
  --orientation 111 --quiet --out "$OUT/opal"
for sides in periodic open; do
  $PACKLAB test compress "$OUT/opal/opal.vtu" --config "$HERE/silica.toml" --solver static --sides $sides \
    --stop-drop 0.5 --no-plots --quiet --out "$OUT/$sides"
done
/usr/bin/python3 "$HERE/fracture_pattern.py" "$OUT"
