#!/usr/bin/env bash
# Table 2 / Fig. 6 at the paper's size (docs/shear.md, "Table 2 at the paper's size"): VEM
# structures with N_S = 8000 at the paper's ratios n = N_V / N_S = 0.125, 0.25, 0.5, 1, 1.625, 2
# (N_V = 1000 ... 16000), Phi_S = 0.4, seed 1, the VEM options of table2_study.sh (threads 1,
# max_q 2.2); a and C (eq. 6, contact eps 0.01); contact bonds at (1 + 0.01) 2r; the shear test
# with examples/shear/table2_small.toml and the quasi-static solver (--solver static: one linear
# solve per orientation, six orientations) after the dynamic §2.2 relaxation; G' against a with
# the fit of eq. 7. The n = 0.25 structure is examples/shear/data/vem_ns8000_nv2000.xyz (same
# N_S, N_V, Phi_S, seed; it stopped at stage III, q = 1.475, before max_q), set
# REGENERATE_NV2000=1 to make it anew. Also checks n = 0.25, z:x with the relaxation run to its
# criterion against the dynamic value of docs/shear.md (2.765 MPa, bench_shear).
# Resumable: a step whose output exists is skipped (an interrupted VEM run goes on from its
# checkpoint); OUTDIR/table2.csv is rebuilt from the finished structures at every call.
# usage: [PYTHON=/usr/bin/python3] examples/shear/table2_ns8000.sh OUTDIR [PACKLAB]
#   (PYTHON: a Python 3 with numpy and matplotlib, for the eq. 7 fit and the figure)
#   (about 80 min of one core: VEM 8-20 min per structure, the relaxations 1-5 min, the solves s)
set -euo pipefail
OUT=${1:?usage: table2_ns8000.sh OUTDIR [PACKLAB]}
B=${2:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$HERE/../../python${PYTHONPATH:+:$PYTHONPATH}"  # packlab.plot (needs numpy, matplotlib)
PY=${PYTHON:-python3}
mkdir -p "$OUT"

# run NAME DIR CMD...: CMD with its wall and CPU seconds in DIR/NAME.time ("wall user system")
run() {
  local name=$1 dir=$2
  shift 2
  if command -v /usr/bin/time >/dev/null; then
    /usr/bin/time -f "%e %U %S" -o "$dir/$name.time" "$@"
  else
    local t0 t1
    t0=$(date +%s.%N)
    "$@"
    t1=$(date +%s.%N)
    echo "$(echo "$t1 - $t0" | bc) nan nan" > "$dir/$name.time"
  fi
}

# The longest VEM run (n = 2) first, then the reused n = 0.25 structure and the others from the
# cheapest up, so that a run cut short still spans the range of a; n = 1.625 (a close to n = 2's)
# last.
for nv in 16000 2000 1000 4000 8000 13000; do
  name=$(printf "nv%05d" "$nv")
  d="$OUT/$name"
  mkdir -p "$d/vem"
  if [ ! -f "$d/vem/packing.xyz" ]; then
    if [ "$nv" -eq 2000 ] && [ "${REGENERATE_NV2000:-0}" != 1 ]; then
      cp "$HERE/data/vem_ns8000_nv2000.xyz" "$d/vem/packing.xyz"
    else
      if [ -f "$d/vem/checkpoint.bin" ]; then  # an interrupted run (vem.time then times the rest only)
        run vem "$d" "$B" generate vem --resume "$d/vem" --threads 1 --quiet
      else
        run vem "$d" "$B" generate vem --structural 8000 --voids "$nv" --phi-s 0.4 --seed 1 --threads 1 \
          --max-q 2.2 --no-plots --quiet --out "$d/vem"
      fi
    fi
  fi
  [ -f "$d/doh/report.json" ] ||
    run analyze "$d" "$B" analyze "$d/vem/packing.xyz" --what cn,doh --threads 1 --quiet --no-plots --out "$d/doh"
  [ -f "$d/bonded.vtu" ] ||
    run bond "$d" "$B" bond "$d/vem/packing.xyz" --model contact --eps 0.01 --threads 1 --out "$d/bonded.vtu" --quiet
  # The loose structures are relaxed to the criterion, as in table2_study.sh (there with slower
  # cycles as well; the static solver has no cycles).
  slow=()
  [ "$nv" -ge 13000 ] && slow=(--relax-max-steps 100000)
  [ -f "$d/shear/report.json" ] ||
    run shear "$d" "$B" test shear "$d/bonded.vtu" --config "$HERE/table2_small.toml" --solver static \
      --threads 1 "${slow[@]}" --no-plots --quiet --out "$d/shear"
  if [ "$nv" -eq 2000 ]; then
    # n = 0.25, z:x, relaxed to the criterion as the dynamic benchmark (bench_shear) was.
    c="$OUT/check_nv02000_zx"
    mkdir -p "$c"
    [ -f "$c/shear/report.json" ] ||
      run shear "$c" "$B" test shear "$d/bonded.vtu" --config "$HERE/table2_small.toml" --solver static \
        --orientations z:x --relax-max-steps 100000 --threads 1 --no-plots --quiet --out "$c/shear"
  fi
done

"$PY" - "$OUT" <<'PY'
import json, os, sys
out = sys.argv[1]
orients = ["x:y", "x:z", "y:x", "y:z", "z:x", "z:y"]
cols = ("name,n,voids,a,a_err,coordination,storage_modulus,std,phase_angle,"
        + ",".join("storage_modulus_" + o.replace(":", "") for o in orients)
        + ",plate_storage_modulus,max_bond_shear_over_strength,broken_bonds,bonds,relax_steps,relax_converged,"
          "relax_final_force,structure,vem_q_end,vem_steps,vem_seconds,vem_cpu_seconds,analyze_seconds,bond_seconds,"
          "relax_seconds,solve_seconds,shear_seconds,shear_wall_seconds,shear_cpu_seconds")

def times(d, step):
    f = f"{d}/{step}.time"
    if not os.path.exists(f):
        return ["", "", ""]
    w, u, s = open(f).read().split()[:3]
    return [w, u, s]

rows = []
for nv in [1000, 2000, 4000, 8000, 13000, 16000]:
    name = f"nv{nv:05d}"
    d = f"{out}/{name}"
    if not os.path.exists(f"{d}/shear/report.json"):
        print(f"missing: {name}", file=sys.stderr)
        continue
    doh = json.load(open(f"{d}/doh/report.json"))
    s = json.load(open(f"{d}/shear/report.json"))
    g = s["storage_modulus"]
    per = {r["orientation"]: r for r in g["per_orientation"]}
    solve = sum(r["seconds"] for r in g["per_orientation"])
    vrep = f"{d}/vem/report.json"
    if os.path.exists(vrep):
        v = json.load(open(vrep))
        structure, q_end, vsteps, vsec = "generated", v["q_end"], v["steps"], v["seconds"]
    else:
        head = open(f"{d}/vem/packing.xyz").readlines()[1]  # the reused file: q_end in its comment
        q_end = head.split("q_end=")[1].split()[0].strip('"') if "q_end=" in head else ""
        structure, vsteps, vsec = "examples/shear/data/vem_ns8000_nv2000.xyz", "", ""
    vt, sh = times(d, "vem"), times(d, "shear")
    cpu = lambda t: f"{float(t[1]) + float(t[2]):.1f}" if t[1] not in ("", "nan") else ""
    row = [name, nv / 8000, nv, doh["doh"]["a"], doh["doh"]["a_err"], doh["mean_coordination"],
           g["mean"], g["std"], s["phase_angle"]] + [per[o]["storage_modulus"] for o in orients] + [
           s["plate_storage_modulus_mean"], s["bonds"]["max_shear_force_over_strength"],
           s["bonds"]["broken_during_loading"], per["z:x"]["bonds"], s["relaxation"]["steps"],
           s["relaxation"]["converged"], s["relaxation"]["final_mean_unbalanced_force"], structure, q_end, vsteps,
           vsec, cpu(vt), times(d, "analyze")[0], times(d, "bond")[0], f"{s['seconds'] - solve:.1f}",
           f"{solve:.2f}", f"{s['seconds']:.1f}", sh[0], cpu(sh)]
    rows.append(",".join(str(x) for x in row))
with open(f"{out}/table2.csv", "w") as f:
    f.write(cols + "\n" + "".join(r + "\n" for r in rows))

ck = f"{out}/check_nv02000_zx/shear/report.json"
if os.path.exists(ck):
    s = json.load(open(ck))
    r = s["storage_modulus"]["per_orientation"][0]
    with open(f"{out}/check_nv02000_zx.csv", "w") as f:
        f.write("orientation,storage_modulus,plate_storage_modulus,relax_steps,relax_converged,relax_final_force,"
                "dynamic_storage_modulus,difference\n")
        f.write(f"z:x,{r['storage_modulus']},{r['plate_storage_modulus']},{s['relaxation']['steps']},"
                f"{s['relaxation']['converged']},{s['relaxation']['final_mean_unbalanced_force']},2.765e6,"
                f"{r['storage_modulus'] / 2.765e6 - 1}\n")

if len(rows) >= 3:
    from packlab.plot.storage_modulus import fit_power_law
    import numpy as np
    a = np.array([float(r.split(",")[3]) for r in rows])
    g = np.array([float(r.split(",")[6]) for r in rows])
    f = fit_power_law(a, g)
    print(f"eq. 7 fit over {len(rows)} structures: a0 = {f['a0']:.4f}, beta = {f['beta']:.4f}, "
          f"C = {f['prefactor']:.4g} Pa")
    for k in range(len(rows)):
        m = np.arange(len(rows)) != k
        fk = fit_power_law(a[m], g[m])
        print(f"  without {rows[k].split(',')[0]}: a0 = {fk['a0']:.4f}, beta = {fk['beta']:.4f}")
PY
if [ "$(wc -l < "$OUT/table2.csv")" -ge 4 ]; then
  "$PY" -m packlab.plot storage_modulus "$OUT/table2.csv" --out "$OUT/storage_modulus.png"
fi
cat "$OUT/table2.csv"
