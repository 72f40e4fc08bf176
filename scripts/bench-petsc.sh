#!/usr/bin/env bash
# The static solver's PETSc backend (MUMPS Cholesky) on growing FCC inverse opals at 1 and 2 MPI
# ranks: times, factor size and every rank's peak resident memory, into
# docs/data/petsc_scaling.csv; then a power-law fit of memory against particles and its
# extrapolation to the paper's 3.4 M particles / 39 M bonds, into docs/data/petsc_extrapolation.txt
# (docs/static-solver.md, "Distributed solve with PETSc").
#   scripts/bench-petsc.sh [BUILD] [TILES...]     (default: build, tiles 1 2 3 4)
# Needs a build with PETSc (bench_static petsc) and mpiexec. One tile of the opal_case.hpp box is
# about 3,400 opal particles; 4 x 4 tiles is the 54k opal of docs/opal.md.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
shift || true
TILES=("$@")
[ ${#TILES[@]} -eq 0 ] && TILES=(1 2 3 4)
WORK=$BUILD/bench-petsc
mkdir -p "$WORK" docs/data
export OMP_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# The benchmark's force-biased packing (15 nm particles, porosity 0.38, periodic x, y).
if [ ! -f "$WORK/fba/packing.xyz" ]; then
  "$BUILD/packlab" generate fba --box 300e-9,259.81e-9,412.95e-9 --diameter 15e-9 --porosity 0.38 --periodic xy \
    --seed 2 --no-plots --quiet --out "$WORK/fba"
fi
CSV=docs/data/petsc_scaling.csv
echo "# scripts/bench-petsc.sh: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores, $(free -g | awk '/Mem:/{print $2}') GiB; MUMPS Cholesky (PETSc $(pkg-config --modversion PETSc 2>/dev/null || echo '?')), OMP_NUM_THREADS=1" > "$CSV.tmp"
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
/usr/bin/python3 - "$CSV" docs/data/petsc_extrapolation.txt <<'EOF'
# Power laws y = a N^b (least squares in log-log) of the factor's entries, the largest rank's
# and all ranks' peak resident memory at 2 ranks, and rank 0's excess over rank 1 (what rank 0
# holds alone: the model, the links, the assembled matrix), against particles; evaluated at the
# paper's 3.4 M particles (39 M bonds: the bonds per particle of these opals are ~5.6, the
# paper's ~11.5, so the memory per particle is scaled by the bonds too, see below).
import csv, math, sys
rows = [r for r in csv.DictReader(line for line in open(sys.argv[1]) if not line.startswith("#"))]
two = [r for r in rows if r["ranks"] == "2"]
def fit(xs, ys):
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    n = len(lx); mx, my = sum(lx) / n, sum(ly) / n
    b = sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sum((x - mx) ** 2 for x in lx)
    return math.exp(my - b * mx), b
N = [float(r["particles"]) for r in two]
bonds = [float(r["bonds"]) for r in two]
rss = [[float(v) for v in r["rss_mib_per_rank"].split(",")] for r in two]
factor = [float(r["factor_nnz"]) for r in two]
out = []
say = out.append
target_n, target_bonds = 3.4e6, 39e6
say("# scripts/bench-petsc.sh from docs/data/petsc_scaling.csv (2-rank rows): y = a N^b, N = particles")
for name, ys in [("factor entries", factor), ("peak RSS rank 0 [MiB]", [r[0] for r in rss]),
                 ("peak RSS rank 1 [MiB]", [r[1] for r in rss]), ("peak RSS both ranks [MiB]", [sum(r) for r in rss])]:
    a, b = fit(N, ys)
    say(f"{name}: a = {a:.4g}, b = {b:.3f}; at N = 3.4e6: {a * target_n ** b:.4g}")
a_f, b_f = fit(N, factor)
bonds_per_particle = sum(bonds) / sum(N)
# The factor's fill follows the graph: per particle it scales with the coupling per particle; the
# paper's model has target_bonds / target_n bonds per particle against these opals' ratio.
scale = (target_bonds / target_n) / bonds_per_particle
factor_target = a_f * target_n ** b_f * scale
a0, b0 = fit(N, [max(r[0] - r[1], 1.0) for r in rss])
a1, b1 = fit(N, [r[1] for r in rss])
rank0_alone = a0 * target_n ** b0 * scale / 1024  # GiB
# Bytes per factor entry measured: MUMPS's working memory over its entries (rank 1 holds only factor work).
bytes_per_entry = max(r[1] * 1048576 / (f / 2) for r, f in zip(rss, factor))
factor_gib = factor_target * bytes_per_entry / 1024**3
node_gib = 24 * 0.85  # usable of a 24 GiB node (system, MPI buffers)
nodes = math.ceil((factor_gib + rank0_alone) / node_gib)
say(f"bonds per particle here {bonds_per_particle:.2f}, paper {target_bonds / target_n:.2f}: x{scale:.2f} on fill and per-particle memory")
say(f"factor entries at 3.4 M particles / 39 M bonds: {factor_target:.3g}; at {bytes_per_entry:.1f} B per entry "
    f"(measured, rank 1's peak over its half of the factor): {factor_gib:.0f} GiB in all")
say(f"rank 0 alone (model, links, assembled matrix; rank 0 - rank 1 peak, fitted b = {b0:.2f}): {rank0_alone:.1f} GiB")
say(f"nodes of 24 GiB / 2 cores (85 % usable, 2 ranks each): {nodes} (factor spread evenly; rank 0's node also holds the model)")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("\n".join(out))
EOF
