#!/usr/bin/env bash
# The reduced-size reproduction of the paper's studies shown in docs/vem.md (N_S = 1000 unless
# the name says otherwise, one thread per run, Table 1 parameters and the defaults of
# docs/vem.md), one study per group: examples/study/vem_GROUP.toml run by `packlab study` into
# OUT/GROUP (docs/study.md). Runs that already have a report are skipped, so the script can be
# restarted. Afterwards examples/vem/study_tables.py OUT writes the tables that `make docs` draws
# from (docs/data/vem_*.csv).
#   [JOBS=1] examples/vem/study.sh [OUT] [PACKLAB] [GROUP...]   GROUP: dt n size phi mass stiffness fig1 relax relax_n phi_ns4000 kn_limit stiffness_limit
# Cost on one free core: ~30 s per N_S = 1000 run, ~15-25 min per soft-void stiffness run
# (K_n <= 1e-4 never reach stage III before max_q = 2), ~10 min for fig1 on two threads.
# JOBS: runs at a time (default 1: one core per run, as the costs above).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${1:-vem-study}
PACKLAB=${2:-packlab}
shift $(( $# > 2 ? 2 : $# )) || true
GROUPS_TO_RUN=${*:-dt n size phi mass stiffness fig1 relax relax_n phi_ns4000 kn_limit stiffness_limit}
for group in $GROUPS_TO_RUN; do
  spec="$HERE/../study/vem_$group.toml"
  [ -f "$spec" ] || { echo "study.sh: unknown group '$group': must be one of dt n size phi mass stiffness fig1 relax relax_n phi_ns4000 kn_limit stiffness_limit" >&2; exit 2; }
  echo "$(date +%T) $group: $PACKLAB study $spec --out $OUT/$group"
  "$PACKLAB" study "$spec" --out "$OUT/$group" --workers "${JOBS:-1}"
done
echo "$(date +%T) done: $OUT"
