"""Validation figures of ``packlab generate bd`` (docs/bd.md) from the tables of
``examples/bd/validation.sh``: ``msd`` (free diffusion against 6 D_0 t), ``potential`` (the DLVO
potential at several surface potentials), ``fractal`` (cluster size against radius of gyration
of diffusion-limited aggregation, with the fitted fractal dimension)."""

import math

from packlab.plot._common import UsageError, argument, new_figure, read_csv, run


def msd_figure(csv_path):
    data = read_csv(csv_path)
    fig, ax = new_figure()
    t = data["reduced_time"]
    ax.plot(t, [m / (0.25e-6) ** 2 for m in data["msd_m2"]], "C0o", ms=3, label="packlab BD, 4000 free spheres")
    ax.plot(t, [m / (0.25e-6) ** 2 for m in data["stokes_einstein_m2"]], "k-", lw=1, label="6 D_0 t (Stokes-Einstein)")
    ax.set_xlabel("t D_0 / a^2")
    ax.set_ylabel("MSD / a^2")
    ax.set_title("Free diffusion")
    ax.legend(fontsize=8)
    return fig


def potential_figure(csv_path):
    data = read_csv(csv_path)
    fig, ax = new_figure()
    for k, mv in enumerate(sorted(set(data["surface_potential_mV"]))):
        rows = [(h, u) for p, h, u in zip(data["surface_potential_mV"], data["separation_m"], data["energy_kT"])
                if p == mv]
        ax.plot([h * 1e9 for h, _ in rows], [u for _, u in rows], f"C{k}-", label=f"psi_0 = {mv:g} mV")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xscale("log")
    ax.set_xlim(1, 250)
    ax.set_ylim(-8, 8)
    ax.set_xlabel("surface separation h [nm]")
    ax.set_ylabel("U / k_B T")
    ax.set_title("DLVO potential (A = 3.67e-20 J, 1/kappa = 10 nm)")
    ax.legend(fontsize=8)
    return fig


def fractal_figure(csv_path, dimension=None):
    data = read_csv(csv_path)
    pts = [(r, n) for n, r in zip(data["size"], data["radius_of_gyration_over_a"]) if n >= 2]
    fig, ax = new_figure()
    ax.loglog([r for r, _ in pts], [n for _, n in pts], "C0o", ms=3, label="clusters (n >= 2)")
    big = [(math.log(r), math.log(n)) for r, n in pts if n >= 5]
    if len(big) >= 2:
        mx = sum(x for x, _ in big) / len(big)
        my = sum(y for _, y in big) / len(big)
        slope = sum((x - mx) * (y - my) for x, y in big) / sum((x - mx) ** 2 for x, _ in big)
        xs = [min(x for x, _ in big), max(x for x, _ in big)]
        ax.loglog([math.exp(x) for x in xs], [math.exp(my + slope * (x - mx)) for x in xs], "k-",
                  label=f"fit n >= 5: d_f = {slope:.2f}")
    ax.set_xlabel("radius of gyration / a")
    ax.set_ylabel("spheres in the cluster")
    ax.set_title("Diffusion-limited aggregation, Phi = 0.03")
    ax.legend(fontsize=8)
    return fig


def figure(which, csv_path):
    if which == "msd":
        return msd_figure(csv_path)
    if which == "potential":
        return potential_figure(csv_path)
    if which == "fractal":
        return fractal_figure(csv_path)
    raise UsageError(f"unknown figure '{which}' (msd, potential, fractal)")


def main(argv):
    return run("bd_validation", argv, figure, argument("which"), argument("csv_path"))
