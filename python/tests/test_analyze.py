"""Analyses: parameters in the constructor, compute(packing), arrays out."""

import numpy as np
import pytest

import packlab


def test_coordination_of_lattices():
    for kind, z in [("sc", 6), ("bcc", 8), ("fcc", 12)]:
        c = packlab.Coordination(contact_eps=0.01).compute(packlab.generate_lattice(type=kind, radius=0.5))
        assert c.mean == pytest.approx(z)
        assert (c.counts == z).all() and c.rattler_count == 0
        assert c.distribution[z] == c.particle_count


def test_coordination_views_are_read_only_and_accumulate():
    p = packlab.generate_random(particles=200, radius=0.5, phi=0.3, seed=1)
    c = packlab.Coordination(rattler_threshold=4)
    c.compute(p)
    with pytest.raises(ValueError):
        c.counts[0] = 3
    assert c.rattlers.dtype == bool and c.rattlers.sum() == c.rattler_count
    c.compute(packlab.generate_random(particles=200, radius=0.5, phi=0.3, seed=2), reset=False)
    assert c.frames == 2 and c.particle_count == 400


def test_reading_before_compute_raises():
    with pytest.raises(Exception):
        packlab.Coordination().mean


def test_find_contacts_branches():
    p = packlab.generate_lattice(type="fcc", cells=(2, 2, 2), radius=0.5)
    c = packlab.find_contacts(p)
    assert len(c["i"]) == 32 * 12 // 2
    assert np.allclose(np.linalg.norm(c["branch"], axis=1), 1.0)


def test_rdf_of_a_hard_sphere_packing():
    p = packlab.generate_ls(phi=0.4, particles=300, radius=0.5, seed=2).packing
    rdf = packlab.Rdf(dr=0.05, r_max=4.0).compute(p)
    r, g = rdf.r, rdf.g()
    assert r.shape == g.shape and rdf.classes == 1
    assert (g[r < 1.95] == 0).all()  # no pair closer than contact (r in units of the radius)
    assert rdf.contact_value() > 1.0
    assert np.mean(g[r > 3.0]) == pytest.approx(1.0, abs=0.15)
    assert packlab.reference.percus_yevick_contact(0.4) > 1.0


def test_pore_size_and_doh_fit():
    p = packlab.generate_ls(phi=0.4, particles=200, radius=0.5, seed=1).packing
    ps = packlab.PoreSize(points=2000).compute(p, seed=1)
    assert ps.porosity() == pytest.approx(0.6, abs=0.05)
    curve = ps.curve()
    assert curve["probability"][0] == pytest.approx(1.0) and (np.diff(curve["probability"]) <= 1e-12).all()
    fit = ps.fit_doh()
    assert fit.converged and fit.a > 0 and fit.r2 > 0.95


def test_fabric_of_a_lattice_is_isotropic():
    f = packlab.Fabric().compute(packlab.generate_lattice(type="fcc", radius=0.5))
    assert np.allclose(f.tensor, np.eye(3) / 3) and f.anisotropy == pytest.approx(0.0, abs=1e-12)


def test_inflection_and_power_law_fits():
    q = np.linspace(0, 3, 200)
    cn = 6 / (1 + np.exp(-(q - 1.2) / 0.1))
    f = packlab.find_inflection(q, cn)
    assert f.found and f.x == pytest.approx(1.2, abs=1e-6) and f.y == pytest.approx(3.0, abs=1e-6)
    x = np.linspace(0.5, 1.0, 20)
    y = 2.0 + 3.0 * (x - 0.5) ** 0.7
    pl = packlab.fit_power_law(x, y, 0.5, 2.0)
    assert pl.found and pl.beta == pytest.approx(0.7, rel=1e-6)
