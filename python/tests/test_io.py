"""read/write: the files of the command line, both ways, bit for bit."""

import json

import numpy as np
import pytest

import packlab


@pytest.mark.parametrize("ext", ["xyz", "vtu", "data", "csv", "txt"])
def test_round_trip_every_format(tmp_path, ext):
    p = packlab.generate_random(particles=50, radius=0.25e-6, phi=0.3, seed=3)
    p.types[:10] = 1
    path = tmp_path / f"p.{ext}"
    packlab.write(p, path, comment="test")
    q = packlab.read(path)
    assert len(q) == 50
    assert np.array_equal(q.positions, p.positions)
    assert np.array_equal(q.radii, p.radii)
    assert np.array_equal(q.types, p.types)
    if ext != "txt":
        assert q.box.length == p.box.length


def test_bonds_survive_vtu(tmp_path):
    p = packlab.generate_lattice(type="sc", cells=(2, 2, 2), radius=0.5)
    c = packlab.find_contacts(p)
    # 2 cells per periodic axis: each pair touches twice, directly and through the boundary, so
    # the image of j (from the branch vector) is what tells the two bonds apart.
    image = np.rint((p.positions[c["i"]] + c["branch"] - p.positions[c["j"]]) / np.array(p.box.length))
    p.set_bonds(c["i"], c["j"], image=image.astype(int))
    packlab.write(p, tmp_path / "b.vtu")
    q = packlab.read(tmp_path / "b.vtu")
    assert len(q.bonds) == len(p.bonds)
    assert np.array_equal(q.bonds.rest_length, p.bonds.rest_length)


def test_python_file_opens_in_the_cli_and_back(tmp_path, cli):
    p = packlab.generate_lattice(type="fcc", cells=(3, 3, 3), radius=0.25e-6)
    packlab.write(p, tmp_path / "fcc.xyz")
    info = json.loads(cli("info", tmp_path / "fcc.xyz", "--json").stdout)
    assert info["particles"] == 108 and info["mean_coordination"] == 12.0
    assert info["volume_fraction"] == pytest.approx(p.volume_fraction(), rel=1e-15)
    cli("generate", "lattice", "--type", "bcc", "--cells", 2, 2, 2, "--radius", 0.5, "--out", tmp_path / "c.data", "--quiet")
    q = packlab.read(tmp_path / "c.data")
    r = packlab.generate_lattice(type="bcc", cells=(2, 2, 2), radius=0.5)
    assert np.array_equal(q.positions, r.positions) and np.array_equal(q.radii, r.radii)


def test_same_random_packing_as_the_cli(tmp_path, cli):
    cli("generate", "random", "--particles", 100, "--radius", 0.5, "--phi", 0.3, "--seed", 7,
        "--out", tmp_path / "r.xyz", "--quiet")
    q = packlab.read(tmp_path / "r.xyz")
    p = packlab.generate_random(particles=100, radius=0.5, phi=0.3, seed=7)
    assert np.array_equal(q.positions, p.positions)


def test_box_for_files_without_one(tmp_path):
    path = tmp_path / "p.txt"
    path.write_text("1 1 1 0.5\n2 2 2 0.5\n")
    q = packlab.read(path, box=packlab.Box(length=(4, 4, 4)))
    assert q.box.length == (4.0, 4.0, 4.0)
    assert packlab.format_of("x.lammpstrj") == packlab.format_of("dump.run")
