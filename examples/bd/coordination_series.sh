#!/usr/bin/env bash
# docs/bd.md "Paper size": the mean coordination 2 (bonds) / N of the N = 8000 central-bond gels
# against the time simulated, for every potential of Table 2 (seed 1, one run each, from its
# log bd_log.csv), and the time at which it reaches the paper's C (linear interpolation between
# log rows): the times examples/bd/time_series.sh then runs with three seeds (the quench at the
# end of a run changes C by <= 0.01 at these times).
# Writes OUTDIR/bd_coordination_ns8000.csv (t, C per potential) and OUTDIR/bd_c_matched_times.csv.
# usage: examples/bd/coordination_series.sh OUTDIR [PACKLAB]
#   env: N (8000), THREADS (1); the run of potential m is OUTDIR/c<m> (kept: an existing run is
#   not repeated). Durations and log rows: 0 mV 1 (200), 12 mV 0.5 (250), 13 mV 1.5 (300),
#   14 mV 3 (300), 15 mV 6 (200) a^2/D_0; about 45 min of one core.
set -euo pipefail
OUT=${1:?usage: coordination_series.sh OUTDIR [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
run() {  # mV duration samples
  [ -f "$OUT/c$1/report.json" ] ||
    "$B" generate bd --particles "${N:-8000}" --phi 0.4 --surface-potential "$1e-3" --duration "$2" --central-bonds \
      --seed 1 --samples "$3" --threads "${THREADS:-1}" --quiet --no-plots --out "$OUT/c$1"
}
run 0 1 200
run 12 0.5 250
run 13 1.5 300
run 14 3 300
run 15 6 200
PYTHONPATH="$HERE/../../python${PYTHONPATH:+:$PYTHONPATH}" /usr/bin/python3 - "$OUT" <<'PY'
import sys
from packlab.plot.bd_table2 import PAPER, crossing_time, read_coordination_log
out = sys.argv[1]
with open(f"{out}/bd_coordination_ns8000.csv", "w") as series, open(f"{out}/bd_c_matched_times.csv", "w") as times:
    series.write("surface_potential_mV,time_diffusion_times,mean_coordination_bonds\n")
    times.write("surface_potential_mV,paper_C,time_diffusion_times\n")
    for mv, (_, target, _, _) in PAPER.items():  # the paper's C
        log = read_coordination_log(f"{out}/c{mv}/bd_log.csv")
        for t, c in log:
            series.write(f"{mv},{t:g},{c:g}\n")
        crossing = crossing_time(log, target)
        times.write(f"{mv},{target},{float('nan') if crossing is None else crossing:.4g}\n")
print(open(f"{out}/bd_c_matched_times.csv").read())
PY
