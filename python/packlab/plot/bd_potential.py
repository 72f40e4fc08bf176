"""DLVO pair potential of ``packlab generate bd``: the energy in k_B T against the surface
separation (``potential.csv``), with its van der Waals and double-layer parts."""

from packlab.plot._common import argument, new_figure, read_csv, run


def figure(potential_csv):
    data = read_csv(potential_csv)
    fig, ax = new_figure()
    h = [v * 1e9 for v in data["separation_m"]]
    ax.plot(h, data["energy_kT"], "k-", label="DLVO (van der Waals + double layer)")
    ax.plot(h, data["van_der_waals_kT"], "C0--", lw=1, label="van der Waals")
    ax.plot(h, data["double_layer_kT"], "C3:", lw=1, label="double layer")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xscale("log")
    finite = [u for u, x in zip(data["energy_kT"], h) if x > 2.0]
    if finite:
        ax.set_ylim(max(min(finite) - 5, -40), max(max(finite) + 5, 5))
    ax.set_xlabel("surface separation h [nm]")
    ax.set_ylabel("U / k_B T")
    ax.set_title("DLVO pair potential")
    ax.legend(fontsize=8)
    return fig


def main(argv):
    return run("bd_potential", argv, figure, argument("potential_csv"))
