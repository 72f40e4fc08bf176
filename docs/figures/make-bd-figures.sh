#!/usr/bin/env bash
# make docs: redraws the figures of docs/bd.md from the tables in docs/data/bd_* (written by
# examples/bd/validation.sh, about 10 min of one core, and by the paper-size scripts below; not
# rerun here).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
export PYTHONPATH="$ROOT/python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
PY=/usr/bin/python3
DATA="$ROOT/docs/data"
IMG="$ROOT/docs/img"
"$PY" -m packlab.plot bd_validation msd "$DATA/bd_msd.csv" --out "$IMG/bd_msd.png"
"$PY" -m packlab.plot bd_validation potential "$DATA/bd_potential.csv" --out "$IMG/bd_potential.png"
"$PY" -m packlab.plot bd_validation fractal "$DATA/bd_dla_clusters.csv" --out "$IMG/bd_fractal.png"
# The paper-size gels (examples/bd/time_series.sh, fig5.sh and coordination_series.sh, about 4 h of one core).
"$PY" -m packlab.plot bd_table2 time "$DATA/bd_time_series_ns8000.csv" --out "$IMG/bd_time_ns8000.png"
"$PY" -m packlab.plot bd_table2 fig5 "$DATA/bd_fig5_ns8000.csv" --out "$IMG/bd_fig5_ns8000.png"
"$PY" -m packlab.plot bd_table2 coordination "$DATA/bd_coordination_ns8000.csv" --out "$IMG/bd_coordination_ns8000.png"
# Fig. 6 with both structure sets: the table and the fits from the BD seeds and the VEM rows.
"$PY" "$ROOT/examples/bd/fig6.py" "$DATA/bd_seeds_ns8000.csv" "$DATA/shear_table2_ns8000.csv" \
  "$DATA/bd_fig6_ns8000.csv" "$DATA/bd_fig6_fit_ns8000.csv" > /dev/null
"$PY" -m packlab.plot storage_modulus "$DATA/bd_fig6_ns8000.csv" \
  --fit-label "this work: VEM (N_S = 8000)|this work: BD (N = 8000; C as the paper's)" --out "$IMG/bd_fig6_ns8000.png"
echo "wrote docs/img/bd_msd.png, bd_potential.png, bd_fractal.png, bd_time_ns8000.png, bd_fig5_ns8000.png,"
echo "  bd_coordination_ns8000.png, bd_fig6_ns8000.png from docs/data/bd_* (and bd_fig6_ns8000.csv, bd_fig6_fit_ns8000.csv)"
