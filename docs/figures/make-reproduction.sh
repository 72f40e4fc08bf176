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
"$PY" -m packlab.reproduction collect "$DATA"
"$PY" -m packlab.reproduction render "$DATA/reproduction.csv" "$ROOT/docs/reproduction.md"
"$PY" -m packlab.plot vem_study relax "$DATA/vem_relax_study.csv" --out "$ROOT/docs/img/vem_relax_study.png"
echo "wrote docs/img/vem_relax_study.png from docs/data/vem_relax_study.csv"
