#!/usr/bin/env bash
# make bench: packlab's benchmarks, and the peers' runs of the same cases in the same session
# so the ratios compare like with like. Prints rates (particle-steps/s, collisions/s, ...).
set -uo pipefail
BUILD=${1:-build}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
# Everything printed also goes to a log, read back at the end into issue #14's table of
# targets (bench/targets.sh): each target with this run's figure and whether it holds.
if [ -z "${PACKLAB_BENCH_LOG_OPEN:-}" ]; then
  LOG=${BENCH_LOG:-$BUILD/bench.log}
  PACKLAB_BENCH_LOG_OPEN=1 bash "$0" "$@" 2>&1 | tee "$LOG"
  status=${PIPESTATUS[0]}
  bash "$ROOT/bench/targets.sh" "$LOG" | tee -a "$LOG"
  echo "(log: $LOG)"
  exit "$status"
fi
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
        'BEGIN { printf "ratio packlab/LAMMPS (%d core%s): %.2f  (%.3g vs %.3g particle-steps/s)\n", t, (t > 1 ? "s" : ""), a / b, a, b }'
    fi
  done
  # Memory beside the peer's: LAMMPS's own estimate for the same case (bench/lammps_memory.sh).
  bash "$ROOT/bench/lammps_memory.sh" "$PEERS"
else
  echo "(peer scripts not found at $PEERS: LAMMPS ratio skipped)"
fi

# Issue #14: two threads on a loaded machine (another process busy on one core) must never be
# slower than one. A busy loop holds one core while the relax case runs 3,000 steps at 1
# thread, at 2 threads fixed, and at 2 threads adapting its count (the default).
echo; echo "== relax on a loaded machine (a busy loop on one core) =="
( while :; do :; done ) &
busy=$!
declare -A loaded
for mode in "1" "2 fixed" "2"; do
  t=${mode%% *}
  extra=""; [ "$mode" = "2 fixed" ] && extra=fixed
  out=$("$BUILD/bench_relax" "$t" 3000 $extra)
  echo "$out" | head -1
  loaded[$mode]=$(echo "$out" | rate)
done
kill "$busy" 2>/dev/null; wait "$busy" 2>/dev/null
awk -v one="${loaded[1]}" -v fixed="${loaded[2 fixed]}" -v adapt="${loaded[2]}" \
  'BEGIN { printf "loaded machine, particle-steps/s: 1 thread %.3g, 2 threads fixed %.3g (%.2fx), 2 threads adaptive %.3g (%.2fx; target >= 1)\n", one, fixed, fixed / one, adapt, adapt / one }'

# Issue #14: 2 threads / 1 thread >= 1.85 on every engine case. Each case at 1 thread and at 2
# threads fixed (adaptation off), short runs, with the load average: the ratio means something
# only when both cores are free (on a busy machine the adaptive default, above, is what counts).
echo; echo "== thread scaling, 2 threads fixed / 1 thread (target >= 1.85; needs two free cores) =="
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
vem_rate() { awk -F'total: ' '/^total: /{split($2, a, ", "); split(a[2], b, " "); r = b[1]} END {print r}'; }
scale() {  # NAME PARSER COMMAND-AT-1 COMMAND-AT-2
  local name=$1 parser=$2 one two
  one=$(eval "$3" 2>&1 | $parser)
  two=$(eval "$4" 2>&1 | $parser)
  awk -v n="$name" -v a="$one" -v b="$two" \
    'BEGIN { if (a > 0 && b > 0) printf "%-22s 1 thread %.3g, 2 threads %.3g particle-steps/s: %.2fx\n", n, a, b, b / a; else printf "%-22s no rate\n", n }'
}
scale "relax" rate "'$BUILD/bench_relax' 1 3000 fixed" "'$BUILD/bench_relax' 2 3000 fixed"
scale "bonded compression" rate "'$BUILD/bench_compress' 1 - 1 500 fixed" "'$BUILD/bench_compress' 2 - 1 500 fixed"
scale "shear" rate "'$BUILD/bench_shear' '$ROOT/examples/shear/data/vem_ns8000_nv2000.xyz' 1 2000 1 fixed" \
  "'$BUILD/bench_shear' '$ROOT/examples/shear/data/vem_ns8000_nv2000.xyz' 2 2000 1 fixed"
scale "VEM (5 void cycles)" vem_rate "'$BUILD/bench_vem' 1 8000 2000 0.4 5 0.2 fixed" \
  "'$BUILD/bench_vem' 2 8000 2000 0.4 5 0.2 fixed"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
# Where the second thread's time goes: perf samples per function at 1 and 2 threads, and what
# one parallel region and one barrier cost (docs/engine.md, "Parallelism").
echo; echo "== thread profile of relax (perf; bench/thread_profile.sh) =="
bash "$ROOT/bench/thread_profile.sh" "$BUILD"

