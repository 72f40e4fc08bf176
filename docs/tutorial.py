#!/usr/bin/python3
"""The code of docs/tutorial.md: generate -> analyze -> bond -> test -> plot.

Run it as `PYTHONPATH=python:build/python /usr/bin/python3 docs/tutorial.py OUTDIR [--small]`;
`make docs` runs it to redraw docs/figures/tutorial-*.png and python/tests/test_tutorial.py
runs it with --small, so the tutorial cannot drift from the code."""

import os
import sys

import numpy as np

import packlab
import packlab.plot.coordination
import packlab.plot.rdf
import packlab.plot.relax
import packlab.plot.shear

out = sys.argv[1] if len(sys.argv) > 1 else "tutorial"
small = "--small" in sys.argv
os.makedirs(out, exist_ok=True)
N = 200 if small else 2000
radius = 0.25e-6  # [m]

# 1. Generate: hard spheres grown by Lubachevsky-Stillinger until they jam (phi=0) ...
ls = packlab.generate_ls(phi=0, particles=N, radius=radius, seed=1)
print(f"LS: {len(ls.packing)} particles, phi = {ls.volume_fraction:.4f} ({ls.stop})")
packlab.write(ls.packing, os.path.join(out, "ls.xyz"))  # opens in OVITO

# ... then the radii grown by 0.5 % (the arrays are NumPy views of the packing) and the
# overlapping soft spheres relaxed with the DEM engine (linear contacts, local damping).
p = ls.packing.copy()
p.radii *= 1.005
relaxed = packlab.relax(p, normal_stiffness=1000, shear_stiffness=10, friction=0.1, density=3690,
                        stiffness_rule="contact", tolerance=1e-3, steps=20000,
                        progress=lambda step, total, d: print(f"  step {step}: unbalanced {d.unbalanced_force_ratio:.3g}"))
print(relaxed.reason)
packlab.write(relaxed.packing, os.path.join(out, "relaxed.vtu"))  # opens in ParaView
packlab.write_table(os.path.join(out, "relax.csv"), relaxed.history)

# 2. Analyze: coordination numbers, g(r), pore sizes, fabric.
cn = packlab.Coordination(contact_eps=0.01).compute(relaxed.packing)
print(f"mean coordination {cn.mean:.3f}, without rattlers {cn.mean_without_rattlers:.3f}, "
      f"{cn.rattler_count} rattlers")
k = np.arange(len(cn.distribution))
packlab.write_table(os.path.join(out, "coordination.csv"),
                    {"contacts": k, "particles": cn.distribution, "fraction": cn.distribution / len(relaxed.packing)})
rdf = packlab.Rdf(dr=0.02, r_max=6.0).compute(ls.packing)
R = rdf.r
packlab.write_table(os.path.join(out, "rdf.csv"), {
    "R": R, "g": rdf.g(),
    "well_stirred": [packlab.reference.well_stirred(x, 1.0) for x in R],
    "willis": [packlab.reference.willis(x, 1.0, ls.volume_fraction) for x in R]})
print(f"g(2a+) = {rdf.contact_value():.3f} at phi = {ls.volume_fraction:.4f}")
pores = packlab.PoreSize(points=5000).compute(relaxed.packing, seed=1)
doh = pores.fit_doh()
print(f"porosity {pores.porosity():.3f}, degree of heterogeneity a = {doh.a:.3f} +- {doh.a_err:.3f}")
print(f"fabric anisotropy {packlab.Fabric().compute(relaxed.packing).anisotropy:.3f}")

# 3. Bond: every pair closer than (1 + eps)(r_i + r_j) becomes a PFC contact bond
#    (doh-elastic-properties §2.1), across periodic boundaries; bonds are saved in VTU files.
model = packlab.bond(relaxed.packing, model="contact", eps=0.01)
print(f"{len(model.bonds)} bonds")
packlab.write(model, os.path.join(out, "bonded.vtu"))  # bonds are line cells in ParaView

# 4. Test: the oscillatory shear test (§2.4) with the paper's Table 1 bond parameters, plate
#    normal z sheared along x, quasi-static (cycle length in steps); G' = |G*| cos(delta).
shear = packlab.shear_test(model, orientations="z:x", cycles=4 if small else 6,
                           steps_per_cycle=2000 if small else 8000, relax_max_steps=5000 if small else 20000)
g = shear["storage_modulus"]
print(f"G' = {g['mean'] / 1e6:.3f} MPa, phase angle {shear['phase_angle']:.4f} rad")
samples = g["per_orientation"][0]["samples"]
packlab.write_table(os.path.join(out, "shear.csv"), {
    "orientation": ["z:x"] * len(samples["strain"]), "cycle": samples["cycle"], "phase": samples["phase"],
    "strain": samples["strain"], "stress": samples["stress"]})

# 5. Plot: the standard figures of packlab.plot, from the tables written above.
packlab.plot.save(packlab.plot.relax.figure(os.path.join(out, "relax.csv")), os.path.join(out, "tutorial-relax.png"))
packlab.plot.save(packlab.plot.coordination.figure(os.path.join(out, "coordination.csv")),
                  os.path.join(out, "tutorial-coordination.png"))
packlab.plot.save(packlab.plot.rdf.figure(os.path.join(out, "rdf.csv"), phi=ls.volume_fraction),
                  os.path.join(out, "tutorial-rdf.png"))
packlab.plot.save(packlab.plot.shear.figure(os.path.join(out, "shear.csv")), os.path.join(out, "tutorial-shear.png"))
print(f"wrote the figures to {out}")
