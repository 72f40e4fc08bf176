#!/usr/bin/env bash
# The generator figures of docs/opal-build.md (FBA) and docs/scrm.md (LS), appended to
# docs/data/generator_bench.txt with the commit, the date and the machine load (uptime) before
# and after each run: FBA iterations per phase and CPU time with the structure statistics
# (contacts, g(r)) over seeds for the current and the first contraction rate, the bench case
# (bench_fba 10), and LS at 10^4 and 10^5 particles in one run (CPU time ratio, bytes per
# particle). usage: scripts/bench-generators.sh [BUILD] [SEEDS]
set -euo pipefail
BUILD=${1:-build}
SEEDS=${2:-4}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT="$ROOT/docs/data/generator_bench.txt"
run() {
  echo "# \$ $*   ($(git -C "$ROOT" rev-parse --short HEAD), $(date -u +%F), uptime:$(uptime | sed 's/.*load average/ load average/'))"
  "$BUILD/$@" 2>/dev/null
  echo "# done, uptime:$(uptime | sed 's/.*load average/ load average/')"
}
{
  run bench_fba seeds 10000 "$SEEDS" classic
  run bench_fba seeds 10000 "$SEEDS"
  run bench_fba 10 1
  run bench_ls scaling 10000 100000 3
} | tee -a "$OUT"
