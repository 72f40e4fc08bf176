"""The DEM engine and relax: keywords like the CLI, GIL released, progress callback."""

import threading

import numpy as np
import pytest

import packlab

MATERIAL = dict(normal_stiffness=1000, shear_stiffness=10, friction=0.1, density=3690, stiffness_rule="contact")


def start(n=100, phi=0.6, seed=1):
    return packlab.generate_random(particles=n, radius=0.25e-6, phi=phi, seed=seed)


def compressed_lattice(kind="sc", cells=3, strain=0.01, jitter=0.0, seed=1):
    """A lattice squeezed by `strain` (every neighbour pair overlaps), optionally jittered."""
    p = packlab.generate_lattice(type=kind, cells=(cells,) * 3, radius=0.5)
    p.positions *= 1 - strain
    p.box.length = tuple(x * (1 - strain) for x in p.box.length)
    p.positions += np.random.default_rng(seed).normal(scale=jitter, size=p.positions.shape)
    return p


def test_relax_converges_and_reports_progress():
    calls = []
    p = compressed_lattice(jitter=0.002)
    result = packlab.relax(p, normal_stiffness=100, shear_stiffness=10, tolerance=1e-2, steps=5000, threads=1,
                           progress=lambda step, total, d: calls.append((step, total, d.unbalanced_force_ratio)),
                           progress_interval=0.0)
    assert result.converged and result.steps <= 5000
    assert result.reason.startswith("converged")
    assert len(result.packing) == 27 and not np.array_equal(result.packing.positions, p.positions)
    h = result.history
    assert h["step"][0] == 0 and len(h["step"]) == len(h["unbalanced_force_ratio"])
    assert calls and calls[-1][1] == 5000
    assert calls[-1][2] == pytest.approx(result.last.unbalanced_force_ratio)


def test_relax_same_as_cli(tmp_path, cli):
    p = start(seed=2)
    packlab.write(p, tmp_path / "start.xyz")
    cli("relax", tmp_path / "start.xyz", tmp_path / "out.xyz", "--normal-stiffness", 1000, "--shear-stiffness", 10,
        "--friction", 0.1, "--density", 3690, "--stiffness-rule", "contact", "--steps", 300, "--tolerance", 0,
        "--threads", 1, "--quiet")
    result = packlab.relax(p, **MATERIAL, steps=300, tolerance=0, threads=1)
    assert np.array_equal(packlab.read(tmp_path / "out.xyz").positions, result.packing.positions)


def test_exception_in_progress_stops_the_run():
    def stop(step, total, d):
        if step >= 200:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        packlab.relax(start(), **MATERIAL, tolerance=0, steps=100000, progress=stop, progress_interval=0.0)


def test_run_alongside_another_python_thread():
    # Engine.run releases the GIL; how often the other thread gets to run depends on the
    # machine's load, so only the outcome is checked.
    engine = packlab.Engine(start(n=300), **MATERIAL, threads=1)
    done = threading.Event()

    def wait():
        while not done.is_set():
            done.wait(0.001)

    t = threading.Thread(target=wait)
    t.start()
    engine.run(3000)
    done.set()
    t.join()
    assert engine.step_count == 3000


def test_engine_forces_stress_and_state():
    p = compressed_lattice()
    e = packlab.Engine(p, normal_stiffness=100, shear_stiffness=10, threads=1)
    d = e.step()
    assert d.contacts == 81
    f = e.contact_forces()
    assert f["force"].shape == (81, 3) and set(f["kind"]) == {0}
    s = e.particle_stress()
    assert s.shape == (27, 3, 3)
    assert np.allclose(s, s.transpose(0, 2, 1))  # symmetric for central forces
    assert (np.einsum("kii->k", s) < 0).all()  # compression is negative
    state = e.save_state()
    e.run(10)
    x10 = e.packing().positions.copy()
    e2 = packlab.Engine(p, normal_stiffness=100, shear_stiffness=10, threads=1)
    e2.load_state(state)
    e2.run(10)
    assert np.array_equal(e2.packing().positions, x10)


def test_adapt_threads_keyword():
    """An adapting engine starts at one thread; adapt_threads=False runs the count asked for."""
    p = compressed_lattice()
    adapting = packlab.Engine(p, normal_stiffness=100, shear_stiffness=10, threads=2)
    fixed = packlab.Engine(p, normal_stiffness=100, shear_stiffness=10, threads=2, adapt_threads=False)
    assert (adapting.threads, adapting.active_threads) == (2, 1)
    assert (fixed.threads, fixed.active_threads) == (2, 2)
    adapting.run(20)
    fixed.run(20)
    # The results do not depend on the thread count.
    assert np.array_equal(adapting.packing().positions, fixed.packing().positions)


def test_bonded_model_holds_under_tension():
    p = packlab.generate_lattice(type="sc", cells=(2, 2, 2), radius=0.5)
    c = packlab.find_contacts(p)
    # 2 cells per periodic axis: each pair touches twice, directly and through the boundary, so
    # the image of j (from the branch vector) is what tells the two bonds apart.
    image = np.rint((p.positions[c["i"]] + c["branch"] - p.positions[c["j"]]) / np.array(p.box.length))
    p.set_bonds(c["i"], c["j"], image=image.astype(int))
    bond = packlab.BondMaterial(normal_stiffness=100, shear_stiffness=10, normal_strength=1e3, shear_strength=1e3)
    e = packlab.Engine(p, normal_stiffness=100, shear_stiffness=10, bond_materials=[bond], threads=1)
    assert e.intact_bonds == 24
    e.run(100)
    assert e.intact_bonds == 24


def test_walls():
    p = packlab.generate_lattice(type="sc", cells=(2, 2, 2), radius=0.5)
    p.box.periodic = (True, True, False)
    e = packlab.Engine(p, normal_stiffness=100, shear_stiffness=10, threads=1)
    k = e.add_wall(point=(0, 0, 1.9), normal=(0, 0, -1), velocity=(0, 0, -0.01))
    assert e.wall_count == 1
    e.run(50)
    assert e.wall_position(k)[2] < 1.9
