"""A small run of each generator, keywords as on the command line."""

import numpy as np
import pytest

import packlab


def no_overlap(p, tol=1e-9):
    c = packlab.find_contacts(p, contact_eps=0.0)
    d = np.linalg.norm(c["branch"], axis=1)
    s = p.radii[c["i"]] + p.radii[c["j"]]
    return (d >= s * (1 - tol)).all()


@pytest.mark.parametrize("kind,n,phi", [("sc", 8, np.pi / 6), ("bcc", 16, np.pi * np.sqrt(3) / 8),
                                        ("fcc", 32, np.pi / (3 * np.sqrt(2)))])
def test_lattice(kind, n, phi):
    p = packlab.generate_lattice(type=kind, cells=(2, 2, 2), radius=0.25e-6)
    assert len(p) == n and p.volume_fraction() == pytest.approx(phi)


def test_random_and_rsa():
    p = packlab.generate_random(particles=300, radius=0.5, phi=0.3, no_overlap=True, seed=4)
    assert p.volume_fraction() == pytest.approx(0.3) and no_overlap(p)
    q = packlab.generate_random(particles=300, radius=0.5, phi=0.3, no_overlap=True, seed=4)
    assert np.array_equal(p.positions, q.positions)  # same seed, same packing


def test_ls_to_target_and_shake():
    blocks = []
    r = packlab.generate_ls(phi=0.5, particles=150, radius=0.5, seed=1,
                            progress=lambda b, phi, pressure: blocks.append(b), progress_interval=0.0)
    assert r.stop == "target_reached" and r.volume_fraction == pytest.approx(0.5)
    assert no_overlap(r.packing) and blocks and len(r.log["block"]) == r.blocks
    s = packlab.shake(r.packing, sweeps=3, seed=2)
    assert s.sweeps == 3 and no_overlap(s.packing)
    assert not np.array_equal(s.packing.positions, r.packing.positions)


def test_scrm_bimodal():
    r = packlab.generate_scrm(phi=0.55, particles=150, sizes=[1, 0.5], number_fractions=[0.5, 0.5],
                              final_shakes=2, seed=3)
    assert r.packing.volume_fraction() == pytest.approx(0.55, rel=1e-6)
    assert len(np.unique(r.packing.radii)) == 2 and no_overlap(r.packing)


def test_vem_small_run():
    v = packlab.generate_vem(structural=60, voids=30, phi_s=0.3, radius=0.25e-6, threads=1, max_q=0.3, seed=1)
    assert len(v.packing) == 60 and set(v.packing.types) == {0}
    c = v.curve
    assert c["q"][0] == pytest.approx(0.0, abs=1e-12) or c["q"][0] > 0
    assert len(c["q"]) == len(c["cn"]) >= 2 and (np.diff(c["q"]) > 0).all()


def test_generator_errors():
    with pytest.raises(packlab.InputError):
        packlab.generate_ls(phi=0.5, particles=10, sizes=[1, 0.5], number_fractions=[1, 1], volume_fractions=[1, 1])
    with pytest.raises(packlab.InputError):
        packlab.generate_vem(structural=10, voids=5, phi_s=0.9)


def test_bond_models_on_fcc(tmp_path):
    # FCC shells at d, sqrt(2) d, sqrt(3) d hold 12, 6, 24 neighbours: the contact model bonds
    # the first shell, the elastic model (1.75 d) the first three.
    p = packlab.generate_lattice(type="fcc", cells=(3, 3, 3), radius=0.5)
    contact = packlab.bond(p, model="contact", eps=0.01)
    assert len(contact.bonds) == 6 * len(p) and len(p.bonds) == 0
    assert np.allclose(contact.bonds.rest_length, 1.0)
    elastic = packlab.bond(p, model="elastic", cutoff_ratio=1.75)
    assert len(elastic.bonds) == 21 * len(p)
    packlab.write(elastic, tmp_path / "elastic.vtu")
    back = packlab.read(tmp_path / "elastic.vtu")
    assert np.array_equal(back.bonds.i, elastic.bonds.i) and np.array_equal(back.bonds.image, elastic.bonds.image)
    with pytest.raises(packlab.InputError, match="model = glue"):
        packlab.bond(p, model="glue")


def test_generate_bd_coagulates_and_reports_the_barrier():
    r = packlab.generate_bd(particles=250, volume_fraction=0.4, surface_potential=0.0, duration=0.02, samples=5,
                            seed=3)
    assert len(r.packing) == 250 and r.packing.volume_fraction() == pytest.approx(0.4)
    assert r.bonds > 100 and r.largest_cluster > 100 and r.stop == "duration"
    assert r.mean_coordination == pytest.approx(2 * r.bonds / 250)
    assert r.log["msd"][-1] > 0 and len(r.log["reduced_time"]) == 6
    assert not r.has_barrier
    r15 = packlab.generate_bd(particles=250, surface_potential=15e-3, duration=1e-4, seed=3)
    assert r15.has_barrier and r15.barrier_above_secondary_minimum_kT == pytest.approx(5.62, abs=0.01)
    with pytest.raises(packlab.InputError, match="volume_fraction"):
        packlab.generate_bd(particles=250, volume_fraction=0.7)
