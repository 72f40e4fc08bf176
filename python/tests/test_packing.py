"""Packing, Box and Bonds: NumPy views share memory with the C++ arrays (no copies)."""

import copy

import numpy as np
import pytest

import packlab


def small():
    return packlab.generate_lattice(type="sc", cells=(2, 2, 2), radius=0.5)


def test_positions_are_a_view_that_shares_memory():
    p = small()
    x = p.positions
    assert x.shape == (8, 3) and x.dtype == np.float64
    assert np.shares_memory(x, p.positions)
    x[3, 1] = 0.123
    assert p.positions[3, 1] == 0.123  # modifying the array changes the packing
    p.radii[:] = 0.4
    assert p.volume_fraction() == pytest.approx(8 * 4 / 3 * np.pi * 0.4**3 / 8.0)
    p.types[0] = 2
    assert list(p.types[:2]) == [2, 0] and p.types.dtype == np.int32


def test_view_keeps_the_packing_alive():
    x = small().positions  # the packing object is only referenced by the view
    import gc

    gc.collect()
    assert x.shape == (8, 3) and np.isfinite(x).all()


def test_assignment_copies_in_place_and_checks_the_count():
    p = small()
    view = p.radii
    p.radii = np.full(8, 0.3)
    assert view[0] == 0.3  # same storage
    with pytest.raises(ValueError, match="radii: must have 8 entries"):
        p.radii = np.ones(7)
    with pytest.raises(ValueError, match="N x 3"):
        p.positions = np.ones((8, 2))


def test_construct_from_numpy_and_optional_arrays():
    rng = np.random.default_rng(1)
    x = rng.uniform(0, 10, size=(20, 3))
    p = packlab.Packing(positions=x, radii=np.full(20, 0.5), box=packlab.Box(length=(10, 10, 10)))
    assert len(p) == 20 and np.array_equal(p.positions, x)
    assert not np.shares_memory(p.positions, x)  # the constructor copies
    assert p.velocities is None and p.fixed is None and p.densities is None
    p.velocities = np.zeros((20, 3))
    p.velocities[5] = (1, 2, 3)
    assert tuple(p.velocities[5]) == (1, 2, 3)
    p.fixed = np.arange(20) < 5
    assert p.fixed.dtype == bool and p.fixed.sum() == 5
    p.fixed = None
    assert p.fixed is None
    p.validate()


def test_box_is_a_reference():
    p = small()
    p.box.length = (3.0, 2.0, 2.0)
    p.box.periodic = (True, True, False)
    assert p.box.length == (3.0, 2.0, 2.0) and p.box.periodic == (True, True, False)
    assert p.box.volume == pytest.approx(12.0)


def test_fields_and_copies():
    p = small()
    p.set_field("stress", np.arange(8.0))
    assert p.field_names == ["stress"]
    p.field("stress")[0] = 42
    assert p.field("stress")[0] == 42
    q = copy.deepcopy(p)
    q.positions[0] = 0.0
    assert not np.shares_memory(p.positions, q.positions)
    with pytest.raises(KeyError):
        p.field("nothing")


def test_bonds_views_and_set_bonds():
    p = small()
    contacts = packlab.find_contacts(p, contact_eps=0.01)
    assert len(contacts["i"]) == 24  # sc 2x2x2 periodic: 3 bonds per particle
    # In a 2-cell periodic box a pair touches twice (directly and through the boundary): the
    # image of j tells the two bonds apart.
    L = np.array(p.box.length)
    image = np.rint((p.positions[contacts["i"]] + contacts["branch"] - p.positions[contacts["j"]]) / L).astype(int)
    p.set_bonds(contacts["i"], contacts["j"], image=image)
    b = p.bonds
    assert len(b) == 24 and b.image.shape == (24, 3)
    # rest lengths default to the current bond vector length |r_j + image L - r_i|
    assert b.rest_length.min() > 0
    b.state[0] = 1
    assert p.bonds.state[0] == 1  # a view of the packing's bond list
    p.bonds.add(0, 1, rest_length=1.0)
    assert len(p.bonds) == 25


def test_validate_raises_input_error():
    p = small()
    p.radii[2] = -1.0
    with pytest.raises(packlab.InputError):
        p.validate()
