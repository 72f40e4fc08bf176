#!/usr/bin/env bash
# make bench: packlab's benchmarks, and the peers' runs of the same cases in the same session
# so the ratios compare like with like. Prints rates (particle-steps/s, collisions/s, ...).
set -uo pipefail
BUILD=${1:-build}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PEERS="$ROOT/../shared/peers/dem"
[ -d "$PEERS" ] || PEERS="$ROOT/shared/peers/dem"

rate() { awk -F'pts_per_s=' '/pts_per_s=/{split($2, a, " "); r = a[1]} END {print r}'; }

echo "== DEM case 'relax' (8000 spheres, 20,000 steps; ../shared/peers/dem/common.sh) =="
declare -A ours theirs
for t in 1 2; do
  out=$("$BUILD/bench_relax" "$t")
  echo "$out"
  ours[$t]=$(echo "$out" | rate)
done
if [ -x "$PEERS/lammps-relax.sh" ]; then
  for np in 1 2; do
    out=$(bash "$PEERS/lammps-relax.sh" "$np" 2>&1)
    echo "$out" | tail -2
    theirs[$np]=$(echo "$out" | rate)
  done
  for t in 1 2; do
    if [ -n "${theirs[$t]:-}" ] && [ -n "${ours[$t]:-}" ]; then
      awk -v a="${ours[$t]}" -v b="${theirs[$t]}" -v t="$t" \
        'BEGIN { printf "ratio packlab/LAMMPS (%d core%s): %.2f  (%.3g vs %.3g particle-steps/s)\n", t, t > 1 ? "s" : "", a / b, a, b }'
    fi
  done
else
  echo "(peer scripts not found at $PEERS: LAMMPS ratio skipped)"
fi

# Every other benchmark program prints its own rates.
for b in "$BUILD"/bench_*; do
  name=$(basename "$b")
  [ "$name" = bench_relax ] && continue
  [ -x "$b" ] || continue
  echo
  echo "== $name =="
  "$b"
done
