#!/usr/bin/env bash
# bench/targets.sh reads issue #14's figures back from a bench log: a log with known lines (the
# formats the benchmarks print) must give those figures and verdicts, an empty one "not measured".
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
cat > "$TMP/log" <<'LOG'
ratio packlab/LAMMPS (1 core): 2.61  (9.5e+06 vs 3.65e+06 particle-steps/s)
lammps relax memory N=8000 mbytes=10.69 bytes_per_particle=1401
loaded machine, particle-steps/s: 1 thread 4.1e+06, 2 threads fixed 3e+06 (0.73x), 2 threads adaptive 4.3e+06 (1.05x; target >= 1)
relax                  1 thread 4.4e+06, 2 threads 6.3e+06 particle-steps/s: 1.43x
bonded compression     1 thread 1.6e+06, 2 threads 3e+06 particle-steps/s: 1.88x
shear                  no rate
packlab relax N=8000 steps=20000 wall_s=32.472 pts_per_s=4.927e+06 bytes_per_particle=367
packlab relax N=8000 steps=3000 wall_s=3 pts_per_s=8e+06 bytes_per_particle=150
bench_vem N_S=8000 N_V=2000 phi_s=0.4 threads=2 (adaptive) skin=0.2 time_step_rule=stiffness_sum safety=0.8
expansion: 294 cycles, 668849 steps in 563.53 s, 1.187e+07 particle-steps/s, 2275 steps/cycle, 1.917 s/cycle, last q 1.475, 5 relaxations at the step limit, stop stage_three
total: 607.93 s, 1.214e+07 particle-steps/s
packlab static compress N=53820 bonds=302217 threads=1 backend=cholmod breaks=30 wall_s=146.97 solver_bytes_per_bond=3325
fba_summary schedule=momentum_0 N=10000 seeds=4 iterations_mean=17336 removal_iterations_mean=17300 max_verified_overlap=0.001
fba_summary schedule=momentum_0.9 N=10000 seeds=4 iterations_mean=1240 removal_iterations_mean=1204 max_verified_overlap=0.0009999
packlab ls N=10000 rate=0.04 phi=0.63878 bytes_per_particle=183 peak_bytes_per_particle=214 peak_rss_per_particle=812 list_limit=12
packlab ls N=10000 rate=0.04 phi=0.63810 bytes_per_particle=183 peak_bytes_per_particle=301 peak_rss_per_particle=812 list_limit=0
packlab ls N=10000 rate=3 phi=0.60719 bytes_per_particle=179 peak_bytes_per_particle=195 peak_rss_per_particle=793
packlab ls N=100000 rate=3 phi=0.60290 bytes_per_particle=179 peak_bytes_per_particle=191 peak_rss_per_particle=427
packlab ls scaling N1=10000 N2=100000 rate=3 cpu_s=3.97,79.86 cpu_ratio=20.13 n_ratio=10.00 events_ratio=12.13 cpu_per_event_ratio=1.66
packlab compress N=53820 bonds=302217 threads=1 pts_per_s=1e6 bond_steps_per_s=5e6 bytes_per_particle=300 bytes_per_bond=98
LOG
out=$(bash "$ROOT/bench/targets.sh" "$TMP/log")
echo "$out"
expect() {  # ROW-START TEXT: the row that starts with ROW-START contains TEXT
  local line
  line=$(echo "$out" | grep -F "| $1" | head -1)
  [[ "$line" == *"$2"* ]] || { echo "FAIL: row '$1' lacks '$2': $line"; exit 1; }
}
expect "relax, 1 core, packlab / LAMMPS" "2.61 (9.5e+06 vs 3.65e+06"
expect "relax, 1 core, packlab / LAMMPS" "| met"
expect "2 threads / 1 thread: relax" "1.43x"
expect "2 threads / 1 thread: relax" "NOT met"
expect "2 threads / 1 thread: bonded compression" "| met"
expect "2 threads / 1 thread: shear" "not measured"
expect "2 threads / 1 thread: VEM" "not measured"
expect "2 threads (adaptive)" "1.05x"
expect "2 threads (adaptive)" "| met"
expect "VEM Fig. 1 case" "607.93 s, 294 cycles, stage_three"
expect "VEM Fig. 1 case" "NOT met"
expect "54k FCC opal" "146.97 s, N = 53820, 30 breaks"
expect "54k FCC opal" "| met"
expect "FBA 10^4" "14.0x (17336 -> 1240)"
expect "FBA 10^4" "| met"
expect "LS to jamming" "20.13x (events 12.13x, per event 1.66x)"
expect "LS to jamming" "NOT met"
expect "engine memory per particle" "367 B (LAMMPS 1401 B: 0.26 of it)"
expect "engine memory per particle" "NOT met"
expect "engine memory per bond" "98 B (300 B per particle, N = 53820)"
expect "engine memory per bond" "| met"
expect "LS memory per particle" "214 B (N = 10000, rate 0.04; every run: 214, 195, 191; without the list limit: 301)"
expect "LS memory per particle" "NOT met"
# make bench solves the 54k opal for E alone: no verdict on the run to the peak.
sed -i 's/breaks=30 wall_s=146.97/breaks=0 wall_s=7.04/' "$TMP/log"
out=$(bash "$ROOT/bench/targets.sh" "$TMP/log")
expect "54k FCC opal" "- (E alone: 7.04 s, N = 53820)"
expect "54k FCC opal" "not measured"
: > "$TMP/empty"
out=$(bash "$ROOT/bench/targets.sh" "$TMP/empty")
expect "relax, 1 core" "not measured"
expect "engine memory per particle" "not measured"
if bash "$ROOT/bench/targets.sh" "$TMP/absent" 2>/dev/null; then echo "FAIL: a missing log was accepted"; exit 1; fi
echo "targets.sh: all rows as expected"
