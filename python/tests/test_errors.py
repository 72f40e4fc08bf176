"""Bad input raises packlab.InputError (a ValueError) with the command line's message."""

import pytest

import packlab


def test_input_error_is_a_value_error():
    assert issubclass(packlab.InputError, ValueError)


def test_same_message_as_the_cli(tmp_path, cli):
    with pytest.raises(packlab.InputError) as error:
        packlab.generate_lattice(type="hcp", radius=0.5)
    result = cli("generate", "lattice", "--type", "hcp", "--out", tmp_path / "x.xyz", check=False)
    assert result.returncode == 2
    assert result.stderr.strip() == f"packlab: error: {error.value}"


def test_malformed_file_names_file_and_line(tmp_path, cli):
    path = tmp_path / "bad.txt"
    path.write_text("1 2 3 0.5\n1 2 x 0.5\n")
    with pytest.raises(packlab.InputError, match=r"bad.txt:2") as error:
        packlab.read(path)
    result = cli("info", path, check=False)
    assert result.stderr.strip() == f"packlab: error: {error.value}"


@pytest.mark.parametrize(
    "call",
    [
        lambda: packlab.generate_random(particles=10, radius=0.5, phi=0.5, no_overlap=True),
        lambda: packlab.write(packlab.generate_lattice(), "packing.unknown"),
        lambda: packlab.read("/nonexistent/file.xyz"),
        lambda: packlab.Coordination(rattler_rule="sometimes"),
        lambda: packlab.relax(packlab.generate_lattice(), damping=1.5),
        lambda: packlab.relax(packlab.generate_lattice(), stiffness_rule="both"),
    ],
)
def test_bad_input_raises(call):
    with pytest.raises(packlab.InputError):
        call()


@pytest.mark.parametrize("seed", [-1, 2**63, 2**64, -(2**70), 1e23])
def test_seeds_out_of_range_are_input_errors(seed):
    # Python integers are unbounded: beyond int64 too the message is the command line's.
    with pytest.raises(packlab.InputError, match=r"seed = .*: (out of range|must be an integer)"):
        packlab.generate_random(particles=10, radius=0.5, phi=0.1, seed=seed)
