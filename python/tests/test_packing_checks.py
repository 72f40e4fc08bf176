"""Packing arrays from Python: views never outlive their memory, and every bad array (shape,
dtype, non-finite value, out-of-range type or index) raises packlab.InputError."""

import gc

import numpy as np
import pytest

import packlab


def small():
    return packlab.generate_lattice(type="sc", cells=(2, 2, 2), radius=0.5)


# --- views and growth ---------------------------------------------------------------------


def test_add_refuses_while_a_view_is_alive_and_the_view_stays_usable():
    p = small()
    x = p.positions
    with pytest.raises(packlab.InputError, match=r"add: 1 NumPy view\(s\) of this array are alive"):
        for _ in range(100):  # enough appends to force a reallocation, had any been allowed
            p.add((0.5, 0.5, 0.5), 0.25)
    assert len(p) == 8
    x[0, 0] = 0.125  # writes through the view land in the packing, not in freed memory
    assert p.positions[0, 0] == 0.125
    del x
    for _ in range(100):
        p.add((0.5, 0.5, 0.5), 0.25)
    assert len(p) == 108 and p.positions.shape == (108, 3)


def test_derived_views_pin_too_and_copies_do_not():
    p = small()
    tail = p.radii[4:]  # a view of a view keeps the storage pinned
    with pytest.raises(packlab.InputError):
        p.add((0, 0, 0), 0.5)
    del tail
    gc.collect()
    copied = p.radii.copy()
    p.add((0, 0, 0), 0.5)
    assert len(copied) == 8 and len(p) == 9


def test_temporary_views_do_not_block_add():
    p = small()
    assert p.positions.shape == (8, 3) and p.types.sum() == 0
    p.add((0.1, 0.2, 0.3), 0.5, type=1)
    assert list(p.types[-1:]) == [1]


def test_bond_views_block_add_and_replacement():
    p = small()
    contacts = packlab.find_contacts(p, contact_eps=0.01)
    L = np.array(p.box.length)
    image = np.rint((p.positions[contacts["i"]] + contacts["branch"] - p.positions[contacts["j"]]) / L).astype(int)
    p.set_bonds(contacts["i"], contacts["j"], image=image)
    state = p.bonds.state
    with pytest.raises(packlab.InputError, match="Bonds.add"):
        p.bonds.add(0, 7, rest_length=1.0)
    with pytest.raises(packlab.InputError, match="bonds"):
        p.set_bonds([0], [7])
    state[0] = 1
    assert p.bonds.state[0] == 1
    del state
    p.bonds.add(0, 7, image=(1, 1, 1), rest_length=1.0)
    assert len(p.bonds) == len(contacts["i"]) + 1


def test_removing_an_optional_array_or_field_refuses_while_viewed():
    p = small()
    p.velocities = np.zeros((8, 3))
    p.set_field("stress", np.arange(8.0))
    v, s = p.velocities, p.field("stress")
    with pytest.raises(packlab.InputError, match="velocities = None"):
        p.velocities = None
    with pytest.raises(packlab.InputError, match="remove_field"):
        p.remove_field("stress")
    v[0] = (1, 2, 3)
    s[1] = 5.0
    assert tuple(p.velocities[0]) == (1, 2, 3) and p.field("stress")[1] == 5.0
    del v, s
    p.velocities = None
    p.remove_field("stress")
    assert p.velocities is None and p.field_names == []


