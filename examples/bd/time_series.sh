#!/usr/bin/env bash
# docs/bd.md "Paper size": the BD gels at N = 8000 (the paper's size), central bonds, seed 1, for
# psi_0 = 0 and 15 mV after several times simulated: a, C and G' (six orientations, static
# solver, k_n = 100 N/m) against the time, to see where the paper's (a, C) would lie.
# Each point is examples/bd/table2_small.sh with N, DURATION and BONDS set; the runs start from the
# same seed, so a shorter run is the start of a longer one (up to its final quench).
# Writes OUTDIR/$CSV (copied to docs/data/ by hand after a run).
# usage: examples/bd/time_series.sh OUTDIR [PACKLAB]
#   env: N (8000), T0 ("0.02 0.05 0.1 0.2 0.5 1": times at 0 mV, in a^2/D_0), T15 ("1.5 2.2 3 6"),
#        SEEDS ("1"; seed 1 in OUTDIR/t<mV>_<t>, seed s in OUTDIR/t<mV>_<t>_s<s>), SEEDS0 / SEEDS15
#        (the seeds of the 0 and 15 mV runs, default SEEDS), THREADS (1), CSV (the table's name)
# docs/data/bd_time_series_ns8000.csv: the defaults; docs/data/bd_seeds_ns8000.csv:
#   SEEDS="1 2 3" T0="0.05 1" T15="2.2" CSV=bd_seeds_ns8000.csv
set -euo pipefail
OUT=${1:?usage: time_series.sh OUTDIR [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
N=${N:-8000}
T0=${T0-"0.02 0.05 0.1 0.2 0.5 1"}
T15=${T15-"1.5 2.2 3 6"}
mkdir -p "$OUT"
SEEDS=${SEEDS:-1}
SEEDS0=${SEEDS0:-$SEEDS}
SEEDS15=${SEEDS15:-$SEEDS}
csv="$OUT/${CSV:-bd_time_series_ns8000.csv}"
header=""
rows=""
for mv in 0 15; do
  times=$([ "$mv" = 0 ] && echo "$T0" || echo "$T15")
  seeds=$([ "$mv" = 0 ] && echo "$SEEDS0" || echo "$SEEDS15")
  for t in $times; do
    for seed in $seeds; do
      d="$OUT/t${mv}_$t$([ "$seed" = 1 ] || echo "_s$seed")"
      N=$N PSI=$mv DURATION=$t SEED=$seed THREADS=${THREADS:-1} BONDS=--central-bonds "$HERE/table2_small.sh" "$d" "$B" > /dev/null
      header="seed,$(head -1 "$d/bd_table2_small.csv")"
      rows+="$seed,$(tail -1 "$d/bd_table2_small.csv")"$'\n'
    done
  done
done
printf '%s\n%s' "$header" "$rows" > "$csv"
cat "$csv"
