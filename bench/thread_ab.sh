#!/usr/bin/env bash
# Two builds side by side on the thread-scaling cases of bench/run.sh (issue #14): relax,
# bonded compression (the 3,400-particle opal) and shear, each at 1 and at 2 threads fixed for
# both builds, ROUNDS times alternating (this VM's rates move from one minute to the next:
# compare medians of alternating runs, never two single runs).
# usage: bench/thread_ab.sh OLD_BUILD_DIR NEW_BUILD_DIR [ROUNDS]
# Every run waits passively (OMP_WAIT_POLICY=passive), as the packlab program does.
set -euo pipefail
OLD=$1 NEW=$2 ROUNDS=${3:-4}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SHEAR="$ROOT/examples/shear/data/vem_ns8000_nv2000.xyz"
export OMP_WAIT_POLICY=passive
rate() { grep -o 'pts_per_s=[^ ]*' | tail -1 | cut -d= -f2; }
echo "# bench/thread_ab.sh $OLD $NEW $ROUNDS ($(date -u +%FT%TZ), load average: $(cut -d' ' -f1-3 /proc/loadavg))"
echo "# case build threads particle-steps/s"
ROWS=$(mktemp); trap 'rm -f "$ROWS"' EXIT
for _ in $(seq 1 "$ROUNDS"); do
  for build in old new; do
    dir=$OLD; [ $build = new ] && dir=$NEW
    for threads in 1 2; do
      echo "relax $build $threads $("$dir/bench_relax" $threads 3000 fixed 2>&1 | rate)"
      echo "compress $build $threads $("$dir/bench_compress" $threads - 1 500 fixed 2>&1 | rate)"
      echo "shear $build $threads $("$dir/bench_shear" "$SHEAR" $threads 2000 1 fixed 2>&1 | rate)"
    done
  done
done | tee "$ROWS"
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# medians (case build threads: median of ROUNDS runs):"
sort -k1,1 -k2,2 -k3,3 -k4,4g "$ROWS" | awk '
  { k = $1 " " $2 " " $3; n[k]++; v[k, n[k]] = $4 }
  END { for (k in n) { m = n[k]; med = m % 2 ? v[k, (m + 1) / 2] : (v[k, m / 2] + v[k, m / 2 + 1]) / 2; printf "#   %s: %.3g\n", k, med } }' | sort
