#!/usr/bin/env bash
# make docs: redraws the figures of docs/vem.md from the tables checked in under docs/data/
# (written by examples/vem/study_tables.py from a run of examples/vem/study.sh; the study
# itself takes CPU-hours and is not rerun here).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
export PYTHONPATH="$ROOT/python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
PY=/usr/bin/python3
DATA="$ROOT/docs/data"
IMG="$ROOT/docs/img"
read -r qi cni slope < <("$PY" -c "import json,sys; i=json.load(open(sys.argv[1]))['inflection']; print(i['q'], i['cn'], i['slope'])" "$DATA/vem_fig1_report.json")
"$PY" -m packlab.plot cn_curve "$DATA/vem_fig1_cn_curve.csv" --qi "$qi" --cni "$cni" --slope "$slope" --out "$IMG/vem_fig1.png"
"$PY" -m packlab.plot vem_study studies "$DATA/vem_study.csv" "$DATA/vem_curves.csv" --out "$IMG/vem_studies.png"
"$PY" -m packlab.plot vem_study stiffness "$DATA/vem_study.csv" --out "$IMG/vem_stiffness.png"
echo "wrote docs/img/vem_fig1.png, vem_studies.png, vem_stiffness.png from docs/data/vem_*"
