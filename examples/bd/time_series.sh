#!/usr/bin/env bash
# docs/bd.md "Paper size": the BD gels at N = 8000 (the paper's size), central bonds, for the
# surface potentials of Table 2 after several times simulated: a, C and G' (six orientations,
# static solver, k_n = 100 N/m) against the time, to see where the paper's (a, C) would lie.
# Each point is examples/bd/table2_small.sh with N, DURATION and BONDS set; the runs start from the
# same seed, so a shorter run is the start of a longer one (up to its final quench).
# Writes OUTDIR/$CSV (copied to docs/data/ by hand after a run).
# usage: examples/bd/time_series.sh OUTDIR [PACKLAB]
#   env: N (8000), PSI ("0 15": the potentials in mV), T<mV>: the times at that potential in
#        a^2/D_0 (T0 "0.02 0.05 0.1 0.2 0.5 1", T15 "1.5 2.2 3 6", T12 / T13 / T14 none),
#        SEEDS ("1"; seed 1 in OUTDIR/t<mV>_<t>, seed s in OUTDIR/t<mV>_<t>_s<s>), SEEDS<mV>
#        (the seeds at that potential, default SEEDS), THREADS (1), CSV (the table's name),
#        BONDS (--central-bonds; e.g. "--bond-slip-force 1e-11" for slip bonds)
# docs/data/bd_time_series_ns8000.csv: the defaults; docs/data/bd_seeds_ns8000.csv:
#   PSI="0 12 13 14 15" SEEDS="1 2 3" T0="0.05 1" T12=0.115 T13=... T14=... T15="2.2"
#   CSV=bd_seeds_ns8000.csv
set -euo pipefail
OUT=${1:?usage: time_series.sh OUTDIR [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
N=${N:-8000}
T0=${T0-"0.02 0.05 0.1 0.2 0.5 1"}
T15=${T15-"1.5 2.2 3 6"}
PSI=${PSI:-"0 15"}
BONDS=${BONDS:---central-bonds}
mkdir -p "$OUT"
SEEDS=${SEEDS:-1}
csv="$OUT/${CSV:-bd_time_series_ns8000.csv}"
header=""
rows=""
for mv in $PSI; do
  times_var="T$mv"
  seeds_var="SEEDS$mv"
  for t in ${!times_var-}; do
    for seed in ${!seeds_var:-$SEEDS}; do
      d="$OUT/t${mv}_$t$([ "$seed" = 1 ] || echo "_s$seed")"
      N=$N PSI=$mv DURATION=$t SEED=$seed THREADS=${THREADS:-1} BONDS=$BONDS "$HERE/table2_small.sh" "$d" "$B" > /dev/null
      header="seed,$(head -1 "$d/bd_table2_small.csv")"
      rows+="$seed,$(tail -1 "$d/bd_table2_small.csv")"$'\n'
    done
  done
done
printf '%s\n%s' "$header" "$rows" > "$csv"
cat "$csv"
