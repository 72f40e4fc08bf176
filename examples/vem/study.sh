#!/usr/bin/env bash
# The reduced-size reproduction of the paper's studies shown in docs/vem.md (N_S = 1000 unless
# the name says otherwise, one thread per run, Table 1 parameters and the defaults of
# docs/vem.md). Runs that already have a report are skipped, so the script can be restarted.
# Afterwards examples/vem/study_tables.py OUT writes the tables that `make docs` draws from
# (docs/data/vem_*.csv).
#   examples/vem/study.sh [OUT] [PACKLAB] [GROUP...]   GROUP: dt n size phi mass stiffness fig1
# Cost on one free core: ~30 s per N_S = 1000 run, ~15-25 min per soft-void stiffness run
# (K_n <= 1e-4 never reach stage III before max_q = 2), ~10 min for fig1 on two threads.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${1:-vem-study}
PACKLAB=${2:-packlab}
shift $(( $# > 2 ? 2 : $# )) || true
GROUPS_TO_RUN=${*:-dt n size phi mass stiffness fig1}
mkdir -p "$OUT/cfg"
printf '[output]\nplots = false\n' > "$OUT/cfg/default.toml"
printf 'void_mass_scaling = 0.25\n[output]\nplots = false\n' > "$OUT/cfg/mass025.toml"
printf 'time_step_rule = "contacts"\ntime_step_safety = 0.2\n[output]\nplots = false\n' > "$OUT/cfg/contacts02.toml"
printf 'time_step_rule = "contacts"\ntime_step_safety = 0.4\n[output]\nplots = false\n' > "$OUT/cfg/contacts04.toml"

run() {  # run NAME ARGS...
  local name=$1
  shift
  [ -f "$OUT/$name/report.json" ] && return 0
  echo "$(date +%T) $name: $PACKLAB generate vem $*"
  "$PACKLAB" generate vem --quiet --no-plots "$@" --out "$OUT/$name"
}
wants() { [[ " $GROUPS_TO_RUN " == *" $1 "* ]]; }

N="--structural 1000 --threads 1"
if wants dt; then  # the time-step rule (docs/vem.md "Time step"), three seeds each
  for seed in 1 2 3; do
    run n050_seed$seed --config "$OUT/cfg/default.toml" $N --voids 500 --seed $seed
    run n050_contacts02_seed$seed --config "$OUT/cfg/contacts02.toml" $N --voids 500 --seed $seed
    run n050_contacts04_seed$seed --config "$OUT/cfg/contacts04.toml" $N --voids 500 --seed $seed
  done
fi
if wants n; then  # Fig. 2/3: n = N_V / N_S
  run n025 --config "$OUT/cfg/default.toml" $N --voids 250
  run n100 --config "$OUT/cfg/default.toml" $N --voids 1000
  run n200 --config "$OUT/cfg/default.toml" $N --voids 2000
fi
if wants size; then  # the curve does not depend on N at fixed n
  run n050_ns2000 --config "$OUT/cfg/default.toml" --structural 2000 --voids 1000 --threads 1
  run n050_ns4000 --config "$OUT/cfg/default.toml" --structural 4000 --voids 2000 --threads 1
fi
if wants phi; then  # Fig. 4: Phi_S
  for phi in 0.2 0.3 0.5 0.55; do
    run phi${phi/./} --config "$OUT/cfg/default.toml" $N --voids 500 --phi-s $phi
  done
fi
if wants mass; then  # void mass scaling c = 0.25 instead of 1
  run n050_mass025 --config "$OUT/cfg/mass025.toml" $N --voids 500
fi
if wants stiffness; then  # Fig. 6-8: K_n = k_n,V / k_n,S with k_n,S = 1e3 N/m
  for knv in 1e1 1e0 1e3 1e-1 1e-2 1e-3; do  # cheap ones first
    run stiffness_kns1e3_knv$knv --config "$HERE/stiffness_study/kns1e3_knv$knv.toml" $N --voids 500
  done
fi
if wants fig1; then  # Fig. 1 at the paper's size: N_S = 8000, N_V = 2000, two threads
  run fig1 --config "$HERE/fig1.toml" --threads 2
fi
echo "$(date +%T) done: $OUT"
