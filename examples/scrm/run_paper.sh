#!/bin/bash
# Reproduces the cases of scrm-bimodal-packs.txt §4 (docs/scrm.md shows the results):
#  1. monodisperse, c = 0.575, 0.6, 0.63: LS (CRM) and SCRM, P realizations of N = 2000 each,
#     averaged RDFs, the drop of the contact value g(2a+) under shaking (paper: 43 %, 21 %, 4 %);
#  2. bimodal, size ratio 0.313, small/large volume ratio 0.333, c = 0.6: partial RDFs g11, g12,
#     g22 for N = 2000 (CRM and SCRM) and N = 7000 (SCRM, M = 3 global shakes);
#  3. the shell count I(r) of a simple cubic lattice for four bin widths;
#  4. fast compression of 10,000 monodisperse spheres to jamming at several growth rates.
# usage: examples/scrm/run_paper.sh [OUT=scrm-paper] [P=8] [JOBS=2]
# Needs `packlab` on PATH (or PACKLAB=path/to/packlab). Takes about an hour on two cores.
set -euo pipefail
OUT=${1:-scrm-paper}
P=${2:-8}
JOBS=${3:-2}
PACKLAB=${PACKLAB:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
export PACKLAB OUT

# LS growth rate of the "CRM" packings (G = ds/dt, docs/scrm.md) and the SCRM schedule:
# shake once every 5 LS blocks during growth, then M = 10 global shakes at c (R_sh = 0.02,
# N_sh = 150: the paper's optimum).
RATE=0.02
run_case() {  # kind c seed extra...
  local kind=$1 c=$2 seed=$3; shift 3
  local dir="$OUT/$kind-c$c/r$seed"
  [ -f "$dir/report.json" ] && return 0
  "$PACKLAB" generate "$@" --phi "$c" --growth-rate "$RATE" --seed "$seed" --out "$dir" --no-plots --quiet
}
export -f run_case
export RATE

jobs=()
for c in 0.575 0.6 0.63; do
  for s in $(seq 1 "$P"); do
    jobs+=("mono-ls $c $s ls --particles 2000")
    jobs+=("mono-scrm $c $s scrm --particles 2000 --final-shakes 10")
  done
done
for s in $(seq 1 "$P"); do
  jobs+=("bi-ls 0.6 $s ls --particles 2000 --sizes 1,0.313 --volume-fractions 0.75,0.25")
  jobs+=("bi-scrm 0.6 $s scrm --particles 2000 --sizes 1,0.313 --volume-fractions 0.75,0.25 --final-shakes 10")
done
for s in 1 2; do
  jobs+=("bi7000-scrm 0.6 $s scrm --particles 7000 --sizes 1,0.313 --volume-fractions 0.75,0.25 --final-shakes 3")
done
printf '%s\n' "${jobs[@]}" | xargs -P "$JOBS" -I{} bash -c 'run_case {}'

# Averaged RDFs (realizations in parallel inside analyze rdf).
for d in "$OUT"/mono-*-c* "$OUT"/bi-*-c* "$OUT"/bi7000-*-c*; do
  [ -f "$d/rdf/report.json" ] && continue
  "$PACKLAB" analyze rdf "$d"/r*/packing.xyz --partial --dr 0.01 --r-max 10 --out "$d/rdf" --quiet
done

# Simple cubic lattice: I(r) for four bin widths (radius 1, lattice spacing 2).
"$PACKLAB" generate lattice --type sc --cells 6 6 6 --radius 1 --out "$OUT/sc.xyz" --quiet
for dr in 0.1 0.01 0.005 0.003; do
  "$PACKLAB" analyze rdf "$OUT/sc.xyz" --dr "$dr" --r-max 5 --out "$OUT/sc-dr$dr" --no-plots --quiet
done

# Fast compression of 10,000 spheres to jamming (reduced pressure 1e12) at several rates.
for g in 0.02 0.04 0.1 0.3 1 3; do
  [ -f "$OUT/jam-G$g/report.json" ] && continue
  "$PACKLAB" generate ls --particles 10000 --growth-rate "$g" --seed 42 --out "$OUT/jam-G$g" --no-plots --quiet
done

/usr/bin/python3 "$HERE/summarize.py" "$OUT"
