#!/usr/bin/env bash
# The LS list-length limit applied to the lists a block ends with (docs/scrm.md, "The limit in the
# dense fluid"): two builds of bench_ls on the slow compressions of make bench, paired by seed
# (the same start points), the two builds of a pair run at the same time (one per core), so that
# the machine's load falls on both. Per case and build: the mean and SD of the CPU time, the
# largest memory per sphere, the volume fraction reached and the reduced pressure at the end;
# per case the paired difference NEW - OLD of phi_exact (to jamming) or of the reduced pressure
# (bimodal, to c = 0.6), how many pairs are the same run to the bit (same phi_exact, collisions
# and transfers), and the reduced pressure compared at equal volume fraction (equal_phi below).
# The runs are traced (a line per block, kept in the output).
# usage: bench/ls_fill_bound.sh OLD_BENCH_LS NEW_BENCH_LS [MONO_SEEDS="42 ... 49"] [BIMODAL_SEEDS="42 ... 47"]
#        > docs/data/ls_fill_bound_DATE.txt
#        bench/ls_fill_bound.sh --summary FILE...   the summary of earlier outputs' runs
set -euo pipefail
. "$(dirname "$0")/summary_awk.sh"
summarize() {  # the runs' lines on stdin
  awk "$SUMMARY_AWK"'
  {
    c = kv($0, "case"); b = kv($0, "build"); k = c " build=" b
    n[k]++
    cpu[k] += kv($0, "ls_cpu_s"); cpu2[k] += kv($0, "ls_cpu_s")^2
    pk[k] += kv($0, "peak_bytes_per_particle"); pk2[k] += kv($0, "peak_bytes_per_particle")^2
    ph[k] += kv($0, "phi_exact"); ph2[k] += kv($0, "phi_exact")^2
    pr[k] += kv($0, "reduced_pressure"); pr2[k] += kv($0, "reduced_pressure")^2
    tr[k] += kv($0, "transfers")
    key = c SUBSEP kv($0, "seed")
    seeds[key] = 1
    stat = (c == "mono") ? kv($0, "phi_exact") : kv($0, "reduced_pressure")
    value[key SUBSEP b] = stat
    run[key SUBSEP b] = kv($0, "phi_exact") " " kv($0, "collisions") " " kv($0, "transfers")
  }
  END {
    for (k in n)
      printf("summary case=%s runs=%d cpu_s=%.2f+-%.2f peak_bytes_per_particle=%.1f+-%.1f phi=%.6f+-%.6f reduced_pressure=%.4g+-%.3g transfers=%.4g\n",
             k, n[k], cpu[k] / n[k], sd(cpu[k], cpu2[k], n[k]), pk[k] / n[k], sd(pk[k], pk2[k], n[k]),
             ph[k] / n[k], sd(ph[k], ph2[k], n[k]), pr[k] / n[k], sd(pr[k], pr2[k], n[k]), tr[k] / n[k])
    for (key in seeds) {
      split(key, part, SUBSEP)
      if (!((key SUBSEP "old") in value) || !((key SUBSEP "new") in value)) continue
      c = part[1]; d = value[key SUBSEP "new"] - value[key SUBSEP "old"]
      pn[c]++; pd[c] += d; pd2[c] += d * d; if (d > 0) up[c]++
      if (run[key SUBSEP "new"] == run[key SUBSEP "old"]) same[c]++
    }
    for (c in pn) {
      m = pn[c]; mean = pd[c] / m; se = sd(pd[c], pd2[c], m) / sqrt(m)
      printf("summary_paired case=%s statistic=%s pairs=%d difference_new_minus_old=%.6g standard_error=%.3g t=%.2f higher_new=%d same_to_the_bit=%d\n",
             c, c == "mono" ? "phi_exact" : "reduced_pressure", m, mean, se, se > 0 ? mean / se : 0, up[c] + 0, same[c] + 0)
    }
  }
' | sort
}
# The pressure at equal volume fraction. A block's reduced pressure is its mean over the block,
# and a block ends after events_per_block x N events (collisions and transfers): where the
# builds transfer differently their blocks end at other volume fractions, and the last block
# (to the target) spans another interval of a steeply rising p. So each NEW block with its
# midpoint's phi in [0.45, 0.6] is compared with OLD's pressure interpolated (linearly, between OLD's block
# midpoints) at the NEW block's midpoint; the relative differences are averaged per seed, then
# over the seeds (mean and standard error).
equal_phi() {  # trace lines on stdin
  awk "$SUMMARY_AWK"'
  {
    k = kv($0, "case") SUBSEP kv($0, "seed") SUBSEP kv($0, "build")
    phi = kv($0, "phi")
    m = ++nb[k]; mid[k, m] = (m > 1 ? (last[k] + phi) / 2 : phi / 2); pr[k, m] = kv($0, "reduced_pressure"); last[k] = phi
    cs[kv($0, "case") SUBSEP kv($0, "seed")] = 1
  }
  END {
    for (c in cs) {
      split(c, part, SUBSEP); o = c SUBSEP "old"; w = c SUBSEP "new"
      if (!(o in nb) || !(w in nb)) continue
      sum = 0; cnt = 0
      for (b = 2; b <= nb[w]; ++b) {
        x = mid[w, b]
        if (x < 0.45 || x > 0.6) continue  # the dense fluid (near jamming p diverges and phi stalls)
        for (q = 2; q < nb[o] && mid[o, q + 1] < x; ++q) {}
        if (q >= nb[o] || mid[o, q] > x || mid[o, q + 1] <= mid[o, q]) continue  # outside OLD midpoints
        f = (x - mid[o, q]) / (mid[o, q + 1] - mid[o, q])
        po = pr[o, q] + f * (pr[o, q + 1] - pr[o, q])
        sum += pr[w, b] / po - 1; cnt++
      }
      if (cnt == 0) continue
      d = sum / cnt; n[part[1]]++; s1[part[1]] += d; s2[part[1]] += d * d; blocks[part[1]] += cnt
    }
    for (c in n) {
      m = n[c]; mean = s1[c] / m; v = m > 1 ? (s2[c] - s1[c] * s1[c] / m) / (m - 1) : 0; se = v > 0 ? sqrt(v / m) : 0
      printf("summary_equal_phi case=%s seeds=%d blocks=%d pressure_new_over_old_minus_1=%.5f standard_error=%.5f t=%.2f\n",
             c, m, blocks[c], mean, se, se > 0 ? mean / se : 0)
    }
  }' | sort
}
if [ "${1:-}" = --summary ]; then
  shift
  { grep -h '^case=' "$@" || true; } | summarize
  { grep -h '^trace ' "$@" || true; } | equal_phi
  exit 0
