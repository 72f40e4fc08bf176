"""Every command ported to an option set (io/config.hpp) takes the same options everywhere:
its command-line flags, its config-file keys and its Python keywords are one set, named by
one rule (key `relax.max_steps`: flag --relax-max-steps, keyword relax_max_steps)."""

import re

import pytest

import packlab

# command, Python function, positional arguments of the function
PORTED = [
    ("generate lattice", "generate_lattice", ()),
    ("generate random", "generate_random", ()),
    ("generate vem", "generate_vem", ()),
    ("generate ls", "generate_ls", ()),
    ("generate scrm", "generate_scrm", ()),
    ("generate fba", "generate_fba", ()),
    ("build opal", "build_opal", (packlab.generate_lattice(),)),
    ("relax", "relax", (packlab.generate_lattice(),)),
    ("shake", "shake", (packlab.generate_lattice(),)),
    ("bond", "bond", (packlab.generate_lattice(),)),
    ("test shear", "shear_test", (packlab.generate_lattice(),)),
    ("calibrate shear", "calibrate_shear", (packlab.generate_lattice(),)),
    ("test compress", "compression_test", (packlab.generate_lattice(),)),
    ("calibrate compress", "calibrate_compress", (packlab.generate_lattice(),)),
]

# Flags that steer the run rather than set an option (input, output, resuming, verbosity).
RUN_CONTROL = {"--help", "--config", "--out", "--resume", "--no-plots", "--no-vtu", "--check", "--quiet", "--log", "--checkpoint"}


def section(cli, command):
    text = cli("config-keys").stdout
    start = text.index(f"## `packlab {command}`")
    end = text.find("\n## ", start + 1)
    return text[start:end if end >= 0 else None]


def declared(cli, command):
    """(key, aliases, command line only) per row of the command's reference table."""
    rows = []
    for line in section(cli, command).splitlines():
        m = re.match(r"\| `([^`]+)` \|", line)
        if not m or m.group(1) == "key":
            continue
        description = line.rsplit("|", 2)[-2]
        aliases = re.findall(r"--([a-z0-9-]+)", re.search(r"\(also ([^)]*)\)", description).group(1)) \
            if "(also " in description else []
        rows.append((m.group(1), [a.replace("-", "_") for a in aliases], "*command line*" in description))
    assert rows, f"no keys for {command}"
    return rows


def help_flags(cli, command):
    flags = set()
    for line in cli(*command.split(), "--help").stdout.splitlines():
        m = re.match(r"^\s+(-[-\w,]+)", line)
        if m:
            flags.update(n for n in m.group(1).split(",") if n.startswith("--"))
    return flags - RUN_CONTROL


def python_keywords(function, args):
    with pytest.raises(packlab.InputError) as e:
        getattr(packlab, function)(*args, no_such_option=1)
    message = str(e.value)
    assert "no_such_option" in message
    return set(re.search(r"known: ([^)]*)\)", message).group(1).split(", "))


def flag(name):
    return "--" + name.replace(".", "-").replace("_", "-")


@pytest.mark.parametrize("command,function,args", PORTED)
def test_flags_keys_and_keywords_are_one_set(cli, command, function, args):
    rows = declared(cli, command)
    expected_flags = {flag(k) for k, _, _ in rows} | {flag(a) for _, aliases, _ in rows for a in aliases}
    assert help_flags(cli, command) == expected_flags
    expected_keywords = {k.replace(".", "_") for k, _, cli_only in rows if not cli_only} | \
        {a for _, aliases, cli_only in rows if not cli_only for a in aliases}
    assert python_keywords(function, args) == expected_keywords


def keywords_of(call):
    """The keywords a function or class takes, from its message for an unknown one."""
    with pytest.raises(packlab.InputError) as e:
        call(no_such_option=1)
    return set(re.search(r"known: ([^)]*)\)", str(e.value)).group(1).split(", "))


def test_analyze_takes_the_keywords_of_the_analysis_classes(cli):
    # `packlab analyze` runs several analyses: its options are the union of their classes'.
    rows = declared(cli, "analyze")
    assert help_flags(cli, "analyze") == {flag(k) for k, _, _ in rows}
    classes = (keywords_of(packlab.Coordination) | keywords_of(packlab.PoreSize) | keywords_of(packlab.Fabric)
               | keywords_of(packlab.PoreSize().fit_doh))
    assert {k for k, _, cli_only in rows if not cli_only} == classes
    rows = declared(cli, "analyze rdf")
    assert help_flags(cli, "analyze rdf") == {flag(k) for k, _, _ in rows}
    assert {k for k, _, cli_only in rows if not cli_only} == keywords_of(packlab.Rdf)


def test_keyword_values_are_checked_like_config_values():
    with pytest.raises(packlab.InputError, match="relax_max_steps"):
        packlab.generate_vem(relax_max_steps=1.5)
    with pytest.raises(packlab.InputError, match="time_step_rule"):
        packlab.generate_vem(time_step_rule=3)
    with pytest.raises(packlab.InputError, match="phi_s"):
        packlab.generate_vem(phi_s=0.9)


def test_list_options_read_as_comma_separated_flags_and_sequences(cli, tmp_path):
    r = packlab.generate_ls(phi=0.3, particles=40, sizes=(1, 0.5), number_fractions=[0.5, 0.5], seed=2)
    assert len(set(r.packing.radii.round(12))) == 2
    config = tmp_path / "ls.toml"
    config.write_text("phi = 0.3\nparticles = 40\nsizes = [1.0, 0.5]\nseed = 2\n")
    cli("generate", "ls", "--config", config, "--number-fractions", "0.5,0.5", "--no-plots", "--quiet",
        "--out", tmp_path / "ls")
    with pytest.raises(packlab.InputError, match="sizes"):
        packlab.generate_ls(sizes="big")


def test_flag_overrides_config_file_which_overrides_default(cli, tmp_path):
    config = tmp_path / "vem.toml"
    config.write_text("structural = 100\nvoids = 50\n[relax]\nmax_steps = 300\n")
    out = cli("generate", "vem", "--check", "--config", config, "--relax-max-steps", "400", "--voids", "60",
              "--out", tmp_path / "o").stdout
    assert "N_S = 100, N_V = 60" in out


def test_engine_and_material_take_the_keywords_of_relax():
    lattice = packlab.generate_lattice()
    engine = python_keywords("Engine", (lattice,))
    relax = python_keywords("relax", (lattice,))
    assert engine == relax - {"steps", "tolerance", "check_interval"}
    material = python_keywords("Material", ())
    assert material < engine and {"normal_stiffness", "work_of_adhesion"} <= material
    m = packlab.Material(normal_stiffness=5.0, adhesion_range=1e-9)
    assert m.normal_stiffness == 5.0 and m.adhesion_range == 1e-9 and m.damping == 0.7
