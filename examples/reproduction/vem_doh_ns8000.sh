#!/usr/bin/env bash
# VEM at the paper's size for both papers (docs/reproduction.md): N_S = 8000, Phi_S = 0.4, the
# DOH paper's N_V = 1000 ... 16000 (n = 0.125 ... 2), Table 1 of the VEM paper, one thread per
# run, max_q 2.2 -- the runs of docs/shear.md's "Table 2 at the paper's size", now per seed and
# with two end points per run:
#   stage3   the structure where stage III stops the default run (strain energy 1e-3)
#   cmatched the first structure whose CN reaches the paper's C of that N_V (Table 2, as in
#            packlab.reproduction); the loose structures reach it only after stage III, so the
#            run goes on until both hold (stop.min_coordination), which leaves the curve up to
#            stage III, and so q_i, the slope and beta, as the default run's
# Each run keeps a snapshot per cycle until both end points are taken out (then they are
# deleted). Each end point is analysed (a and C: eq. 6, eps 0.01), bonded (contact bonds at
# (1 + 0.01) 2 r), relaxed (§2.2) and tested in six orientations by the quasi-static solver
# (examples/shear/table2_small.toml). examples/reproduction/vem_doh_tables.py OUT collects the
# runs into docs/data/vem_doh_ns8000.csv.
# Resumable: a step whose output exists is skipped; a killed VEM run goes on from its checkpoint.
# usage: examples/reproduction/vem_doh_ns8000.sh OUT [PACKLAB] [SEEDS] [N_V...]
#   SEEDS: a list like "1 2 3" (default); N_V: default 16000 13000 8000 4000 2000 1000 400 (400 is
#   the VEM paper's smallest, n = 0.05, run with max_q 3; its C is not in Table 2: 4.69 is used).
#   NS=... sets another N_S (tests of the script only); VEM_OPTIONS="..." adds options to the VEM
#   runs (variations such as Table 1's other structural stiffness, docs/reproduction.md).
#   Cost on one core: VEM 9-30 min per run, the two tests 2-3 min; run two copies with different
#   SEEDS or N_V lists on two cores.
set -euo pipefail
OUT=${1:?usage: vem_doh_ns8000.sh OUT [PACKLAB] [SEEDS] [N_V...]}
B=${2:-packlab}
SEEDS=${3:-1 2 3}
shift $(( $# > 3 ? 3 : $# )) || true
NVS=${*:-16000 13000 8000 4000 2000 1000 400}
HERE=$(cd "$(dirname "$0")" && pwd)
SHEAR_CFG="$HERE/../shear/table2_small.toml"
PY=${PYTHON:-python3}

# The paper's C per N_V (doh-elastic-properties Table 2, VEM rows: packlab.reproduction's
# DOH_TABLE2_VEM); 4.69 for an N_V the table does not list.
paper_c() {
  PYTHONPATH="$HERE/../../python${PYTHONPATH:+:$PYTHONPATH}" "$PY" -c \
    'import sys; from packlab.reproduction import DOH_TABLE2_VEM as t; print(t.get(int(sys.argv[1]), (0, 4.69))[1])' "$1"
}

# timed NAME DIR CMD...: CMD with its wall and CPU seconds in DIR/NAME.time ("wall user system")
timed() {
  local name=$1 dir=$2
  shift 2
  /usr/bin/time -f "%e %U %S" -o "$dir/$name.time" "$@"
}

for seed in $SEEDS; do
  for nv in $NVS; do
    d="$OUT/seed$seed/nv$(printf %05d "$nv")"
    mkdir -p "$d"
    c=$(paper_c "$nv")
    maxq=2.2
    [ "$nv" -lt 1000 ] && maxq=3.0  # the VEM paper's N_V = 400 (n = 0.05) has q_i near 2.2
    if [ ! -f "$d/vem/report.json" ]; then
      if [ -f "$d/vem/checkpoint.bin" ]; then
        timed vem_resume "$d" "$B" generate vem --resume "$d/vem" --threads 1 --quiet
      else
        timed vem "$d" "$B" generate vem --structural "${NS:-8000}" --voids "$nv" --phi-s 0.4 --seed "$seed" \
          --threads 1 --max-q "$maxq" --stop-min-coordination "$c" --snapshot-every 1 --no-plots --quiet \
          ${VEM_OPTIONS:-} --out "$d/vem"
      fi
    fi
    # The two end points out of the snapshots (the snapshot of a cycle is the row of that cycle).
    if [ ! -f "$d/stage3.xyz" ] || [ ! -f "$d/cmatched.xyz" ]; then
      "$PY" - "$d" "$c" <<'PY'
import csv, json, os, shutil, sys
d, target = sys.argv[1], float(sys.argv[2])
r = json.load(open(os.path.join(d, "vem", "report.json")))
p = r["parameters"]
scale = r["structural"] * p["structural_material"]["normal_stiffness_N_per_m"] * p["radius_m"] ** 2
rows = list(csv.DictReader(l for l in open(os.path.join(d, "vem", "cn_curve.csv")) if not l.startswith("#")))
stage3 = next(int(x["cycle"]) for x in rows if float(x["strain_energy"]) / scale >= p["stop"]["strain_energy"])
cmatched = next(int(x["cycle"]) for x in rows if float(x["cn"]) >= target)
for name, cycle in (("stage3", stage3), ("cmatched", cmatched)):
    src = os.path.join(d, "vem", "snapshots", f"cycle_{cycle:05d}.xyz")
    shutil.copyfile(src, os.path.join(d, name + ".xyz.tmp"))
    os.replace(os.path.join(d, name + ".xyz.tmp"), os.path.join(d, name + ".xyz"))
json.dump({"stage3_cycle": stage3, "cmatched_cycle": cmatched, "target_coordination": target},
          open(os.path.join(d, "ends.json"), "w"))
PY
    fi
    rm -rf "$d/vem/snapshots"
    for end in stage3 cmatched; do
      e="$d/$end"
      mkdir -p "$e"
      [ -f "$e/doh/report.json" ] ||
        timed analyze "$e" "$B" analyze "$d/$end.xyz" --what cn,doh --threads 1 --quiet --no-plots --out "$e/doh"
      [ -f "$e/bonded.vtu" ] ||
        timed bond "$e" "$B" bond "$d/$end.xyz" --model contact --eps 0.01 --threads 1 --out "$e/bonded.vtu" --quiet
      slow=()
      [ "$nv" -ge 13000 ] && slow=(--relax-max-steps 100000)
      [ -f "$e/shear/report.json" ] ||
        timed shear "$e" "$B" test shear "$e/bonded.vtu" --config "$SHEAR_CFG" --solver static \
          --threads 1 "${slow[@]}" --no-plots --quiet --out "$e/shear"
    done
    echo "$(date +%T) done seed $seed N_V $nv"
  done
done
