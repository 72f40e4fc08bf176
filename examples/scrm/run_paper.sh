#!/bin/bash
# Reproduces the cases of scrm-bimodal-packs.txt §4 (docs/scrm.md shows the results):
#  1. monodisperse, c = 0.575, 0.6, 0.63: LS (CRM) and SCRM, P realizations of N = 2000 each,
#     averaged RDFs, the drop of the contact value g(2a+) under shaking (paper: 43 %, 21 %, 4 %);
#  2. bimodal, size ratio 0.313, small/large volume ratio 0.333, c = 0.6: partial RDFs g11, g12,
#     g22 for N = 2000 (CRM and SCRM) and N = 7000 (SCRM, M = 3 global shakes);
#  3. the shell count I(r) of a simple cubic lattice for four bin widths;
#  4. fast compression of 10,000 monodisperse spheres to jamming at several growth rates;
#  5. the move rule of the shakes, what moves the drop at c = 0.575, and the number of final
#     shakes M of the bimodal packs (Figs. 12-13), also under the two other move rules.
# The packings are seven studies (docs/study.md): examples/study/scrm_paper.toml (1, 2 at
# N = 2000), scrm_bi7000.toml, scrm_lattice.toml (3), scrm_jamming.toml (4), scrm_rules.toml,
# scrm_diagnosis.toml, scrm_mstudy.toml and scrm_mstudy_rules.toml (5), run by `packlab study` into OUT/paper,
# OUT/bi7000, ... The folders of the summary (OUT/mono-ls-c0.6/r1, OUT/jam-G0.02,
# OUT/sc-dr0.01, ...) link to their runs; the averaged RDFs (one `packlab analyze rdf` over the
# realizations of a case) and summarize.py (tables, docs/data/scrm_*.csv, figures) follow.
# usage: examples/scrm/run_paper.sh [OUT=scrm-paper] [P=80] [JOBS=2]
# Needs `packlab` on PATH (or PACKLAB=path/to/packlab). Takes about an hour on two cores.
set -euo pipefail
OUT=${1:-scrm-paper}
P=${2:-80}
JOBS=${3:-2}
PACKLAB=${PACKLAB:-packlab}
HERE=$(cd "$(dirname "$0")" && pwd)
SPECS="$HERE/../study"
mkdir -p "$OUT"

# P realizations per curve: the SPEC has seeds 1-80; another P gets a copy with seeds 1-P.
paper="$SPECS/scrm_paper.toml"
if [ "$P" != 80 ]; then
  paper="$OUT/scrm_paper_P$P.toml"
  sed "s/^seeds = .*/seeds = [$(seq -s, 1 "$P")]/" "$SPECS/scrm_paper.toml" > "$paper"
fi
"$PACKLAB" study "$paper" --out "$OUT/paper" --workers "$JOBS"
for s in rules diagnosis mstudy mstudy_rules bi7000 lattice jamming; do
  "$PACKLAB" study "$SPECS/scrm_$s.toml" --out "$OUT/$s" --workers "$JOBS"
done

# The folders of the summary, linked to the studies' runs.
/usr/bin/python3 - "$OUT" <<'PY'
import csv, os, sys
out = sys.argv[1]

def rows(study):
    with open(os.path.join(out, study, "tasks.csv"), newline="") as f:
        return [r for r in csv.DictReader(f) if r["status"] == "done"]

def link(target, name):
    path = os.path.join(out, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if os.path.islink(path):
        os.remove(path)
    os.symlink(os.path.relpath(os.path.join(out, target), os.path.dirname(path)), path)

for r in rows("paper"):
    case = f"{'bi' if r['sizes'] != 'false' else 'mono'}-{r['method']}-c{r['phi']}"
    link(f"paper/runs/generate-{r['task']}", f"{case}/r{r['seed']}")
for r in rows("rules"):
    rule = "freest" if r["move-rule"] == "freest" else f"metropolis{r['max-trials']}"
    if r["sizes"] != "false":
        link(f"rules/runs/scrm-{r['task']}", f"bi-scrm-{rule}-M{r['final-shakes']}-c{r['phi']}/r{r['seed']}")
    else:
        link(f"rules/runs/scrm-{r['task']}", f"mono-scrm-{rule}-c{r['phi']}/r{r['seed']}")
for r in rows("diagnosis"):
    case = f"{r['method']}-G{r['growth-rate']}"
    if r["final-shakes"] not in ("false", "10"):
        case += f"-M{r['final-shakes']}"
    if r["blocks-per-cycle"] != "false":
        case += f"-bpc{r['blocks-per-cycle']}"
    link(f"diagnosis/runs/generate-{r['task']}", f"diag-{case}-c{r['phi']}/r{r['seed']}")
for r in rows("mstudy"):
    link(f"mstudy/runs/scrm-{r['task']}", f"bi-scrm-M{r['final-shakes']}-c0.6/r{r['seed']}")
for r in rows("bi7000"):
    link(f"bi7000/runs/scrm-{r['task']}", f"bi7000-scrm-c0.6/r{r['seed']}")
for r in rows("jamming"):
    link(f"jamming/runs/ls-{r['task']}", f"jam-G{r['growth-rate']}")
for r in rows("lattice"):
    link(f"lattice/runs/rdf-{r['task']}", f"sc-dr{r['rdf.dr']}")
PY

# Averaged RDFs (realizations in parallel inside analyze rdf).
for d in "$OUT"/mono-*-c* "$OUT"/bi-*-c* "$OUT"/bi7000-*-c*; do
  # Averaged already over the same number of realizations (another P averages again).
  n=$(ls -d "$d"/r[0-9]* | wc -l)
  [ -f "$d/rdf/report.json" ] && grep -q "\"realizations\": *$n[,}]" "$d/rdf/report.json" && continue
  "$PACKLAB" analyze rdf "$d"/r*/packing.xyz --partial --dr 0.01 --r-max 10 --out "$d/rdf" --quiet
done

/usr/bin/python3 "$HERE/summarize.py" "$OUT"
# The M study under the two other move rules (its own table: docs/data/scrm_mstudy_rules.csv).
PYTHONPATH="$HERE/../../python:$HERE/../../build/python${PYTHONPATH:+:$PYTHONPATH}" \
  /usr/bin/python3 "$HERE/mstudy_rules.py" "$OUT/mstudy_rules"