# The other capabilities' benchmarks, each printing its own rates. BENCH_QUICK=1 keeps the
# long end-to-end cases short (rates only).
quick=${BENCH_QUICK:-0}
run() { echo; echo "== $* =="; "$BUILD/$@"; }
run bench_analyze 1
# Micro-benchmarks (Google Benchmark; rates per CPU second): pair kernel of every contact and
# bond law, neighbour build, LS event, shake trial, one engine step. The installed Google
# Benchmark (1.7) takes the minimum time as plain seconds ("0.2s" is for >= 1.8).
run bench_micro --benchmark_min_time=0.2
run bench_neighbor 8000 2000 0.4 200 1   # neighbour-list build, 10,000 particles (VEM stage I)
run bench_neighbor 8000 2000 0.4 200 2
run bench_ls 10000 0.04          # LS to jamming, 10^4 monodisperse (PackingGeneration: 87 s at rate 1e-2)
run bench_ls 10000 0.04 0 1 0.333 1e12 42 0   # the same without the neighbour-list limit (docs/scrm.md)
if [ "$quick" = 1 ]; then
  run bench_ls 10000 3           # fast compression (PackingGeneration: 22.7 s at rate 1e-1)
fi
run bench_ls 10000 0.015 0.6 0.313 0.333   # bimodal case of the paper to c = 0.6
if [ "$quick" = 1 ]; then
  run bench_vem 1 8000 2000 0.4 20          # Fig. 1 case, first 20 void cycles (rates)
else
  # 10^4 and 10^5 monodisperse at G = 3 in one run: CPU time ratio (issue #14: <= 13, N log N),
  # bytes per particle (PackingGeneration: 22.7 s and 555 s at rate 1e-1)
  run bench_ls scaling 10000 100000 3
  run bench_vem 2                           # Fig. 1 case end to end on 2 threads (about 10 minutes here)
fi
# Oscillatory shear: one orientation of the N = 8000 shear case (doh §2.4), contact bonds.
run bench_shear "$ROOT/examples/shear/data/vem_ns8000_nv2000.xyz" 1 $([ "$quick" = 1 ] && echo "2000 2" || echo "10000 10")
# Brownian-dynamics coagulation: 8000 spheres at Phi = 0.4, psi_0 = 15 mV, 2000 steps.
run bench_bd 8000 2000 15
# Inverse opals: FBA + opal builder (~49k particles, pore/particle 10), then compression of a
# ~54,000-particle FCC opal: particle-steps/s, bond-steps/s, bytes per particle and per bond.
run bench_fba 10                   # prints the iterations per phase (contraction, removal at the target)
[ "$quick" = 1 ] || run bench_fba seeds 10000 2 classic   # 10^4 spheres, first version (no momentum)
[ "$quick" = 1 ] || run bench_fba seeds 10000 2           # ... and now: iterations, contacts, g(r)
if [ "$quick" = 1 ]; then run bench_compress 1 - 1 500; else run bench_compress 1; fi
# Issue #14's adaptive rate (docs/opal.md, "Adaptive rate"): the 3,365-particle FCC opal of
# examples/opal/run.sh compressed at the automatic rate and with --elastic-speedup 10, from a
# fresh folder: steps and CPU seconds of each, E and strength against the automatic rate.
if [ "$quick" != 1 ] && [ -x "$BUILD/packlab" ]; then
  echo; echo "== adaptive rate, 3,365-particle FCC opal: automatic rate vs --elastic-speedup 10 =="
  adaptive=$(mktemp -d)
  /usr/bin/python3 "$ROOT/examples/opal/adaptive_rate.py" "$adaptive" "$adaptive/table.csv" --packlab "$BUILD/packlab" \
    --speedups 10 --uncoated-only --workers 1 | grep -v '^+'
  rm -rf "$adaptive"
fi
# The quasi-static solver (docs/static-solver.md): E of the same ~54,000-particle opal from one
# solve, and G' in six orientations of the N = 8000 shear structure.
run bench_static compress 1 - cholmod -1
run bench_static shear 1 "$ROOT/examples/shear/data/vem_ns8000_nv2000.xyz"
# Its PETSc backend (a build with PETSc): MUMPS over 1 and 2 MPI ranks, memory per rank and the
# extrapolation to the paper's 3.4 M particles (scripts/bench-petsc.sh; the docs' data stay).
if grep -qs PACKLAB_HAVE_PETSC "$BUILD/CMakeFiles/packlab_lib.dir/flags.make"; then
  echo; echo "== static solver, PETSc backend (scripts/bench-petsc.sh) =="
  PETSC_BENCH_DATA="$BUILD/bench-petsc" bash "$ROOT/scripts/bench-petsc.sh" "$BUILD" $([ "$quick" = 1 ] && echo "1 2")
fi
