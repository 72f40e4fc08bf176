"""packlab.bond, packlab.shear_test, packlab.calibrate_shear and the shear figures."""

import math

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

import packlab
import packlab.plot
import packlab.plot.shear
import packlab.plot.storage_modulus

R0 = 0.25e-6
FAST = dict(stiffness_rule="contact", normal_stiffness=100, shear_stiffness=10, normal_strength=math.inf,
            shear_strength=math.inf, cycles=2, steps_per_cycle=4000, regions=1, threads=1)


def sc_lattice():
    p = packlab.generate_lattice(type="sc", cells=(4, 4, 4), radius=R0)
    return packlab.bond(p, model="contact", eps=0.01)


def sc_modulus(ks):
    # Simple-cubic network between rigid plates, n = 4 layers: G = k_s n / ((2n + 1) d).
    return ks * 4 / (9 * 2 * R0)


def test_bond_installs_the_six_neighbours_of_the_cubic_lattice():
    p = sc_lattice()
    assert len(p.bonds) == 192


def test_shear_test_matches_the_closed_form_and_returns_samples():
    calls = []
    r = packlab.shear_test(sc_lattice(), orientations="z", progress=lambda *a: calls.append(a), **FAST)
    g = r["storage_modulus"]
    assert g["mean"] == pytest.approx(sc_modulus(10), rel=0.01)
    assert len(g["per_orientation"]) == 2
    run = g["per_orientation"][0]
    assert run["orientation"] == "z:x"
    assert abs(r["phase_angle"]) < 0.01
    s = run["samples"]
    assert isinstance(s["stress"], np.ndarray) and len(s["stress"]) == 2 * 40
    # The strain follows the prescribed sine: last cycle amplitude 1e-3.
    assert np.max(np.abs(s["strain"])) == pytest.approx(1e-3, rel=1e-9)
    assert calls, "progress callback never called"
    assert len(r["packing"].bonds) == 192


def test_storage_modulus_scales_with_both_stiffnesses():
    # Four times k_n and k_s: dt halves exactly, the run is the same in steps, forces x 4.
    p = sc_lattice()
    a = packlab.shear_test(p, orientations="z:x", **FAST)["storage_modulus"]["mean"]
    fast4 = dict(FAST, normal_stiffness=400, shear_stiffness=40)
    b = packlab.shear_test(p, orientations="z:x", **fast4)["storage_modulus"]["mean"]
    assert b == pytest.approx(4 * a, rel=1e-12)


def test_bad_orientation_is_a_value_error():
    with pytest.raises(Exception, match="orientations"):
        packlab.shear_test(sc_lattice(), orientations="q", **FAST)


def test_calibrate_shear_recovers_the_stiffness():
    r = packlab.calibrate_shear(sc_lattice(), target_storage_modulus=sc_modulus(12.0), orientations="z:x", stiffness_rule="contact",
                                cycles=1, steps_per_cycle=4000, tolerance=0.002)
    assert r["converged"]
    assert r["normal_stiffness"] == pytest.approx(120.0, rel=0.01)


def test_figures(tmp_path):
    csv = tmp_path / "stress_strain.csv"
    phase = 2 * np.pi * np.arange(1, 41) / 40
    rows = ["orientation,cycle,step,time,phase,strain,stress,plate_stress"]
    for c in (1, 2):
        for k, ph in enumerate(phase):
            g = 1e-3 * c / 2 * math.sin(ph)
            rows.append(f"z:x,{c},{k},{k},{ph},{g},{1e6 * g},{1e6 * g}")
    csv.write_text("\n".join(rows) + "\n")
    packlab.plot.save(packlab.plot.shear.figure(csv), tmp_path / "shear.png")
    assert (tmp_path / "shear.png").stat().st_size > 1000
    # eq. 7 with the paper's a0 = 0.373, beta = 0.19: the fit recovers them from exact points.
    a = np.array([0.392, 0.399, 0.418, 0.467, 0.521, 0.594])
    g = 2.0e6 * (a - 0.373) ** 0.19
    f = packlab.plot.storage_modulus.fit_power_law(a, g)
    assert f["a0"] == pytest.approx(0.373, abs=2e-3)
    assert f["beta"] == pytest.approx(0.19, abs=0.01)
    table = tmp_path / "table.csv"
    table.write_text("a,storage_modulus,std,label\n" + "".join(f"{x},{y},{0.1 * y},this work\n" for x, y in zip(a, g)))
    packlab.plot.save(packlab.plot.storage_modulus.figure(table), tmp_path / "g.png")
    assert (tmp_path / "g.png").stat().st_size > 1000
    # Fit over several labels ("A|B", e.g. VEM and BD points together): the two A points alone
    # give no fit, A and B together the eq. 7 parameters of all six.
    table.write_text("a,storage_modulus,std,label\n" + "".join(
        f"{x},{y},{0.1 * y},{'A' if k < 2 else 'B'}\n" for k, (x, y) in enumerate(zip(a, g))))
    fit_lines = lambda fig: [t.get_text() for t in fig.axes[0].get_legend().get_texts() if t.get_text().startswith("fit")]
    assert fit_lines(packlab.plot.storage_modulus.figure(table, fit_label="A")) == []
    [both] = fit_lines(packlab.plot.storage_modulus.figure(table, fit_label="A|B"))
    assert f"$a_0$ = {f['a0']:.3f}" in both


def test_static_solver_gives_the_closed_form_through_the_same_call():
    # solver="static": one linear solve per orientation, the same set-up and report.
    r = packlab.shear_test(sc_lattice(), orientations="z", solver="static", **FAST)
    assert r["solver"] == "static"
    assert r["storage_modulus"]["mean"] == pytest.approx(sc_modulus(10), rel=1e-8)
    assert abs(r["phase_angle"]) < 1e-12
    assert r["storage_modulus"]["per_orientation"][0]["solver"] == "static"


def test_static_compression_of_a_beam_bond_column_is_pi_over_4_e_b():
    # Simple cubic column, beam bonds to the six neighbours: E = (pi / 4) E_b.
    p = packlab.generate_lattice(type="sc", cells=(3, 3, 8), radius=7.5e-9)
    p = packlab.bond(p, model="elastic", cutoff_ratio=1.01)
    r = packlab.compression_test(p, solver="static", max_strain=0.003, threads=1)
    assert r.solver == "static"
    assert r.youngs_modulus == pytest.approx(math.pi / 4 * 6.53e9, rel=1e-8)
