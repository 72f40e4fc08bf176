#!/usr/bin/env python3
"""Where the FCC opal breaks (bpm-inverse-opals §3, Fig. 8) from the break records of
examples/opal/fracture_pattern.sh: the same opal compressed by the quasi-static solver with
periodic and with open sides. The paper's observations, made quantitative:

* "initial defects and cracks originate starting from the interpore openings": the share of the
  breaks up to the peak whose bond lies near an interpore opening (within half a pore radius of
  the midpoint of two neighbouring pores), against the share of all bonds that lie there
  (enrichment = their ratio; 1 = breaks fall anywhere);
* "in the presence of PBC ... one macroscopic crack passing through the entire sample,
  perpendicular to the loading direction; with open boundaries vertically oriented intrapore
  cracks": the share of the breaks after the peak that fall in the densest horizontal band of
  a fifth of the sample's height (a horizontal crack: near 1; cracks along the load: near 0.2).

* where along the load the breaks start: per pore layer (the layers of pore centres along z,
  1 = next to the substrate; a bond belongs to the layer whose centre plane is nearest its
  midpoint), the share of the breaks up to the peak and of all breaks against the share of the
  bonds in that layer.

Writes DATA/opal_fracture_pattern.csv (one row per side condition), DATA/opal_fracture_layers.csv
(one row per side condition and pore layer) and FIGURE (break positions projected on the x-z
plane, in order of breaking, with the pores).

RUN_OUT holds one folder per sample, layersN (N pore layers: 3 and 4), each with opal/,
periodic/ and open/; the figure shows the tallest sample.

usage: fracture_pattern.py RUN_OUT [DATA] [FIGURE]"""

import csv
import json
import os
import sys

import numpy as np

import packlab
from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))
NEAR = 0.5  # "near an opening": within this many pore radii of its centre
BAND = 0.2  # the horizontal band, as a fraction of the sample's height


def read_pores(path):
    with open(path) as f:
        count = int(f.readline())
        f.readline()
        rows = [f.readline().split() for _ in range(count)]
    return np.array([[float(v) for v in r[1:4]] for r in rows]), float(rows[0][4])


def openings(centres, radius, box):
    """Midpoints of neighbouring pores (centre distance within 5 % of the nearest), with the
    periodic images along x and y."""
    shifts = [np.array([sx * box[0], sy * box[1], 0.0]) for sx in (-1, 0, 1) for sy in (-1, 0, 1)]
    pairs = []
    for s in shifts:
        d = np.linalg.norm(centres[None, :, :] + s - centres[:, None, :], axis=2)
        pairs.append((d, s))
    nearest = min(np.min(d[d > 0.1 * radius]) for d, _ in pairs)
    out = []
    for d, s in pairs:
        i, j = np.nonzero((d > 0.1 * radius) & (d < 1.05 * nearest))
        out.extend(0.5 * (centres[i] + centres[j] + s))
    return np.array(out), nearest


def distance_to_nearest(points, targets, box):
    """Minimum-image distance (x and y periodic) of each point to the nearest target."""
    best = np.full(len(points), np.inf)
    for start in range(0, len(points), 20000):
        p = points[start:start + 20000]
        d = targets[None, :, :] - p[:, None, :]
        for a in (0, 1):
            d[:, :, a] -= box[a] * np.round(d[:, :, a] / box[a])
        best[start:start + 20000] = np.sqrt((d * d).sum(axis=2)).min(axis=1)
    return best


def bond_midpoints(model):
    x = np.asarray(model.positions)
    b = model.bonds
    i, j = np.asarray(b.i), np.asarray(b.j)
    box = np.asarray(model.box.length)
    d = x[j] - x[i]
    for a in (0, 1):
        d[:, a] -= box[a] * np.round(d[:, a] / box[a])
    return x[i] + 0.5 * d


def pore_layers(centres, radius):
    """The z of each layer of pore centres, bottom first (centres within 0.1 R in z are one layer)."""
    layers = []
    for z in np.sort(centres[:, 2]):
        if not layers or z - layers[-1][-1] > 0.1 * radius:
            layers.append([z])
        else:
            layers[-1].append(z)
    return np.array([np.mean(layer) for layer in layers])


