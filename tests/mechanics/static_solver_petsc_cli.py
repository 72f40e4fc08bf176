"""`mpiexec -n K packlab test compress --solver static --solver-backend petsc` at 1 and 2 ranks
gives the default backend's Young's modulus and strength to solver tolerance, with the same
bonds broken in the same order (sequential linear analysis on a ~500-particle force-biased
sample with elastic bonds). Run by ctest as static_solver_petsc_cli in a build with PETSc:

    static_solver_petsc_cli.py PACKLAB MPIEXEC NUMPROC_FLAG WORKDIR [MPIEXEC_PREFLAGS...]
"""
import csv
import json
import os
import shutil
import subprocess
import sys

packlab, mpiexec, numproc_flag, work = sys.argv[1:5]
preflags = sys.argv[5:]
source = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
env = dict(os.environ, OMP_NUM_THREADS="1")
# Open MPI refuses root (CI containers) and more ranks than cores unless told; other MPIs ignore these.
env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")


def run(args, ranks=0):
    command = ([mpiexec, numproc_flag, str(ranks), *preflags] if ranks else []) + [packlab, *args]
    result = subprocess.run(command, env=env, capture_output=True, text=True, timeout=120)
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {' '.join(command)}\n{result.stdout}\n{result.stderr}")
    return result


def find(tree, key):
    """The first value of `key` anywhere in a JSON tree."""
    if isinstance(tree, dict):
        if key in tree:
            return tree[key]
        tree = list(tree.values())
    if isinstance(tree, list):
        for item in tree:
            found = find(item, key)
            if found is not None:
                return found
    return None


run(["generate", "fba", "--box", "1e-7,1e-7,1.5e-7", "--diameter", "1.5e-8", "--porosity", "0.40",
     "--periodic", "xy", "--seed", "3", "--no-plots", "--quiet", "--out", f"{work}/fba"])
run(["bond", f"{work}/fba/packing.xyz", "--model", "elastic", "--out", f"{work}/model.vtu"])
test = ["test", "compress", f"{work}/model.vtu", "--config", f"{source}/examples/opal/silica.toml",
        "--solver", "static", "--max-breaks", "40", "--no-plots", "--quiet"]
run(test + ["--out", f"{work}/default"])
for ranks in (1, 2):
    run(test + ["--solver-backend", "petsc", "--out", f"{work}/petsc{ranks}"], ranks)


def outcome(name):
    with open(f"{work}/{name}/report.json") as f:
        report = json.load(f)
    with open(f"{work}/{name}/broken_bonds.csv") as f:
        rows = [row for row in csv.reader(line for line in f if not line.startswith("#"))]
    return report, rows


reference, reference_breaks = outcome("default")
failures = []
for ranks in (1, 2):
    report, breaks = outcome(f"petsc{ranks}")
    for key in ("youngs_modulus", "strength", "strain_at_peak"):
        a, b = find(report, key), find(reference, key)
        if a is None or b is None or abs(a - b) > 1e-8 * abs(b):
            failures.append(f"{ranks} rank(s): {key} = {a}, default backend {b}")
    if find(report, "broken_bonds") != find(reference, "broken_bonds") or find(reference, "broken_bonds") < 10:
        failures.append(f"{ranks} rank(s): broken_bonds = {find(report, 'broken_bonds')}, "
                        f"default backend {find(reference, 'broken_bonds')}")
    # The bonds broken, in order: the first column after the header of broken_bonds.csv.
    if [row[0] for row in breaks] != [row[0] for row in reference_breaks]:
        failures.append(f"{ranks} rank(s): another sequence of broken bonds")
    if find(report, "mpi_ranks") != ranks:
        failures.append(f"{ranks} rank(s): report says mpi_ranks = {find(report, 'mpi_ranks')}")
if failures:
    sys.exit("\n".join(failures))
print(f"petsc backend at 1 and 2 ranks: E = {find(reference, 'youngs_modulus'):.10g} Pa, "
      f"strength = {find(reference, 'strength'):.10g} Pa, {find(reference, 'broken_bonds')} breaks, as the default")
