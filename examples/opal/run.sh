#!/usr/bin/env bash
# The inverse-opal study of docs/opal.md at reduced resolution (15 nm particles, pores of 10
# particle diameters = 150 nm instead of 762 nm), single-threaded. Every number and figure of
# docs/opal.md comes from this script; the total is about 30 CPU-minutes. It ends with the
# tables of docs/data/ (OUT/docs-data/opal_*.csv) and the figures drawn from them (OUT/figures):
#   examples/opal/run.sh [OUT] [PACKLAB]
#   cp OUT/docs-data/opal_*.csv docs/data/ && make docs      # refresh the docs from the new run
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${1:-opal-study}
PACKLAB=${2:-packlab}
# The Python package (plots) and, beside a built PACKLAB, the compiled module (packlab.fit_porosity_law).
BIN=$(command -v "$PACKLAB" || true)
PY_BUILD=${BIN:+$(dirname "$BIN")/python}
export PYTHONPATH="$HERE/../../python${PY_BUILD:+:$PY_BUILD}${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
CFG="$HERE/silica.toml"
mkdir -p "$OUT"
d=15e-9

# 1. Bulk factor K_E = E_macro / E_b (eq. 20) and bulk strength from a pore-free sample.
$PACKLAB generate fba --box 150e-9,150e-9,210e-9 --diameter $d --porosity 0.38 --periodic xy \
  --seed 1 --quiet --no-plots --out "$OUT/bulk-packing"
$PACKLAB bond "$OUT/bulk-packing/packing.vtu" --model elastic --cutoff-ratio 1.75 --quiet --out "$OUT/bulk.vtu"
$PACKLAB calibrate compress "$OUT/bulk.vtu" --bulk-factor --config "$CFG" --out "$OUT/bulk"
# The same sample with open sides (a free-standing pillar) and with eq. 16 applied to compressed
# bonds too (the two other readings in docs/opal.md).
$PACKLAB calibrate compress "$OUT/bulk.vtu" --bulk-factor --config "$CFG" --sides open --out "$OUT/bulk-open"
$PACKLAB calibrate compress "$OUT/bulk.vtu" --bulk-factor --config "$CFG" --bond-compressive-breakage \
  --out "$OUT/bulk-compressive"

# 2. FCC inverse opal ([111] along z), 2 x 1 lateral periods, 3 pore layers (box height =
#    substrate 2 d + 2 layer spacings + D, like the paper's 2.01 um), two fixed substrate layers,
#    bonds within 1.75 d. Eq. (1) removes every particle with L <= R + r, i.e. it cuts spheres of
#    radius R + r: at D/d = 51 (the paper) that widens touching pores by 2 % (openings of 0.2 R);
#    at D/d = 10 it would widen them by 10 % (porosity 0.87). So the pore lattice keeps the
#    nearest-neighbour distance a = 150 nm and the pores get D = 138 nm (R + r = 76.5 nm: the
#    paper's relative opening), spacing ratio a / D = 1.087: porosity 0.75.
a=150e-9
D=138e-9
$PACKLAB generate fba --box 300e-9,259.81e-9,412.95e-9 --diameter $d --porosity 0.38 --periodic xy \
  --seed 2 --quiet --no-plots --out "$OUT/fcc-packing"
$PACKLAB build opal "$OUT/fcc-packing/packing.vtu" --pores fcc --pore-diameter $D --pore-spacing 1.087 --orientation 111 --quiet \
  --out "$OUT/fcc"
# Why not D = a: touching pores of D = 150 nm, widened by eq. (1) to nearly cut struts.
$PACKLAB build opal "$OUT/fcc-packing/packing.vtu" --pores fcc --pore-diameter $a --pore-spacing 1 --orientation 111 \
  --quiet --out "$OUT/fcc-touching"
$PACKLAB test compress "$OUT/fcc-touching/opal.vtu" --config "$CFG" --no-vtu --out "$OUT/fcc-touching-test"
# The paper's bond parameters as they are, with bond strain and stress snapshots (Fig. 7, Table 2).
$PACKLAB test compress "$OUT/fcc/opal.vtu" --config "$CFG" --snapshot-strains 0.005,0.01,0.015,0.02 \
  --out "$OUT/fcc-paper"
# Rate independence: twice the rate.
$PACKLAB test compress "$OUT/fcc/opal.vtu" --config "$CFG" --quasi-static 2e-4 --no-vtu --out "$OUT/fcc-fast"

# 3. Calibration (eq. 18-19) to the experiment: E* = 1.7 GPa, strength 41.3 MPa, to 0.5 %.
$PACKLAB calibrate compress "$OUT/fcc/opal.vtu" --config "$CFG" --target-youngs-modulus 1.7e9 \
  --target-strength 41.3e6 --stop-drop 0.85 --out "$OUT/fcc-calibration"

# 4. Coated opal: titania on the pore walls, 3.6 nm thick = the paper's 20 nm scaled by the pore
#    size (138 / 762): density 668 kg/m^3 as the paper's 20 nm sample. Compared with step 2's
#    uncoated test at the same (paper's) bond values: silica 6.53 GPa / 94.3 MPa, titania
#    17.89 GPa / 834 MPa (Table 1, 20 nm), stresses per material at the same strains (Table 2).
$PACKLAB build opal "$OUT/fcc-packing/packing.vtu" --pores fcc --pore-diameter $D --pore-spacing 1.087 --orientation 111 \
  --coating 3.6e-9 --quiet --out "$OUT/fcc-coated"
$PACKLAB test compress "$OUT/fcc-coated/opal.vtu" --config "$CFG" --snapshot-strains 0.005,0.01,0.015,0.02 \
  --out "$OUT/fcc-coated-paper"

# 5. Porosity study (§4): random pores (2, 3 and 4 pores of 138 nm in a 250 x 250 x 300 nm
#    sample: more do not fit through the force-biased pore placement), two realizations each, fits of
#    eq. 22, 23 and 26 (E0 held at the bulk modulus K_E E_b of step 1). With the paper's bond
#    values: E is proportional to E_b (the fitted b, m do not depend on it) and the strength
#    nearly so to sigma_max; twice the default rate (E moves 0.2 %, the strength 2 %, see
#    docs/opal.md) to halve the cost.
/usr/bin/python3 "$HERE/porosity_study.py" --out "$OUT/porosity" --packlab "$PACKLAB" --config "$CFG" \
  --bulk-report "$OUT/bulk/report.json" --quasi-static 2e-4 --counts 2,3,4 --seeds 1,2

# 6. The tables of docs/data/ and the figures of docs/opal.md drawn from them (the same code as
#    make docs: docs/figures/make-opal-figures.sh).
/usr/bin/python3 "$HERE/study_figures.py" tables "$OUT" "$OUT/docs-data"
/usr/bin/python3 "$HERE/study_figures.py" figures "$OUT/docs-data" "$OUT/figures"
echo "to refresh the docs: cp $OUT/docs-data/opal_*.csv docs/data/ && make docs"
