"""Figures of the void-expansion study of docs/vem.md, drawn from the tables that
``examples/vem/study_tables.py`` writes (``docs/data/vem_study.csv``, ``vem_curves.csv``):

* ``studies``: CN against q n^(1/3) for the n-study, against q for the size study, against
  Phi_T for the Phi_S-study, and q_i / slope for the three time-step settings;
* ``stiffness``: q_i and the slope at the inflection against K_n = k_n,V / k_n,S with the
  paper's law q_i = 0.02 ln K_n + 1.16 (K_n <= 1e-4) and its plateau (§3.4, Fig. 7-8);
* ``relax``: the relaxation study of docs/reproduction.md (``docs/data/vem_relax_study.csv``):
  slope n^1/3, q_i n^1/3, Phi_T,i and beta against the fixed number of steps per increment at
  n = 0.5, and slope n^1/3 and q_i n^1/3 against n at 50 steps, with the paper's values and scatter.

usage: python3 -m packlab.plot vem_study studies|stiffness|relax STUDY.csv [CURVES.csv] --out FILE.png"""

from packlab.plot._common import argument, read_csv, run, subplots, UsageError


def _rows(study):
    names = study["name"]
    return {name: {key: study[key][k] for key in study} for k, name in enumerate(names)}


def _curve(curves, name):
    import numpy as np

    mask = np.array([n == name for n in curves["name"]])
    return curves["q"][mask], curves["cn"][mask], curves["phi_total"][mask]


def _present(rows, names):
    """(k, name) for the names that the study has, k counting all names (colour C{k} stays put)."""
    return [(k, name) for k, name in enumerate(names) if name in rows]