def layer_of(z, layer_z):
    """Index of the nearest layer plane to each z."""
    return np.argmin(np.abs(np.asarray(z)[:, None] - layer_z[None, :]), axis=1)


def densest_band(z, height):
    """Largest share of the values z in any window of width BAND x height."""
    z = np.sort(z)
    if len(z) == 0:
        return float("nan")
    ends = np.searchsorted(z, z + BAND * height, side="right")
    return float(np.max(ends - np.arange(len(z))) / len(z))


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    run = argv[1]
    data = argv[2] if len(argv) > 2 else os.path.join(HERE, "..", "..", "docs", "data")
    figure = argv[3] if len(argv) > 3 else os.path.join(HERE, "..", "..", "docs", "img", "opal_fracture_pattern.png")
    # One sample per folder RUN_OUT/layersN (N pore layers); the figure shows the tallest.
    samples = sorted((int(name[len("layers"):]), os.path.join(run, name)) for name in os.listdir(run)
                     if name.startswith("layers") and name[len("layers"):].isdigit())
    if not samples:
        sys.exit(f"fracture_pattern: no layersN folder in {run}")
    table = {k: [] for k in ("pore_layers", "sides", "particles", "bonds", "pore_to_particle_diameter", "youngs_modulus",
                             "strength", "breaks", "breaks_at_peak", "bonds_near_openings",
                             "early_breaks_near_openings", "enrichment", "late_breaks", "late_in_densest_band",
                             "substrate_breaks")}
    layers = {k: [] for k in ("pore_layers", "sides", "layer", "layer_z", "bonds_share", "breaks_at_peak", "breaks_at_peak_share",
                              "breaks", "breaks_share")}
    for pore_layer_count, sample in samples:
        centres, pore_radius = read_pores(os.path.join(sample, "opal", "pores.xyz"))
        panels = sample_tables(sample, pore_layer_count, centres, pore_radius, table, layers)
    write_tables(data, table, layers)
    draw(figure, panels, centres, pore_radius)
    return 0


def sample_tables(sample, pore_layer_count, centres, pore_radius, table, layers):
    """Adds the rows of one sample (both side conditions) to the tables; returns its panels."""
    layer_z = None
    panels = []
    for sides in ("periodic", "open"):
        out = os.path.join(sample, sides)
        with open(os.path.join(out, "report.json")) as f:
            res = json.load(f)
        with open(os.path.join(out, "curve.csv")) as f:
            curve = list(csv.DictReader(f))
        # The breaks up to the peak: those of the curve's point of highest stress.
        peak = max(curve, key=lambda r: float(r["stress"]))
        model = packlab.read(os.path.join(out, "model.vtu"))
        box = np.asarray(model.box.length)
        z_all = np.asarray(model.positions)[:, 2]
        height = z_all.max() - z_all.min()
        ops, _ = openings(centres, pore_radius, box)
        mid = bond_midpoints(model)
        with open(os.path.join(out, "broken_bonds.csv")) as f:
            breaks = list(csv.DictReader(f))
        bond = np.array([int(r["bond"]) for r in breaks], dtype=int)
        where = np.array([[float(r["x"]), float(r["y"]), float(r["z"])] for r in breaks]).reshape(-1, 3)
        at_peak = int(peak["broken_bonds"])
        near_all = float(np.mean(distance_to_nearest(mid, ops, box) < NEAR * pore_radius))
        early = where[:max(at_peak, 1)]
        near_early = float(np.mean(distance_to_nearest(early, ops, box) < NEAR * pore_radius)) if len(early) else np.nan
        late = where[at_peak:]
        material = np.asarray(model.bonds.material)
        diameter = 2.0 * float(np.mean(np.asarray(model.radii)))
        row = {"pore_layers": pore_layer_count, "sides": sides, "particles": res["particles"], "bonds": res["bonds"],
               "pore_to_particle_diameter": 2.0 * pore_radius / diameter, "youngs_modulus": res["youngs_modulus"],
               "strength": res["strength"], "breaks": len(breaks), "breaks_at_peak": at_peak,
               "bonds_near_openings": near_all, "early_breaks_near_openings": near_early,
               "enrichment": near_early / near_all, "late_breaks": len(late),
               "late_in_densest_band": densest_band(late[:, 2], height),
               "substrate_breaks": int(np.sum(material[bond] == 2)) if len(bond) else 0}
        for k in table:
            table[k].append(row[k])
        if layer_z is None:  # the layers of pores whose centres lie inside the sample
            layer_z = pore_layers(centres, pore_radius)
            layer_z = layer_z[(layer_z > z_all.min()) & (layer_z < z_all.max())]
        bond_layer = np.bincount(layer_of(mid[:, 2], layer_z), minlength=len(layer_z))
        early_layer = np.bincount(layer_of(early[:, 2], layer_z), minlength=len(layer_z)) if at_peak else \
            np.zeros(len(layer_z), dtype=int)
        all_layer = np.bincount(layer_of(where[:, 2], layer_z), minlength=len(layer_z))
        for k in range(len(layer_z)):
            for key, value in (("pore_layers", pore_layer_count), ("sides", sides), ("layer", k + 1), ("layer_z", layer_z[k]),
                               ("bonds_share", bond_layer[k] / max(len(mid), 1)),
                               ("breaks_at_peak", int(early_layer[k])),
                               ("breaks_at_peak_share", early_layer[k] / max(at_peak, 1)),
                               ("breaks", int(all_layer[k])), ("breaks_share", all_layer[k] / max(len(where), 1))):
                layers[key].append(value)
        print(f"{pore_layer_count} pore layers, {sides}: breaks up to the peak per pore layer (bottom first) "
              f"{[int(v) for v in early_layer]}, bonds per layer {[int(v) for v in bond_layer]}")
        print(f"{pore_layer_count} pore layers, {sides}: {len(breaks)} breaks ({at_peak} up to the peak): "
              f"{near_early:.2f} of the early ones near an opening against {near_all:.2f} of all bonds (x{near_early / near_all:.2f}); "
              f"{row['late_in_densest_band']:.2f} of the later ones in one band of {BAND:g} H")
        panels.append((sides, where, at_peak, box, height, z_all.min()))
    return panels


