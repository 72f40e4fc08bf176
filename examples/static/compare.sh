#!/usr/bin/env bash
# The data of docs/static-solver.md: the static solver against the dynamic tests on small
# disordered models (bench_static compare), and its benchmark on the papers' large cases
# (bench_static compress / shear). About 8 minutes.
#   examples/static/compare.sh [BUILD] [OUT]      # BUILD: the build folder (default build)
#   then: cp OUT/static_*.{csv,txt} docs/data/
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
BUILD=${1:-$ROOT/build}
OUT=${2:-$ROOT/docs/data}
mkdir -p "$OUT"
"$BUILD/bench_static" compare "$OUT/static_vs_dynamic.csv"
{
  echo "# bench_static compress 1 - cholmod -1   (E of the ~54,000-particle FCC opal, one thread)"
  "$BUILD/bench_static" compress 1 - cholmod -1
  echo "# bench_static compress 2 - cholmod -1   (the same on two threads)"
  "$BUILD/bench_static" compress 2 - cholmod -1
  echo "# bench_static shear 1 examples/shear/data/vem_ns8000_nv2000.xyz   (G', six orientations)"
  "$BUILD/bench_static" shear 1 "$ROOT/examples/shear/data/vem_ns8000_nv2000.xyz"
  echo "# bench_static shear 1 examples/shear/data/vem_ns8000_nv2000.xyz eigen   (Eigen's simplicial Cholesky)"
  "$BUILD/bench_static" shear 1 "$ROOT/examples/shear/data/vem_ns8000_nv2000.xyz" eigen
} 2>&1 | tee "$OUT/static_bench.txt"
