#!/usr/bin/env bash
# The LS memory of two builds side by side (docs/scrm.md, "Slow compressions and the list limit"):
# the fast (G = 3) and slow (G = 0.04) runs to jamming of 10^4 spheres and the bimodal growth to
# c = 0.6 (G = 0.015), each build's bench_ls line with phi_exact, collisions and transfers, so that
# a change of layout can be shown to leave the runs the same to the bit.
# usage: bench/ls_memory_compare.sh OLD_BENCH_LS NEW_BENCH_LS > docs/data/ls_memory_compare_DATE.txt
set -euo pipefail
OLD=$1
NEW=$2
echo "# bench/ls_memory_compare.sh, $(git -C "$(dirname "$0")" describe --always --dirty 2>/dev/null || echo "?"), $(date -u +%F)"
for args in "10000 3" "10000 0.04" "10000 0.015 0.6 0.313 0.333"; do
  for b in "$OLD" "$NEW"; do
    # shellcheck disable=SC2086
    line=$("$b" $args 2>/dev/null | grep -E '^(stop=|packlab ls)' | paste -sd' ')
    echo "build=$(basename "$(dirname "$b")") args=\"$args\" $line"
  done
done