# --- shapes, dtypes and values -----------------------------------------------------------


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda p: setattr(p, "positions", np.ones((8, 2))), r"positions: must be an N x 3 array"),
        (lambda p: setattr(p, "positions", None), r"positions: must be an N x 3 array of numbers, got None"),
        (lambda p: setattr(p, "positions", [[None, 0, 0]] * 8), r"positions: .*dtype object"),
        (lambda p: setattr(p, "radii", np.ones(7)), r"radii: must have 8 entries, got 7"),
        (lambda p: setattr(p, "radii", ["a"] * 8), r"radii: must be a 1-D array of numbers"),
        (lambda p: setattr(p, "types", np.full(8, 1.5)), r"types: must be a 1-D array of integers, got dtype float64"),
        (lambda p: setattr(p, "types", np.full(8, -1)), r"types\[0\] = -1: must be >= 0"),
        (lambda p: setattr(p, "types", np.full(8, 2**40)), r"types\[0\] = 1099511627776: must be in"),
        (lambda p: setattr(p, "fixed", np.full(8, 0.5)), r"fixed: must be a 1-D array of booleans"),
    ],
)
def test_bad_arrays_raise_input_error(call, message):
    p = small()
    before = p.positions.copy()
    with pytest.raises(packlab.InputError, match=message):
        call(p)
    assert np.array_equal(p.positions, before)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_values_raise_input_error(bad):
    p = small()
    x = p.positions.copy()
    x[3, 1] = bad
    with pytest.raises(packlab.InputError, match=r"positions\[3\] = .*: must be finite"):
        p.positions = x
    r = np.full(8, 0.5)
    r[2] = bad
    with pytest.raises(packlab.InputError, match=r"radii\[2\] = .*: must be positive and finite"):
        p.radii = r
    with pytest.raises(packlab.InputError, match="velocities"):
        p.velocities = np.full((8, 3), bad)
    with pytest.raises(packlab.InputError, match="angular_velocities"):
        p.angular_velocities = np.full((8, 3), bad)
    with pytest.raises(packlab.InputError, match="densities"):
        p.densities = np.full(8, bad)
    with pytest.raises(packlab.InputError, match=r"add: position = .*: must be finite"):
        p.add((0.0, bad, 0.0), 0.5)
    with pytest.raises(packlab.InputError, match="add: radius"):
        p.add((0.0, 0.0, 0.0), bad)
    with pytest.raises(packlab.InputError, match="length"):
        packlab.Box(length=(1.0, bad, 1.0))
    with pytest.raises(packlab.InputError, match="lo"):
        p.box.lo = (bad, 0.0, 0.0)
    assert len(p) == 8 and np.isfinite(p.positions).all()


def test_constructor_checks():
    x = np.zeros((3, 3))
    with pytest.raises(packlab.InputError, match="radii: required"):
        packlab.Packing(positions=x)
    with pytest.raises(packlab.InputError, match="positions: required"):
        packlab.Packing(positions=None, radii=np.ones(3))
    with pytest.raises(packlab.InputError, match="types: must be a 1-D array of integers"):
        packlab.Packing(positions=x, radii=np.ones(3), types=[0.0, 1.0, 2.0])
    with pytest.raises(packlab.InputError, match="types: must be a 1-D array"):
        packlab.Packing(positions=x, radii=np.ones(3), types=99)
    with pytest.raises(packlab.InputError, match="types"):
        packlab.Packing(positions=x, radii=np.ones(3), types=[0, -99, 0])
    with pytest.raises(packlab.InputError, match="add: type = -1"):
        packlab.Packing().add((0, 0, 0), 0.5, type=-1)
    assert len(packlab.Packing()) == 0


def test_bond_checks():
    p = small()
    with pytest.raises(packlab.InputError, match="i: must be a 1-D array of integers, got dtype float64"):
        p.set_bonds([0.0, 1.0], [1, 2])
    with pytest.raises(packlab.InputError, match="image: must be an M x 3 array of integers"):
        p.set_bonds([0], [1], image=[[0.5, 0, 0]])
    with pytest.raises(packlab.InputError, match=r"indices must be in \[0, 8\)"):
        p.set_bonds([0], [8])
    with pytest.raises(packlab.InputError, match="to itself"):
        p.set_bonds([0, 1], [1, 1])
    with pytest.raises(packlab.InputError, match="bonded at most once"):
        p.set_bonds([0, 1], [1, 0])
    with pytest.raises(packlab.InputError, match="rest length of bond 0 = nan"):
        p.set_bonds([0], [1], rest_length=[np.nan])
    assert len(p.bonds) == 0  # every failed call left the bond list alone
    with pytest.raises(packlab.InputError, match="to itself"):
        p.bonds.add(3, 3, rest_length=1.0)
    p.set_bonds([0, 0], [1, 0], image=[[0, 0, 0], [1, 0, 0]])  # a bond to its own image is fine
    assert len(p.bonds) == 2


def test_shape_errors_are_still_value_errors():
    p = small()
    with pytest.raises(ValueError):
        p.radii = np.ones(3)
