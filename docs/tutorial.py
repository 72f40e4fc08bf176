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

# 3. Bond: every contact becomes a PFC contact bond (rest length = current distance).
model = relaxed.packing.copy()
contacts = packlab.find_contacts(model, contact_eps=0.01)
L = np.array(model.box.length)
image = np.rint((model.positions[contacts["i"]] + contacts["branch"] - model.positions[contacts["j"]]) / L).astype(int)
model.set_bonds(contacts["i"], contacts["j"], image=image)
print(f"{len(model.bonds)} bonds")
packlab.write(model, os.path.join(out, "bonded.vtu"))  # bonds are line cells in ParaView

# 4. Test: a bonded model in the engine; stress per particle (the mechanical tests
#    (shear, compression) come with the mechanics issue).
bond = packlab.BondMaterial(normal_stiffness=1000, shear_stiffness=10, normal_strength=1e-3, shear_strength=1e-3)
engine = packlab.Engine(model, normal_stiffness=1000, shear_stiffness=10, density=3690,
                        stiffness_rule="contact", bond_materials=[bond])
engine.run(200)
stress = engine.particle_stress()  # N x 3 x 3 [Pa]
print(f"{engine.intact_bonds} intact bonds, mean pressure {-np.trace(stress, axis1=1, axis2=2).mean() / 3:.3g} Pa")

# 5. Plot: the standard figures of packlab.plot, from the tables written above.
packlab.plot.save(packlab.plot.relax.figure(os.path.join(out, "relax.csv")), os.path.join(out, "tutorial-relax.png"))
packlab.plot.save(packlab.plot.coordination.figure(os.path.join(out, "coordination.csv")),
                  os.path.join(out, "tutorial-coordination.png"))
packlab.plot.save(packlab.plot.rdf.figure(os.path.join(out, "rdf.csv"), phi=ls.volume_fraction),
                  os.path.join(out, "tutorial-rdf.png"))
print(f"wrote the figures to {out}")
