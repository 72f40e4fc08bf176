"""packlab.compression_test and packlab.fit_porosity_law: the compression test from Python (same
physics as `packlab test compress`) and the porosity laws of bpm-inverse-opals eq. 22-26."""

import math

import numpy as np
import pytest

import packlab

R = 7.5e-9
E, NU = 6.53e9, 0.17


def sc_column(layers=8):
    """3 x 3 x layers simple cubic lattice, periodic, with elastic bonds to all 26 neighbours
    (the pairs within 1.75 d), built with Packing.set_bonds."""
    p = packlab.generate_lattice(type="sc", cells=(3, 3, layers), radius=R)
    d = 2 * R
    cells = np.array([3, 3, layers])
    index = {tuple(np.rint((x - d / 4) / d).astype(int)): k for k, x in enumerate(p.positions)}
    bi, bj, image = [], [], []
    for (a, b, c), i in index.items():
        for off in np.ndindex(3, 3, 3):
            o = np.array(off) - 1
            if (o[0], o[1], o[2]) <= (0, 0, 0):
                continue  # each pair once: the lexicographically positive half of the 26 neighbours
            n = np.array([a, b, c]) + o
            bi.append(i)
            bj.append(index[tuple(n % cells)])
            image.append(n // cells)
    p.set_bonds(i=np.array(bi), j=np.array(bj), image=np.array(image))
    return p


def test_glued_plate_gives_the_closed_form_modulus_of_a_simple_cubic_column():
    # Constrained modulus of the SC elastic-bond lattice with 26 bonded neighbours (tests/mechanics).
    g = E / (2 * (1 + NU))
    m = math.pi / 4 * (E + math.sqrt(2) * (E + g) + 4 * (E + 2 * g) / (3 * math.sqrt(3)))
    calls = []
    r = packlab.compression_test(sc_column(), bond_strength=math.inf, strain_rate=1e6, max_strain=0.003, samples=50,
                         snapshot_strains=[0.002], snapshot_stresses=[0.5 * m * 0.003, 10 * m * 0.003],
                         progress=lambda strain, stress: calls.append(strain), progress_interval=0.0)
    assert r.youngs_modulus == pytest.approx(m, rel=2e-3)
    assert r.broken_bonds == 0 and r.fixed_particles == 18
    c = r.curve
    assert c["stress"][-1] == pytest.approx(m * c["strain"][-1], rel=2e-3)
    assert calls and calls[-1] <= 0.003 + 1e-9
    # The stress request (half the final stress) comes first, at the first point reaching it; the
    # one never reached gives none.
    by_stress, snap = r.snapshots
    assert by_stress["requested_stress"] == 0.5 * m * 0.003 and snap["requested_strain"] == 0.002
    first = int(np.argmax(c["stress"] >= 0.5 * m * 0.003))
    assert by_stress["strain"] == c["strain"][first] and by_stress["stress"] == c["stress"][first]
    # Every level of the column is compressed alike: bond strains <= 0 (in-plane ones 0), particle stress
    # sigma_zz negative (compressive) in the free particles.
    strain = snap["bond_strain"]
    assert np.nanmax(strain) <= 1e-3 * abs(np.nanmin(strain))  # in-plane bonds: zero up to the dynamics
    assert snap["particle_stress"].shape == (len(r.model), 3, 3)
    assert snap["stress_by_type"][0]["mean"][2] < 0


def test_elastic_speedup_breaks_no_bond_fast_and_keeps_modulus_and_strength():
    # The adaptive rate from Python (docs/opal.md, "Adaptive rate"): fast until the first break,
    # then back to the point before it; every break lies past the switch, fewer steps are run, and
    # E and the strength are those of the constant-rate run (tolerances of the C++ test).
    kw = dict(bond_strength=94.3e6, bond_compressive_breakage=True, strain_rate=4e6, max_strain=0.03, samples=200,
              threads=1)
    constant = packlab.compression_test(sc_column(6), **kw)
    adaptive = packlab.compression_test(sc_column(6), elastic_speedup=4, **kw)
    assert math.isnan(constant.rate_switch_strain) and constant.broken_bonds > 0
    assert 0 < adaptive.rate_switch_strain <= adaptive.breaks["strain"].min()
    assert adaptive.rolled_back_steps > 0
    assert adaptive.steps + adaptive.rolled_back_steps < constant.steps
    assert adaptive.youngs_modulus == pytest.approx(constant.youngs_modulus, rel=2e-3)
    assert adaptive.strength == pytest.approx(constant.strength, rel=0.05)
    with pytest.raises(ValueError, match="elastic_speedup"):
        packlab.compression_test(sc_column(4), elastic_speedup=0.5)


def test_bad_keyword_values_raise_value_errors():
    with pytest.raises(ValueError, match="sides"):
        packlab.compression_test(sc_column(4), sides="closed")
    with pytest.raises(ValueError, match="strain_rate"):
        packlab.compression_test(sc_column(4), strain_rate=-1.0)


def test_porosity_fits_recover_m_and_b():
    eps = np.repeat([0.39, 0.45, 0.49, 0.55, 0.59, 0.63], 3)
    scatter = np.tile([-0.01, 0.0, 0.01], 6)
    e = 22.06e9 * (1 - eps) ** 1.92 * (1 + scatter)
    power = packlab.fit_porosity_law("power", eps, e, fixed_e0=22.06e9)
    assert power.exponent == pytest.approx(1.92, abs=0.01)
    expo = packlab.fit_porosity_law("exponential", eps, e, fixed_e0=22.06e9)
    assert expo.rss > power.rss
    s = 576.3e6 * np.exp(-3.85 * eps) * (1 + scatter)
    strength = packlab.fit_porosity_law("exponential", eps, s)
    assert strength.exponent == pytest.approx(3.85, abs=0.1)
    assert strength(0.5) == pytest.approx(576.3e6 * math.exp(-3.85 * 0.5), rel=0.02)
