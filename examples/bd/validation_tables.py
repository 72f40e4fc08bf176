"""Tables of docs/bd.md from the runs of examples/bd/validation.sh:
docs/data/bd_msd.csv, bd_potential.csv, bd_potential_extrema.csv, bd_dla_clusters.csv and
bd_validation.json (D/D_0, the barrier heights, the fractal dimension).
usage: /usr/bin/python3 validation_tables.py RUNDIR DATADIR"""
import csv
import json
import sys

import numpy as np


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def read_xyz(path):
    with open(path) as f:
        n = int(f.readline())
        header = f.readline()
        lattice = [float(v) for v in header.split('Lattice="')[1].split('"')[0].split()]
        pos, rad = [], []
        for _ in range(n):
            parts = f.readline().split()
            pos.append([float(v) for v in parts[1:4]])
            rad.append(float(parts[4]))
    return np.array(pos), np.array(rad), np.array([lattice[0], lattice[4], lattice[8]])


def clusters(pos, radius, box, eps=0.03):
    """Clusters of spheres closer than (1 + eps)(r_i + r_j) (periodic), each unwrapped by a
    breadth-first walk over its bonds; returns [(size, radius of gyration)]."""
    from scipy.spatial import cKDTree
    p = np.mod(pos, box)
    tree = cKDTree(p, boxsize=box)
    pairs = tree.query_pairs((1 + eps) * 2 * radius.max(), output_type="ndarray")
    n = len(p)
    nbr = [[] for _ in range(n)]
    for i, j in pairs:
        nbr[i].append(j)
        nbr[j].append(i)
    seen = np.zeros(n, bool)
    out = []
    for s in range(n):
        if seen[s]:
            continue
        seen[s] = True
        unwrapped = {s: p[s]}
        stack = [s]
        while stack:
            i = stack.pop()
            for j in nbr[i]:
                if seen[j]:
                    continue
                d = p[j] - p[i]
                d -= box * np.round(d / box)
                unwrapped[j] = unwrapped[i] + d
                seen[j] = True
                stack.append(j)
        x = np.array(list(unwrapped.values()))
        rg = np.sqrt(((x - x.mean(0)) ** 2).sum(1).mean()) if len(x) > 1 else 0.0
        out.append((len(x), rg))
    return out


def main(run, data):
    result = {}
    # 1. Free diffusion.
    msd = read_csv(f"{run}/free/msd.csv")
    free = json.load(open(f"{run}/free/report.json"))
    d0 = free["results"]["diffusion_coefficient_m2_per_s"]
    t, m = msd["time_s"][1:], msd["msd_m2"][1:]
    d_fit = float((m * t).sum() / (t * t).sum() / 6)
    result["free_diffusion"] = {"particles": free["parameters"]["particles"], "D0_m2_per_s": d0,
                                "D_fit_m2_per_s": d_fit, "D_fit_over_D0": d_fit / d0,
                                "standard_error_expected": float(np.sqrt(2 / 3 / free["parameters"]["particles"]))}
    with open(f"{data}/bd_msd.csv", "w") as f:
        f.write("# examples/bd/validation.sh: free diffusion, N = 4000, Phi = 0.002, A = 0\n")
        f.write("time_s,reduced_time,msd_m2,stokes_einstein_m2\n")
        for a, b, c in zip(msd["time_s"], msd["reduced_time"], msd["msd_m2"]):
            f.write(f"{a:.8e},{b:.8g},{c:.8e},{6 * d0 * a:.8e}\n")
    # 2. Potentials.
    rows = []
    with open(f"{data}/bd_potential.csv", "w") as f:
        f.write("# examples/bd/validation.sh: the DLVO potential (defaults) in kT against h\n")
        f.write("surface_potential_mV,separation_m,energy_kT\n")
        for mv in (0, 12, 13, 14, 15):
            pot = read_csv(f"{run}/potential_{mv}/potential.csv")
            for h, u in zip(pot["separation_m"], pot["energy_kT"]):
                f.write(f"{mv},{h:.6e},{u:.8g}\n")
            p = json.load(open(f"{run}/potential_{mv}/report.json"))["potential"]
            rows.append((mv, p))
    with open(f"{data}/bd_potential_extrema.csv", "w") as f:
        f.write("surface_potential_mV,has_barrier,barrier_kT,barrier_separation_nm,secondary_minimum_kT,"
                "secondary_minimum_separation_nm,barrier_above_secondary_minimum_kT\n")
        for mv, p in rows:
            f.write(f"{mv},{int(p['has_barrier'])},{p['barrier_kT']:.4f},{p['barrier_separation_m'] * 1e9:.3f},"
                    f"{p['secondary_minimum_kT']:.4f},{p['secondary_minimum_separation_m'] * 1e9:.3f},"
                    f"{p['barrier_above_secondary_minimum_kT']:.4f}\n")
    result["potential"] = {str(mv): p for mv, p in rows}
    # 3. DLCA fractal dimension: log n = d_f log(R_g / a) + c over clusters of n >= 5.
    pos, rad, box = read_xyz(f"{run}/dla/packing.xyz")
    a = rad.mean()
    cl = clusters(pos, rad, box)
    with open(f"{data}/bd_dla_clusters.csv", "w") as f:
        f.write("# examples/bd/validation.sh: DLCA, N = 3000, Phi = 0.03, psi_0 = 0, t = 200 a^2/D_0\n")
        f.write("size,radius_of_gyration_over_a\n")
        for n, rg in sorted(cl):
            f.write(f"{n},{rg / a:.6g}\n")
    big = np.array([(n, rg / a) for n, rg in cl if n >= 5])
    slope, intercept = np.polyfit(np.log(big[:, 1]), np.log(big[:, 0]), 1)
    dla = json.load(open(f"{run}/dla/report.json"))["results"]
    result["dla"] = {"clusters_ge_5": int(len(big)), "largest": int(big[:, 0].max()), "fractal_dimension": float(slope),
                     "prefactor": float(np.exp(intercept)), "time_diffusion_times": dla["time_simulated_diffusion_times"],
                     "particle_steps_per_second": dla["particle_steps_per_second"]}
    result["rates_particle_steps_per_second"] = {"free_phi_0.002": free["results"]["particle_steps_per_second"],
                                                 "dla_phi_0.03": dla["particle_steps_per_second"]}
    json.dump(result, open(f"{data}/bd_validation.json", "w"), indent=1)
    print(json.dumps({k: result[k] for k in ("free_diffusion", "dla")}, indent=1))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
