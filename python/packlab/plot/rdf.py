"""g(r) of a packing against R = r/a with the analytic references: well-stirred (eq. 10),
Willis (eq. 11-13), the Percus-Yevick contact value (eq. 13) and the full Percus-Yevick g(r)
(column ``percus_yevick`` where the CSV has it), as two panels like the
paper's Figs. 1-2: the contact region and the full range (the CSV written by
``packlab analyze rdf``, ``generate ls``, ``generate scrm`` and ``shake``). Several CSV files
(e.g. LS and SCRM) are drawn on the same axes, labelled by ``--labels``."""

from packlab.plot._common import argument, comma_list, read_csv, run, subplots


def percus_yevick_contact(c):
    return (1.0 + 0.5 * c) / (1.0 - c) ** 2


def figure(rdf_csvs, phi=None, labels=None, contact_range=(1.95, 2.25)):
    if isinstance(rdf_csvs, str):
        rdf_csvs = [rdf_csvs]
    labels = labels or [None] * len(rdf_csvs)
    fig, (ax1, ax2) = subplots(1, 2, width=9.5, gridspec_kw={"width_ratios": [1, 2]})
    data = None
    for k, (path, label) in enumerate(zip(rdf_csvs, labels)):
        data = read_csv(path)
        name = label or ("measured" if len(rdf_csvs) == 1 else path)
        for ax in (ax1, ax2):
            ax.plot(data["R"], data["g"], f"C{k}-", lw=1.0, label=name)
    r = data["R"]
    ax2.plot(r, data["well_stirred"], "k:", lw=0.8, label="well-stirred (10)")
    if phi:
        ax2.plot(r, data["willis"], "k--", lw=0.8, label="Willis (11-13)")
        if "percus_yevick" in data:
            for ax in (ax1, ax2):
                ax.plot(r, data["percus_yevick"], "-", color="0.5", lw=0.8,
                        label="Percus-Yevick g(r)" if ax is ax2 else None)
        g_py = percus_yevick_contact(phi)
        for ax in (ax1, ax2):
            ax.plot([2.0], [g_py], "kv", ms=6, label="Percus-Yevick g(2a+)" if ax is ax2 else None)
    ax1.set_xlim(*contact_range)
    ax1.set_xlabel("R = r / a")
    ax1.set_ylabel("g")
    ax1.set_title("contact")
    ax2.set_xlim(1.5, min(float(r[-1]), 8.0))
    ax2.set_ylim(0, 4)
    ax2.set_xlabel("R = r / a")
    ax2.set_title(f"g(r), c = {phi:.4g}" if phi else "g(r)")
    ax2.legend(fontsize=7, loc="upper right")
    return fig


def main(argv):
    return run("rdf", argv, figure, argument("rdf_csv", nargs="+"), argument("--phi", type=float, default=None),
               argument("--labels", type=comma_list, default=None, help="comma-separated, one per CSV"))