def write_tables(data, table, layers):
    path = os.path.join(data, "opal_fracture_pattern.csv")
    write_table(path, table, "examples/opal/fracture_pattern.sh + fracture_pattern.py: the FCC opal compressed "
                             "by the quasi-static solver, paper's bonds; near = within 0.5 R of an interpore opening")
    print(f"wrote {path}")
    path = os.path.join(data, "opal_fracture_layers.csv")
    write_table(path, layers, "examples/opal/fracture_pattern.py: breaks per pore layer (1 = next to the substrate; "
                              "a bond in the layer whose centre plane is nearest its midpoint), up to the peak and "
                              "in all, against the layer's share of the bonds")
    print(f"wrote {path}")


def draw(figure, panels, centres, pore_radius):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    for ax, (sides, where, at_peak, box, height, z0) in zip(axes, panels):
        for c in centres:
            ax.add_patch(plt.Circle((c[0] * 1e9, c[2] * 1e9), pore_radius * 1e9, fill=False, lw=0.4, color="0.7"))
        order = np.arange(len(where))
        sc = ax.scatter(where[:, 0] * 1e9, where[:, 2] * 1e9, c=order, s=3, cmap="viridis")
        ax.scatter(where[:at_peak, 0] * 1e9, where[:at_peak, 2] * 1e9, s=7, facecolors="none", edgecolors="red",
                   lw=0.4, label=f"the {at_peak} up to the peak")
        ax.set_title(f"{sides} sides: {len(where)} breaks")
        ax.set_xlabel("x [nm]")
        ax.set_xlim(0, box[0] * 1e9)
        ax.set_ylim(z0 * 1e9, (z0 + height) * 1e9)
        ax.set_aspect("equal")
        ax.legend(loc="upper right", fontsize=7)
    axes[0].set_ylabel("z (loading) [nm]")
    fig.colorbar(sc, ax=axes, label="break order")
    os.makedirs(os.path.dirname(figure), exist_ok=True)
    fig.savefig(figure, dpi=130)
    print(f"wrote {figure}")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
