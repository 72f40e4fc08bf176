#!/usr/bin/env bash
# make docs: redraws the five figures of docs/opal.md (docs/figures/opal-*.png) from the tables
# checked in under docs/data/opal_*.csv, without any simulation. The tables come from the study
# examples/opal/run.sh (about 30 CPU-minutes; it writes OUT/docs-data/opal_*.csv: copy them
# here to refresh). The drawing code is examples/opal/study_figures.py, which run.sh also uses.
#   docs/figures/make-opal-figures.sh [BUILD]
# BUILD is not needed; when make docs has put the compiled module on PYTHONPATH, the porosity
# fits in opal_porosity_fits.csv are checked against a refit of opal_porosity.csv.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
export PYTHONPATH="$ROOT/python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
/usr/bin/python3 "$ROOT/examples/opal/study_figures.py" figures "$ROOT/docs/data" "$ROOT/docs/figures"
