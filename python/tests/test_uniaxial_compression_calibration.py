"""packlab.calibrate_compress: `packlab calibrate compress` from Python (bpm-inverse-opals
eq. 18-20) on a tiny pore-free force-biased sample: Newton recovers bond values that produced
the targets, the bulk factor is E / E_b of one packlab.compression_test run and equals the command line's."""

import json

import numpy as np
import pytest

import packlab

# One rate for every run (calibrate_compress, like the command line, keeps the automatic rate of
# its starting values; an explicit rate makes the reference run comparable).
TEST = dict(strain_rate=2e7, max_strain=0.15, stop_drop=0.8, samples=300)


@pytest.fixture(scope="module")
def sample():
    fba = packlab.generate_fba(particles=120, diameter=15e-9, porosity=0.38, periodic="xy", aspect=(1, 1, 1.5),
                               seed=3)
    return packlab.bond(fba.packing, model="elastic", cutoff_ratio=1.75)


def test_newton_recovers_the_bond_values_of_the_targets(sample):
    e_b, s_max = 8.0e9, 120e6
    ref = packlab.compression_test(sample, bond_youngs_modulus=e_b, bond_strength=s_max, **TEST)
    assert ref.broken_bonds > 0  # the peak is a failure, not the end of the run
    seen = []
    r = packlab.calibrate_compress(sample, target_youngs_modulus=ref.youngs_modulus, target_strength=ref.strength,
                                   progress=lambda *run: seen.append(run), **TEST)
    assert r["mode"] == "calibrate" and r["converged"], r["reason"]
    assert r["youngs_modulus"] == pytest.approx(ref.youngs_modulus, rel=0.005)
    assert r["strength"] == pytest.approx(ref.strength, rel=0.005)
    assert r["bond_youngs_modulus"] == pytest.approx(e_b, rel=0.005)  # E is proportional to E_b
    assert r["bond_strength"] == pytest.approx(s_max, rel=0.02)  # measured: 0.01 % and 0.04 % off
    h = r["history"]
    assert len(h["youngs_modulus"]) == r["simulations"] == len(seen) >= 3
    assert h["bond_youngs_modulus"][0] == 6.53e9 and h["bond_strength"][0] == 94.3e6  # the paper's values first
    assert h["finite_difference"].dtype == bool and h["finite_difference"].any()
    final = r["final"]
    assert isinstance(final, packlab.UniaxialCompressionResult)
    assert final.youngs_modulus == r["youngs_modulus"] and final.strength == r["strength"]


def test_bulk_factor_is_one_compression_and_matches_the_command_line(sample, cli, tmp_path):
    b = packlab.calibrate_compress(sample, bulk_factor=True, **TEST)
    one = packlab.compression_test(sample, **TEST)
    assert b["mode"] == "bulk_factor"
    assert b["youngs_modulus"] == one.youngs_modulus and b["strength"] == one.strength  # deterministic
    assert b["bulk_factor"] == pytest.approx(one.youngs_modulus / 6.53e9, rel=1e-12)
    assert b["strength_ratio"] == pytest.approx(one.youngs_modulus / one.strength, rel=1e-12)
    assert np.array_equal(b["final"].curve["stress"], one.curve["stress"])
    packlab.write(sample, tmp_path / "bulk.vtu")
    cli("calibrate", "compress", tmp_path / "bulk.vtu", "--bulk-factor", "--strain-rate", TEST["strain_rate"],
        "--max-strain", TEST["max_strain"], "--stop-drop", TEST["stop_drop"], "--samples", TEST["samples"],
        "--threads", 1, "--quiet", "--no-plots", "--out", tmp_path / "bulk")
    report = json.load(open(tmp_path / "bulk" / "report.json"))
    assert report["bulk_factor"] == pytest.approx(b["bulk_factor"], rel=1e-9)


def test_bad_input_raises_value_errors(sample):
    with pytest.raises(ValueError, match="target_youngs_modulus"):
        packlab.calibrate_compress(sample, target_strength=40e6)
    with pytest.raises(ValueError, match="sides"):
        packlab.calibrate_compress(sample, bulk_factor=True, sides="closed")
