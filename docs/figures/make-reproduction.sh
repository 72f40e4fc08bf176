#!/usr/bin/env bash
# make docs: docs/data/reproduction.csv from the tables under docs/data (packlab.reproduction
# collect) and the tables of docs/reproduction.md from it (render), with the figures of the page
# (the studies behind them take CPU-hours and are not rerun here: examples/reproduction/,
# examples/vem/study.sh relax relax_n).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
export PYTHONPATH="$ROOT/python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
PY=/usr/bin/python3
DATA="$ROOT/docs/data"
# Fig. 6 with the VEM structures stopped at the paper's C (seed means) and the BD gels, and the
# eq. 7 fits, from the paper-size runs (examples/reproduction/vem_doh_ns8000.sh + vem_doh_tables.py).
if [ -f "$DATA/vem_doh_ns8000.csv" ]; then
  END=cmatched "$PY" "$ROOT/examples/bd/fig6.py" "$DATA/bd_seeds_ns8000.csv" "$DATA/vem_doh_ns8000.csv" \
    "$DATA/doh_fig6_cmatched.csv" "$DATA/doh_fig6_cmatched_fit.csv" > /dev/null
  "$PY" -m packlab.plot storage_modulus "$DATA/doh_fig6_cmatched.csv" \
    --fit-label "this work: VEM (N_S = 8000; C as the paper's)|this work: BD (N = 8000; C as the paper's)" \
    --out "$ROOT/docs/img/doh_fig6_cmatched.png"
  echo "wrote docs/data/doh_fig6_cmatched*.csv, docs/img/doh_fig6_cmatched.png from docs/data/vem_doh_ns8000.csv"
fi
# The opal resolution study (docs/opal.md "Finer resolution") extrapolated to the paper's D/d.
if [ -f "$DATA/opal_resolution.csv" ]; then
  "$PY" "$ROOT/examples/opal/resolution_extrapolation.py" "$DATA" > /dev/null
  echo "wrote docs/data/opal_resolution_extrapolation.csv from docs/data/opal_resolution.csv"
fi
"$PY" -m packlab.reproduction collect "$DATA"
"$PY" -m packlab.reproduction render "$DATA/reproduction.csv" "$ROOT/docs/reproduction.md"
"$PY" -m packlab.plot vem_study relax "$DATA/vem_relax_study.csv" --out "$ROOT/docs/img/vem_relax_study.png"
echo "wrote docs/img/vem_relax_study.png from docs/data/vem_relax_study.csv"
