#!/usr/bin/env bash
# The static solver's PETSc backend (MUMPS Cholesky) on growing FCC inverse opals at 1 and 2 MPI
# ranks: times, factor size and every rank's peak resident memory, into
# docs/data/petsc_scaling.csv; then a power-law fit of memory against particles and its
# extrapolation to the paper's 3.4 M particles / 39 M bonds, into docs/data/petsc_extrapolation.txt
# (docs/static-solver.md, "Distributed solve with PETSc").
#   scripts/bench-petsc.sh [BUILD] [TILES...]     (default: build, tiles 1 2 3 4)
# PETSC_BENCH_DATA=DIR writes the two files there instead of docs/data (make bench does).
# Needs a build with PETSc (bench_static petsc) and mpiexec. One tile of the opal_case.hpp box is
# about 3,400 opal particles; 4 x 4 tiles is the 54k opal of docs/opal.md.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
shift || true
TILES=("$@")
[ ${#TILES[@]} -eq 0 ] && TILES=(1 2 3 4)
WORK=$BUILD/bench-petsc
DATA=${PETSC_BENCH_DATA:-docs/data}
mkdir -p "$WORK" "$DATA"
export OMP_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# The benchmark's force-biased packing (15 nm particles, porosity 0.38, periodic x, y).
if [ ! -f "$WORK/fba/packing.xyz" ]; then
  "$BUILD/packlab" generate fba --box 300e-9,259.81e-9,412.95e-9 --diameter 15e-9 --porosity 0.38 --periodic xy \
    --seed 2 --no-plots --quiet --out "$WORK/fba"
fi
CSV=$DATA/petsc_scaling.csv
echo "# scripts/bench-petsc.sh: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc --all) cores, $(free -g | awk '/Mem:/{print $2}') GiB, load average $(cut -d" " -f1 /proc/loadavg) at the start (a machine shared with other builds); MUMPS Cholesky (PETSc $(pkg-config --modversion PETSc 2>/dev/null || echo '?')), OMP_NUM_THREADS=1" > "$CSV.tmp"
echo "tiles,particles,bonds,ranks,unknowns,matrix_nnz,factor_nnz,factor_s,solve_s,wall_s,youngs_modulus,rss_mib_per_rank" >> "$CSV.tmp"
for t in "${TILES[@]}"; do
  model=$WORK/opal_t$t.vtu
  [ -f "$model" ] || "$BUILD/bench_static" model "$t" "$WORK/fba/packing.xyz" "$model" > /dev/null
  for np in 1 2; do
    line=$(mpiexec -n "$np" "$BUILD/bench_static" petsc "$model" 1 | grep '^packlab static petsc')
    echo "$line" >&2
    # key=value pairs of the last line into the CSV row.
    /usr/bin/python3 - "$t" "$line" >> "$CSV.tmp" <<'EOF'
import sys
kv = dict(item.split("=", 1) for item in sys.argv[2].split()[3:])
print(",".join([sys.argv[1], kv["N"], kv["bonds"], kv["ranks"], kv["unknowns"], kv["matrix_nnz"], kv["factor_nnz"],
                kv["factor_s"], kv["solve_s"], kv["wall_s"], kv["E"], '"' + kv["rss_mib"] + '"']))
EOF
  done
done
mv "$CSV.tmp" "$CSV"
/usr/bin/python3 - "$CSV" "$DATA/petsc_extrapolation.txt" <<'EOF'
# From the 2-rank rows: the factor's entries against particles (power law, least squares in
# log-log, and the 4/3 law of nested dissection on a 3D graph from the largest model); MUMPS's
# memory per factor entry (rank 1 holds only its part of the factor: the slope of its peak
# resident memory against half the entries); what rank 0 holds alone (its peak minus rank 1's:
# the model, the links, the assembled matrix) per bond. Evaluated at the paper's 3.4 M particles
# and 39 M bonds, and as nodes of 24 GiB and 2 cores (2 ranks each, 85 % of the memory usable).
import csv, math, sys
rows = [r for r in csv.DictReader(line for line in open(sys.argv[1]) if not line.startswith("#"))]
two = [r for r in rows if r["ranks"] == "2"]
N = [float(r["particles"]) for r in two]
bonds = [float(r["bonds"]) for r in two]
entries = [float(r["factor_nnz"]) for r in two]
rss = [[float(v) * 1048576 for v in r["rss_mib_per_rank"].split(",")] for r in two]
def line(xs, ys):
    n = len(xs); mx, my = sum(xs) / n, sum(ys) / n
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return my - b * mx, b
la, b_fit = line([math.log(x) for x in N], [math.log(y) for y in entries])
_, bytes_per_entry = line([e / 2 for e in entries], [r[1] for r in rss])
_, rank0_per_bond = line(bonds, [r[0] - r[1] for r in rss])
Nt, Bt, GiB = 3.4e6, 39e6, 1024.0**3
usable = 24 * 0.85
out = ["# scripts/bench-petsc.sh from docs/data/petsc_scaling.csv (2-rank rows)",
       f"factor entries ~ N^{b_fit:.3f} (fit over N = {N[0]:.0f}..{N[-1]:.0f}); MUMPS memory {bytes_per_entry:.1f} B per "
       f"factor entry (slope of rank 1's peak); rank 0 alone {rank0_per_bond:.0f} B per bond (slope of rank 0 - rank 1 peak)",
       f"bonds per particle: these opals {sum(bonds) / sum(N):.2f}, the paper's model {Bt / Nt:.2f}"]
rank0 = rank0_per_bond * Bt / GiB
for label, e in [("fitted exponent", math.exp(la) * Nt**b_fit),
                 ("4/3 law from the largest model", entries[-1] * (Nt / N[-1]) ** (4 / 3)),
                 ("4/3 law, fill x bonds-per-particle ratio",
                  entries[-1] * (Nt / N[-1]) ** (4 / 3) * (Bt / Nt) / (bonds[-1] / N[-1]))]:
    factor = e * bytes_per_entry / GiB
    nodes = math.ceil((factor + rank0) / usable)
    out.append(f"at 3.4 M particles / 39 M bonds, {label}: {e:.3g} factor entries, factor {factor:.0f} GiB + rank 0 "
               f"alone {rank0:.1f} GiB = {factor + rank0:.0f} GiB: {nodes} nodes of 24 GiB ({2 * nodes} ranks)")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("\n".join(out))
EOF
