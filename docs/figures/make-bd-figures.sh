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
# The paper-size gels (examples/bd/time_series.sh and examples/bd/fig5.sh, about 2 h of one core).
"$PY" -m packlab.plot bd_table2 time "$DATA/bd_time_series_ns8000.csv" --out "$IMG/bd_time_ns8000.png"
"$PY" -m packlab.plot bd_table2 fig5 "$DATA/bd_fig5_ns8000.csv" --out "$IMG/bd_fig5_ns8000.png"
echo "wrote docs/img/bd_msd.png, bd_potential.png, bd_fractal.png, bd_time_ns8000.png, bd_fig5_ns8000.png from docs/data/bd_*"
