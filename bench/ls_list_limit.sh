#!/usr/bin/env bash
# The LS neighbour-list limit (LsParams::neighbor_list_limit, docs/scrm.md "Slow compressions and
# the list limit"): the slow compressions of make bench with the default limit (12) and without
# it (0), several seeds each, alternating so that the machine's drift falls on both; then per
# setting the mean and SD of the CPU time, the largest memory per sphere and the volume fraction
# reached, and the difference of the volume fraction paired by seed (the same start points).
# usage: bench/ls_list_limit.sh [BUILD=build] [MONO_SEEDS="42 ... 49"] [BIMODAL_SEEDS="42 43 44"]
#        > docs/data/ls_list_limit_DATE.txt
#        bench/ls_list_limit.sh --summary FILE...   the summaries of the runs of earlier outputs together
set -euo pipefail
. "$(dirname "$0")/summary_awk.sh"
summarize() {  # the runs' lines on stdin
  awk "$SUMMARY_AWK"'
  {
    k = kv($0, "case") " list_limit=" kv($0, "list_limit")
    n[k]++; cpu[k] += kv($0, "ls_cpu_s"); cpu2[k] += kv($0, "ls_cpu_s")^2
    peak[k] += kv($0, "peak_bytes_per_particle"); peak2[k] += kv($0, "peak_bytes_per_particle")^2
    phi[k] += kv($0, "phi_exact"); phi2[k] += kv($0, "phi_exact")^2
    tr[k] += kv($0, "transfers")
    at[kv($0, "case") SUBSEP kv($0, "seed") SUBSEP kv($0, "list_limit")] = kv($0, "phi_exact")
    seeds[kv($0, "case") SUBSEP kv($0, "seed")] = 1
  }
  END {
    for (k in n)
      printf("summary case=%s runs=%d cpu_s=%.2f+-%.2f peak_bytes_per_particle=%.1f+-%.1f phi=%.6f+-%.6f transfers=%.4g\n",
             k, n[k], cpu[k] / n[k], sd(cpu[k], cpu2[k], n[k]), peak[k] / n[k], sd(peak[k], peak2[k], n[k]),
             phi[k] / n[k], sd(phi[k], phi2[k], n[k]), tr[k] / n[k])
    # The runs are paired by seed (same start points): the difference limit 12 - none per seed.
    for (cs in seeds) {
      split(cs, part, SUBSEP)
      if (!((cs SUBSEP "12") in at) || !((cs SUBSEP "0") in at)) continue
      d = at[cs SUBSEP "12"] - at[cs SUBSEP "0"]
      pn[part[1]]++; pd[part[1]] += d; pd2[part[1]] += d * d; if (d > 0) pup[part[1]]++
    }
    for (c in pn) {
      m = pn[c]; mean = pd[c] / m; se = sd(pd[c], pd2[c], m) / sqrt(m)
      printf("summary_paired case=%s pairs=%d phi_difference=%.6f standard_error=%.6f t=%.2f higher_with_limit=%d\n",
             c, m, mean, se, se > 0 ? mean / se : 0, pup[c] + 0)
    }
  }
' | sort
}
if [ "${1:-}" = --summary ]; then
  shift
  cat "$@" | grep '^case=' | summarize
  exit 0
fi
BUILD=${1:-build}
MONO_SEEDS=${2-"42 43 44 45 46 47 48 49"}
BIMODAL_SEEDS=${3-"42 43 44"}
B="$BUILD/bench_ls"
echo "# bench/ls_list_limit.sh, $(git -C "$(dirname "$0")" describe --always --dirty 2>/dev/null || echo "?"), $(date -u +%F), load: $(cut -d' ' -f1-3 /proc/loadavg)"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# One line per run: bench_ls's last two lines joined (phi_exact and transfers are on the first).
one() {  # CASE SEED LIMIT ARGS...
  local name=$1 seed=$2 limit=$3; shift 3
  "$B" "$@" 1e12 "$seed" "$limit" 2>/dev/null | grep -E '^(stop=|packlab ls)' | paste -sd' ' | sed "s/^/case=$name seed=$seed /" | tee -a "$log"
}
for seed in $MONO_SEEDS; do
  for limit in 12 0; do one mono "$seed" "$limit" 10000 0.04 0 1 0.333; done  # to jamming at G = 0.04
done
for seed in $BIMODAL_SEEDS; do
  for limit in 12 0; do one bimodal "$seed" "$limit" 10000 0.015 0.6 0.313 0.333; done  # the paper's case to c = 0.6
done
summarize < "$log"
