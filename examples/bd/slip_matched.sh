#!/usr/bin/env bash
# docs/bd.md "Slip bonds": for each slip force F_s (0: central bonds), the 0 and 15 mV gels
# stopped when their coordination reaches the paper's C (4.52 and 4.97), as the paper-size rows:
# one long run per potential logs 2 (bonds) / N against the time, the time where it crosses the
# paper's C is read off (linear interpolation), then examples/bd/table2_small.sh runs to that
# time and gives a, C and G' (six orientations, static solver, k_n = 100 N/m).
# Writes OUTDIR/$CSV: bond_slip_force_N, then the columns of table2_small.sh.
# usage: examples/bd/slip_matched.sh OUTDIR [PACKLAB]
#   env: N (1000), FORCES ("0 3e-13 1e-12"), D0 (1) and D15 (12): the long runs' durations in
#        a^2/D_0, SEED (1), CSV (bd_slip_matched.csv)
set -euo pipefail
OUT=${1:?usage: slip_matched.sh OUTDIR [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
N=${N:-1000}
SEED=${SEED:-1}
mkdir -p "$OUT"
header=""
rows=""
for force in ${FORCES:-0 3e-13 1e-12}; do
  bonds=$([ "$force" = 0 ] && echo "--central-bonds" || echo "--bond-slip-force $force")
  for mv in 0 15; do
    long="$OUT/fs${force}_long$mv"
    duration=$([ "$mv" = 0 ] && echo "${D0:-1}" || echo "${D15:-12}")
    [ -f "$long/report.json" ] ||
      "$B" generate bd --particles "$N" --phi 0.4 --surface-potential "${mv}e-3" --duration "$duration" $bonds \
        --seed "$SEED" --samples 400 --quiet --no-plots --out "$long"
    # the paper's C (doh-elastic-properties Table 2, BD rows) and the time the log reaches it
    tc=$(PYTHONPATH="$HERE/../../python${PYTHONPATH:+:$PYTHONPATH}" /usr/bin/python3 - "$long/bd_log.csv" "$mv" <<'PY'
import sys
from packlab.plot.bd_table2 import PAPER, crossing_time
target = PAPER[int(sys.argv[2])][1]
t = crossing_time(sys.argv[1], target)
print(target, "none" if t is None else f"{t:.4g}")
PY
)
    target=${tc% *} t=${tc#* }
    if [ "$t" = none ]; then
      echo "F_s = $force N, $mv mV: C stays below $target within $duration a^2/D_0" >&2
      continue
    fi
    d="$OUT/fs${force}_t${mv}_$t"
    N=$N PSI=$mv DURATION=$t SEED=$SEED BONDS="$bonds" "$HERE/table2_small.sh" "$d" "$B" > /dev/null
    header="bond_slip_force_N,$(head -1 "$d/bd_table2_small.csv")"
    rows+="$force,$(tail -1 "$d/bd_table2_small.csv")"$'\n'
  done
done
printf '%s\n%s' "$header" "$rows" > "$OUT/${CSV:-bd_slip_matched.csv}"
cat "$OUT/${CSV:-bd_slip_matched.csv}"