fi
OLD=${1:?usage: ls_fill_bound.sh OLD_BENCH_LS NEW_BENCH_LS [MONO_SEEDS] [BIMODAL_SEEDS]}
NEW=${2:?usage: ls_fill_bound.sh OLD_BENCH_LS NEW_BENCH_LS [MONO_SEEDS] [BIMODAL_SEEDS]}
MONO_SEEDS=${3-"42 43 44 45 46 47 48 49"}
BIMODAL_SEEDS=${4-"42 43 44 45 46 47"}
echo "# bench/ls_fill_bound.sh, $(git -C "$(dirname "$0")" describe --always --dirty 2>/dev/null || echo "?"), $(date -u +%F), load: $(cut -d' ' -f1-3 /proc/loadavg)"
log=$(mktemp)
trap 'rm -f "$log" "$log".*' EXIT
one() {  # BUILD_NAME BINARY CASE SEED ARGS...: bench_ls's last two lines joined
  local name=$1 bin=$2 cs=$3 seed=$4; shift 4
  local out
  out=$(BENCH_LS_TRACE=1 "$bin" "$@" 1e12 "$seed" 2>/dev/null)
  grep -E '^(stop=|packlab ls)' <<< "$out" | paste -sd' ' | sed "s/^/case=$cs seed=$seed build=$name /"
  grep '^trace ' <<< "$out" | sed "s/^trace /trace case=$cs seed=$seed build=$name /"
}
pair() {  # CASE SEED ARGS...: old and new at once, one per core
  one old "$OLD" "$@" > "$log.old" &
  one new "$NEW" "$@" > "$log.new"
  wait
  cat "$log.old" "$log.new" | tee -a "$log"
}
for seed in $MONO_SEEDS; do pair mono "$seed" 10000 0.04 0 1 0.333; done                 # to jamming at G = 0.04
for seed in $BIMODAL_SEEDS; do pair bimodal "$seed" 10000 0.015 0.6 0.313 0.333; done   # the paper's case to c = 0.6
grep '^case=' "$log" | summarize
grep '^trace ' "$log" | equal_phi
