"""Distribution of bonds over their axial strain at several macroscopic strains (Fig. 7 of
bpm-inverse-opals; the ``bond_strain.csv`` of ``packlab test compress --snapshot-strains``)."""

from packlab.plot._common import argument, new_figure, read_csv, run


def figure(bond_strain_csv):
    data = read_csv(bond_strain_csv)
    fig, ax = new_figure()
    x = data["strain_bin"] * 100
    width = (x[1] - x[0]) if len(x) > 1 else 1.0
    for name, values in data.items():
        if not name.startswith("fraction_at_"):
            continue
        macro = float(name[len("fraction_at_"):])
        ax.step(x, values * 100, where="mid", label=f"sample strain {macro * 100:.2f} %")
    ax.set_xlabel("bond strain [%] (negative = compressed)")
    ax.set_ylabel(f"fraction of bonds per {width:.3g} % bin [%]")
    ax.axvline(0, color="k", lw=0.5)
    ax.legend(fontsize=8)
    ax.set_title("bond strain distribution")
    return fig


def main(argv):
    return run("bond_strain", argv, figure, argument("bond_strain_csv"))
