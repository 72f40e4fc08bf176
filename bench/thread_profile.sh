#!/usr/bin/env bash
# Where the second thread's time goes (issue #14, 2 threads / 1 thread on the relax case):
# perf samples (CPU time) per function of `bench_relax` at 1 thread and at 2 threads fixed, with
# the wait policy the program sets (passive) and with OMP_WAIT_POLICY=active, and the ratio of
# each function's samples at 2 threads to 1. The same work is done at both counts, so a ratio
# above 1 is CPU time the second thread adds: waiting shows as the runtime's own symbols
# (libgomp, the kernel's wake-ups), slower work as the engine's functions. Then the OpenMP
# synchronization micro-benchmarks (bench_micro openmp_*). Needs perf and two free cores.
# usage: bench/thread_profile.sh [BUILD] [STEPS]   (docs/data/thread_profile_*.txt)
set -euo pipefail
BUILD=${1:-build}
STEPS=${2:-4000}
command -v perf > /dev/null || { echo "perf not found: no thread profile"; exit 0; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
profile() {  # NAME THREADS [ENV...]
  local name=$1 threads=$2
  shift 2
  env "$@" perf record -q -o "$work/$name.data" "$BUILD/bench_relax" "$threads" "$STEPS" fixed 2> /dev/null |
    grep -o "pts_per_s=[0-9.e+]*" | sed "s/^/$name: /"
  # "overhead samples dso [.] symbol": samples, then "dso: symbol"; libgomp's spinning and
  # sleeping show as addresses in libgomp.so.
  perf report -q -i "$work/$name.data" -n --sort dso,symbol 2> /dev/null |
    awk '{ s = $2; d = $3; $1 = ""; $2 = ""; $3 = ""; $4 = ""; sub(/^ +/, ""); sub(/ +- -$/, ""); print s "\t" d ": " $0 }' \
      > "$work/$name.txt"
}
profile one 1
profile two 2
profile two_active 2 OMP_WAIT_POLICY=active
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

# Per function: samples at 1 thread, at 2 (passive), at 2 (active), and the ratios; the 12
# largest at 2 threads (passive), then the totals.
awk -F'\t' '
  FILENAME ~ /one.txt$/ { one[$2] += $1; total1 += $1; next }
  FILENAME ~ /two.txt$/ { two[$2] += $1; total2 += $1; names[$2] = 1; next }
  { act[$2] += $1; totala += $1; names[$2] = 1 }
  END {
    printf "%-75s %8s %8s %8s %7s %7s\n", "function", "1 thread", "2 pass.", "2 act.", "ratio", "ratio"
    n = 0
    for (f in names) order[++n] = f
    for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j)
      if (two[order[j]] + act[order[j]] > two[order[i]] + act[order[i]]) { t = order[i]; order[i] = order[j]; order[j] = t }
    for (i = 1; i <= n && i <= 12; ++i) {
      f = order[i]
      r2 = "-"; ra = "-"
      if (one[f] > 0) { r2 = sprintf("%.2f", two[f] / one[f]); ra = sprintf("%.2f", act[f] / one[f]) }
      printf "%-75s %8d %8d %8d %7s %7s\n", substr(f, 1, 75), one[f], two[f], act[f], r2, ra
    }
    printf "%-75s %8d %8d %8d %7.2f %7.2f\n", "all", total1, total2, totala, total2 / total1, totala / total1
  }' "$work/one.txt" "$work/two.txt" "$work/two_active.txt"

echo
"$BUILD/bench_micro" --benchmark_filter=openmp --benchmark_min_time=0.5 2>&1 | grep -E "^openmp"
OMP_WAIT_POLICY=active "$BUILD/bench_micro" --benchmark_filter=openmp --benchmark_min_time=0.5 2>&1 |
  grep -E "^openmp" | sed 's/^/(active) /'
