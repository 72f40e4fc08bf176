#!/usr/bin/env bash
# The LS memory of two or more builds side by side (docs/scrm.md, "Slow compressions and the list limit"):
# the fast (G = 3) and slow (G = 0.04) runs to jamming of 10^4 spheres and the bimodal growth to
# c = 0.6 (G = 0.015), each build's bench_ls line with phi_exact, collisions and transfers, so that
# a change of layout can be shown to leave the runs the same to the bit.
# usage: bench/ls_memory_compare.sh OLD_BENCH_LS NEW_BENCH_LS [MORE_BENCH_LS...] > docs/data/ls_memory_compare_DATE.txt
#        (each build is named by its binary's folder, or by BUILD_NAMES="old new ..." in that order)
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: ls_memory_compare.sh OLD_BENCH_LS NEW_BENCH_LS [MORE_BENCH_LS...]" >&2; exit 2; }
read -r -a names <<< "${BUILD_NAMES:-}"
echo "# bench/ls_memory_compare.sh, $(git -C "$(dirname "$0")" describe --always --dirty 2>/dev/null || echo "?"), $(date -u +%F)"
for args in "10000 3" "10000 0.04" "10000 0.015 0.6 0.313 0.333"; do
  k=0
  for b in "$@"; do
    name=${names[$k]:-$(basename "$(dirname "$b")")}
    k=$((k + 1))
    # One traced run (BENCH_LS_TRACE: a line per block): its last block's line gives the largest
    # memory to a tenth of a byte, bench_ls's last two lines the rest.
    # shellcheck disable=SC2086
    out=$(BENCH_LS_TRACE=1 "$b" $args 2>/dev/null)
    line=$(grep -E '^(stop=|packlab ls)' <<< "$out" | paste -sd' ')
    peak=$(grep '^trace ' <<< "$out" | tail -1 | grep -o 'peak_bytes_per_particle=[^ ]*' | cut -d= -f2)
    echo "build=$name args=\"$args\" $line peak_bytes_per_particle_exact=$peak"
  done
done