def _label(ax, xlabel, ylabel, title, legend=True):
    """Axis labels and title of one panel, and its legend."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    if legend:
        ax.legend(fontsize=7)


def studies(study, curves):
    rows = _rows(study)
    fig, axes = subplots(2, 2, width=10, height=8, layout=None)
    ax = axes[0, 0]
    for k, name in _present(rows, ["n025", "n050_seed1", "n100", "n200"]):
        q, cn, _ = _curve(curves, name)
        n = rows[name]["n"]
        ax.plot(q * n ** (1 / 3), cn, "-", color=f"C{k}", lw=1, label=f"n = {n:g}")
        ax.plot([rows[name]["q_n13"]], [rows[name]["cn_i"]], "o", color=f"C{k}", ms=4)
    ax.axvline(0.82, color="k", ls=":", lw=0.8, label="paper q_i n^1/3 = 0.82")
    _label(ax, "q n^(1/3)", "CN (structural)", "n-study, N_S = 1000 (Fig. 2)")

    ax = axes[0, 1]
    for k, name in _present(rows, ["n050_seed1", "n050_ns2000", "n050_ns4000"]):
        q, cn, _ = _curve(curves, name)
        ax.plot(q, cn, "-", color=f"C{k}", lw=1, label=f"N_S = {int(rows[name]['structural'])}")
    _label(ax, "q = r_V / r_S", "CN (structural)", "size at n = 0.5")

    ax = axes[1, 0]
    for k, name in _present(rows, ["phi02", "phi03", "n050_seed1", "phi05", "phi055"]):
        _, cn, phi_total = _curve(curves, name)
        ax.plot(phi_total, cn, "-", color=f"C{k}", lw=1, label=f"Phi_S = {rows[name]['phi_s']:g}")
        ax.plot([rows[name]["phi_total_i"]], [rows[name]["cn_i"]], "o", color=f"C{k}", ms=4)
    ax.axvline(0.615, color="k", ls=":", lw=0.8, label="paper Phi_T,i = 0.615")
    _label(ax, "Phi_T = Phi_S (1 + q^3 n)", "CN (structural)", "Phi_S-study, n = 0.5 (Fig. 4)")

    ax = axes[1, 1]
    settings = [("n050_contacts02_seed", "contacts, 0.2"), ("n050_contacts04_seed", "contacts, 0.4"),
                ("n050_seed", "stiffness_sum, 0.8 (default)")]
    for k, (prefix, label) in enumerate(settings):
        qs = [rows[f"{prefix}{s}"]["q_i"] for s in (1, 2, 3) if f"{prefix}{s}" in rows]
        slopes = [rows[f"{prefix}{s}"]["slope"] for s in (1, 2, 3) if f"{prefix}{s}" in rows]
        ax.plot(qs, slopes, "o", color=f"C{k}", label=label)
    _label(ax, "q_i", "dCN/dq at q_i", "time-step rule and safety, n = 0.5, seeds 1-3")
    fig.tight_layout()
    return fig


def stiffness(study):
    import numpy as np

    rows = _rows(study)
    picked = [r for name, r in rows.items() if name.startswith("stiffness_") or name == "n050_seed1"]
    picked.sort(key=lambda r: r["kn_ratio"])
    kn = np.array([r["kn_ratio"] for r in picked])
    fig, (a, b) = subplots(1, 2, width=10, height=4, layout=None)
    a.errorbar(kn, [r["q_i"] for r in picked], yerr=[r["q_i_unc"] for r in picked], fmt="o", label="packlab, N_S = 1000")
    law = np.logspace(-7, -4, 20)
    a.plot(law, 0.02 * np.log(law) + 1.16, "k--", lw=0.8, label="paper: 0.02 ln K_n + 1.16")
    a.plot([1e-4, 1e1], [1.02, 1.02], "k:", lw=0.8, label="paper plateau ~1.02")
    a.set_xscale("log")
    _label(a, "K_n = k_n,V / k_n,S", "q_i", "void stiffness (Fig. 7)")
    b.errorbar(kn, [r["slope"] for r in picked], yerr=[r["slope_unc"] for r in picked], fmt="o")
    b.set_xscale("log")
    _label(b, "K_n = k_n,V / k_n,S", "dCN/dq at q_i", "slope at the inflection (Fig. 8)", legend=False)
    fig.tight_layout()
    return fig


def relax(study):
    from packlab.reproduction import PAPER_ROWS

    rows = list(_rows(study).values())
    fig, axes = subplots(2, 3, width=12, height=7, layout=None)
    half = [r for r in rows if abs(r["n"] - 0.5) < 1e-9]
    panels = [("slope_n13", "vem.slope_n13", "dCN/dq|_i n^1/3"), ("q_n13", "vem.q_i_n13", "q_i n^1/3"),
              ("phi_total_i", "vem.phi_ti_over_n", "Phi_T,i"), ("beta", "vem.beta", "beta (eq. 9)")]
    for ax, (column, key, label) in zip(axes.flat, panels):
        ax.plot([r["relax_max_steps"] for r in half], [r[column] for r in half], "o", label="packlab, n = 0.5, seeds 1-3")
        _paper_band(ax, PAPER_ROWS[key])
        ax.set_xscale("log")
        _label(ax, "steps per increment (fixed)", label, label + " against the relaxation", legend=column == "slope_n13")
    fifty = [r for r in rows if r["relax_max_steps"] == 50]
    for ax, (column, key, label) in zip(axes.flat[4:], panels[:2]):
        ax.plot([r["n"] for r in fifty], [r[column] for r in fifty], "o", label="packlab, 50 steps, seeds 1-3")
        _paper_band(ax, PAPER_ROWS[key])
        ax.set_xscale("log")
        _label(ax, "n = N_V / N_S", label, label + " against n at 50 steps", legend=False)
    fig.suptitle("VEM, N_S = 1000: a fixed relaxation per increment (docs/reproduction.md)")
    fig.tight_layout()
    return fig


def _paper_band(ax, paper_row):
    value, scatter = float(paper_row[3]), float(paper_row[4] or 0.0)
    ax.axhline(value, color="k", ls="--", lw=0.8, label=f"paper {paper_row[3]} ± {paper_row[4]}")
    if scatter:
        ax.axhspan(value - scatter, value + scatter, color="k", alpha=0.1)


def _draw(kind, study_csv, curves_csv):
    study = read_csv(study_csv)
    if kind == "relax":
        return relax(study)
    if kind == "studies":
        if not curves_csv:
            raise UsageError("studies needs the curves table")
        return studies(study, read_csv(curves_csv))
    return stiffness(study)


def main(argv):
    return run("vem_study", argv, _draw, argument("kind", choices=["studies", "stiffness", "relax"]), argument("study"),
               argument("curves", nargs="?"))
