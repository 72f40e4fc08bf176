#!/usr/bin/env bash
# Where the LS lists of a slow compression take their memory (docs/scrm.md, "Slow compressions and
# the list limit"): the per-block trace (BENCH_LS_TRACE=1: mean list length, skin, bytes per sphere)
# of the 10^4-sphere run to jamming at G = 0.04 (seed 42) without the list limit and with the
# default, of 2000 spheres at G = 0.02 to c = 0.6 (the SCRM studies' case) without it, and the
# largest memory of the G = 0.04 run for several limits; then the fast compression (G = 3) with and
# without the limit, whose lists stay below it: the same run to the bit (phi_exact, collisions).
# usage: bench/ls_list_trace.sh [BUILD=build] > docs/data/ls_list_trace_DATE.txt
set -euo pipefail
BUILD=${1:-build}
B="$BUILD/bench_ls"
echo "# bench/ls_list_trace.sh, $(git -C "$(dirname "$0")" describe --always --dirty 2>/dev/null || echo "?"), $(date -u +%F)"
for limit in 0 12; do
  echo "## 10^4 mono to jamming, G = 0.04, seed 42, list limit $limit"
  BENCH_LS_TRACE=1 "$B" 10000 0.04 0 1 0.333 1e12 42 "$limit" 2>/dev/null | grep -E '^(trace|packlab ls)'
done
echo "## 2000 mono to c = 0.6, G = 0.02, seed 1, list limit 0"
BENCH_LS_TRACE=1 "$B" 2000 0.02 0.6 1 0.333 1e12 1 0 2>/dev/null | grep -E '^(trace|packlab ls)'
echo "## the largest memory against the limit (10^4 mono to jamming, G = 0.04, seed 42)"
for limit in 20 14 10; do
  "$B" 10000 0.04 0 1 0.333 1e12 42 "$limit" 2>/dev/null | grep '^packlab ls'
done
echo "## 10^4 mono to jamming, G = 3, seed 42, list limit 0 and 12"
for limit in 0 12; do
  "$B" 10000 3 0 1 0.333 1e12 42 "$limit" 2>/dev/null | grep -E '^(stop=|packlab ls)' | paste -sd' '
done
