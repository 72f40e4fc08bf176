#!/usr/bin/env bash
# docs/bd.md "Slip bonds": BD gels whose bonds resist rolling up to a tangential force F_s
# (--bond-slip-force), for psi_0 = 0 and 15 mV and several F_s: a, C and G' (six orientations,
# static solver, k_n = 100 N/m) of each, as examples/bd/time_series.sh does for central bonds.
# Writes OUTDIR/$CSV with a first column bond_slip_force_N (copied to docs/data/ by hand).
# usage: examples/bd/slip_scan.sh OUTDIR [PACKLAB]
#   env: N (1000), FORCES ("1e-12 3e-12 1e-11": F_s in N), T0 ("2": the time at 0 mV in
#        a^2/D_0), T15 ("6"), SEEDS ("1"), THREADS (1), CSV (bd_slip_scan.csv)
set -euo pipefail
OUT=${1:?usage: slip_scan.sh OUTDIR [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
FORCES=${FORCES:-"1e-12 3e-12 1e-11"}
csv="$OUT/${CSV:-bd_slip_scan.csv}"
mkdir -p "$OUT"
header=""
rows=""
for force in $FORCES; do
  d="$OUT/fs$force"
  N=${N:-1000} T0=${T0:-2} T15=${T15:-6} PSI="0 15" SEEDS=${SEEDS:-1} THREADS=${THREADS:-1} \
    BONDS="--bond-slip-force $force" CSV=scan.csv "$HERE/time_series.sh" "$d" "$B" > /dev/null
  header="bond_slip_force_N,$(head -1 "$d/scan.csv")"
  while IFS= read -r line; do
    [ -n "$line" ] && rows+="$force,$line"$'\n'
  done < <(tail -n +2 "$d/scan.csv")
done
printf '%s\n%s' "$header" "$rows" > "$csv"
cat "$csv"
