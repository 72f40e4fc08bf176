"""packlab.generate_fba and packlab.build_opal (docs/opal-build.md): the FBA reaches
its porosity with overlaps below the tolerance (checked here by brute force with NumPy), the
same seed gives the same packing, the opal model has no particle centre inside a pore (eq. 1),
substrate = fixed, bond materials follow the bpm-inverse-opals §2.1 rules and rest lengths are
the periodic-image distances; bad input raises InputError naming the key."""

import numpy as np
import pytest

import packlab


def max_overlap(packing):
    x = np.asarray(packing.positions)
    r = np.asarray(packing.radii)
    box = packing.box
    L = np.asarray(box.length)
    per = np.asarray(box.periodic, dtype=bool)
    d = x[None, :, :] - x[:, None, :]
    d[:, :, per] -= L[per] * np.round(d[:, :, per] / L[per])
    dist = np.sqrt((d * d).sum(-1))
    s = r[:, None] + r[None, :]
    np.fill_diagonal(dist, np.inf)
    return max(0.0, float(((s - dist) / s).max()))


def test_fba_reaches_porosity_without_overlap_and_is_reproducible():
    a = packlab.generate_fba(particles=400, porosity=0.40, periodic="xy", seed=4)
    assert a.stop == "target_reached"
    assert a.porosity == pytest.approx(0.40, abs=1e-12)
    assert max_overlap(a.packing) <= 1e-3
    assert a.verified_max_overlap == pytest.approx(max_overlap(a.packing), abs=1e-12)
    assert len(a.history["iteration"]) >= 2
    b = packlab.generate_fba(particles=400, porosity=0.40, periodic="xy", seed=4)
    assert np.array_equal(a.packing.positions, b.packing.positions)


def test_build_opal_fcc_with_coating():
    D = 6.0
    per = (D, D * np.sqrt(3.0), D * np.sqrt(6.0))
    fba = packlab.generate_fba(box=(2 * per[0], per[1], per[2] + 2.0), diameter=1.0, porosity=0.40,
                               periodic="xy", seed=2)
    o = packlab.build_opal(fba.packing, pores="fcc", pore_diameter=D, orientation="111", coating=0.6)
    m = o.packing
    x = np.asarray(m.positions)
    L = np.asarray(m.box.length)
    for c, R in zip(o.pore_centres, o.pore_radii):
        d = x - c
        d[:, :2] -= L[:2] * np.round(d[:, :2] / L[:2])
        silica = np.asarray(m.types) != 3  # titania is the shell inside the pores (eq. 2)
        assert (np.sqrt((d * d).sum(1)) > R + np.asarray(m.radii))[silica].all()  # eq. (1)
    types = np.asarray(m.types)
    fixed = np.asarray(m.fixed)
    assert np.array_equal(fixed, types == 4)
    assert o.titania_particles > 0 and o.substrate_particles > 0
    bi, bj = np.asarray(m.bonds.i), np.asarray(m.bonds.j)
    ti, tj = types[bi], types[bj]
    expected = np.where((ti == 3) | (tj == 3), 1, np.where((ti == 4) & (tj == 4), 2, 0))
    assert np.array_equal(np.asarray(m.bonds.material), expected)
    vec = x[bj] + np.asarray(m.bonds.image) * L - x[bi]
    assert np.allclose(np.sqrt((vec * vec).sum(1)), m.bonds.rest_length, rtol=1e-12)
    assert o.mean_coordination == pytest.approx(2 * len(m.bonds) / len(m.radii))


def test_random_pores_and_bad_input():
    fba = packlab.generate_fba(box=(12.0, 12.0, 14.0), porosity=0.40, periodic="xy", seed=1)
    o = packlab.build_opal(fba.packing, pores="random", pore_ratio=4.0, pore_count=8, seed=3)
    assert o.pores == 8
    # Periodic pores over the whole box: the eight pores plus the images of those that cross the
    # top or bottom face (pores counts every sphere cut).
    p = packlab.build_opal(fba.packing, pores="random", pore_ratio=4.0, pore_count=8, pore_boundary="periodic", seed=3)
    assert p.pores > 8
    with pytest.raises(packlab.InputError, match="pore_boundary = open: must be walls or periodic"):
        packlab.build_opal(fba.packing, pores="random", pore_ratio=4.0, pore_count=8, pore_boundary="open")
    with pytest.raises(packlab.InputError, match="pore_boundary = periodic: only with pores = random"):
        packlab.build_opal(fba.packing, pore_ratio=4.0, pore_boundary="periodic")
    with pytest.raises(packlab.InputError, match="bond_cutoff = 2.5"):
        packlab.build_opal(fba.packing, pore_ratio=4.0, bond_cutoff=2.5)
    with pytest.raises(packlab.InputError, match="porosity = 0.1"):
        packlab.generate_fba(particles=100, porosity=0.1)
