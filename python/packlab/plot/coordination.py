"""Histogram of the number of contacts per particle, from the ``coordination.csv`` written
by ``packlab analyze``."""

from packlab.plot._common import argument, new_figure, read_csv, run


def figure(coordination_csv):
    data = read_csv(coordination_csv)
    k, fraction = data["contacts"], data["fraction"]
    fig, ax = new_figure()
    ax.bar(k, fraction, width=0.8, color="C0")
    total = sum(data["particles"])
    mean = sum(k * data["particles"]) / total if total else 0.0
    ax.axvline(mean, color="C3", ls="--", lw=1.2, label=f"mean {mean:.3f}")
    ax.set_xlabel("contacts per particle")
    ax.set_ylabel("fraction of particles")
    ax.legend(fontsize=8)
    ax.set_title(f"coordination ({int(total)} particles)")
    return fig


def main(argv):
    return run("coordination", argv, figure, argument("coordination_csv"))
