"""Tables and figures of examples/scrm/run_paper.sh: contact values and peaks of the averaged
RDFs against the paper's values, the jamming densities, and the PNGs shown in docs/scrm.md; the
paper's estimators over the realizations (examples/scrm/estimators.py) into
docs/data/scrm_contact_values.csv (contact value against the bin width), scrm_mono.csv and
scrm_bimodal.csv, which python/packlab/reproduction.py reads for the scrm.* rows.
usage: PYTHONPATH=build/python:python /usr/bin/python3 examples/scrm/summarize.py OUT [DOCS_DIR]"""

import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "build", "python"))  # the compiled module (packlab.Rdf)

from packlab.plot import read_csv, save  # noqa: E402
from packlab.plot import rdf as rdf_plot  # noqa: E402
from packlab.plot import rdf_partial, windows  # noqa: E402

sys.path.insert(0, HERE)
import estimators  # noqa: E402

C_VALUES = ("0.575", "0.6", "0.63")
# Bimodal g11 peaks (paper §4.2, Fig. 9) and the search interval around each; gaps of g11 (2 + lambda)
# and of g12, g22 (1/lambda, "observed as 3.3").
G11_PEAKS = {"2.64": (2.5, 2.8), "3.464": (3.3, 3.62), "4.0": (3.85, 4.2), "4.54": (4.35, 4.75)}
GAPS = {(0, 0): (2.1, 2.5), (0, 1): (2.6, 4.0), (1, 1): (2.6, 4.0)}


def write_csv(path, columns, rows):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(",".join(columns) + "\n")
        for r in rows:
            f.write(",".join(estimators.fmt(r.get(c, "")) for c in columns) + "\n")
    os.replace(tmp, path)


def mono_cases(out):
    """case folder name -> (c, method, rule, growth rate, M, blocks per cycle)."""
    cases = {}
    for c in C_VALUES:
        cases[f"mono-ls-c{c}"] = (c, "ls", "", 0.02, "", "")
        cases[f"mono-scrm-c{c}"] = (c, "scrm", "metropolis (N_sh = 150)", 0.02, 10, 5)
        cases[f"mono-scrm-freest-c{c}"] = (c, "scrm", "freest (N_sh = 150)", 0.02, 10, 5)
        cases[f"mono-scrm-metropolis1-c{c}"] = (c, "scrm", "metropolis (N_sh = 1)", 0.02, 10, 5)
    for c in C_VALUES:  # examples/study/scrm_diagnosis.toml
        for g in ("0.005", "0.1"):
            cases[f"diag-ls-G{g}-c{c}"] = (c, "ls", "", float(g), "", "")
            cases[f"diag-scrm-G{g}-c{c}"] = (c, "scrm", "metropolis (N_sh = 150)", float(g), 10, 5)
        cases[f"diag-scrm-G0.02-M60-c{c}"] = (c, "scrm", "metropolis (N_sh = 150)", 0.02, 60, 5)
        cases[f"diag-scrm-G0.02-bpc1-c{c}"] = (c, "scrm", "metropolis (N_sh = 150)", 0.02, 10, 1)
    return {k: v for k, v in cases.items() if os.path.isdir(os.path.join(out, k))}


def ls_reference(name, c):
    """The LS case whose contact value a case's drop is taken against: LS at the same growth rate."""
    for rate in ("0.005", "0.1"):
        if name.startswith(f"diag-scrm-G{rate}-"):
            return f"diag-ls-G{rate}-c{c}"
    return f"mono-ls-c{c}"


def mono_data(out, data):
    """docs/data/scrm_contact_values.csv and scrm_mono.csv from the monodisperse cases."""
    import packlab
    contact_rows, mono_rows, measured = [], [], {}
    for name, (c, method, rule, rate, shakes, bpc) in mono_cases(out).items():
        case = estimators.Case(os.path.join(out, name), packlab)
        measured[name] = case
        base = {"case": name, "c": c, "method": method, "move_rule": rule, "growth_rate": rate, "final_shakes": shakes,
                "blocks_per_cycle": bpc, "realizations": case.realizations, "particles": case.particles}
        for dr in estimators.BIN_WIDTHS:
            v, se = case.contact_value(dr=dr)
            contact_rows.append({**base, "dr": dr, "contact_value": v, "contact_value_se": se})
        v, se = case.contact_value()
        top, top_r, top_se = case.near_contact_max()
        gap_r, gap_se = case.extremum((-1, -1), 2.3, 3.2, "min")
        p2, p2_se = case.extremum((-1, -1), 3.3, 3.7, "max")
        p3, p3_se = case.extremum((-1, -1), 3.85, 4.2, "max")
        wm, wm_se = case.window_mean_se()
        wv, wv_se = case.window_variance_se()
        mono_rows.append({**base, "contact_value": v, "contact_value_se": se, "max_near_contact": top,
                          "max_near_contact_se": top_se, "max_near_contact_R": top_r, "gap_R": gap_r, "gap_R_se": gap_se, "peak_2sqrt3_R": p2,
                          "peak_2sqrt3_R_se": p2_se, "peak_4_R": p3, "peak_4_R_se": p3_se, "window_mean": wm,
                          "window_mean_se": wm_se, "window_variance": wv, "window_variance_se": wv_se})
    head = ["case", "c", "method", "move_rule", "growth_rate", "final_shakes", "blocks_per_cycle", "realizations",
            "particles"]
    if contact_rows:
        write_csv(os.path.join(data, "scrm_contact_values.csv"), head + ["dr", "contact_value", "contact_value_se"],
                  contact_rows)
        write_csv(os.path.join(data, "scrm_mono.csv"),
                  head + ["contact_value", "contact_value_se", "max_near_contact", "max_near_contact_se", "max_near_contact_R", "gap_R",
                          "gap_R_se", "peak_2sqrt3_R", "peak_2sqrt3_R_se", "peak_4_R", "peak_4_R_se", "window_mean",
                          "window_mean_se", "window_variance", "window_variance_se"], mono_rows)
    return measured, contact_rows, {r["case"]: r for r in mono_rows}


def bimodal_data(out, data):
    """docs/data/scrm_bimodal.csv: per bimodal case and pair of classes, the contact value (with the
    paired ratio to M = 60 for the M study), the first gap and, for g11, the paper's four peaks."""
    import packlab
    cases = {"bi-ls-c0.6": ("ls", 2000, ""), "bi-scrm-c0.6": ("scrm", 2000, 10), "bi-scrm-M3-c0.6": ("scrm", 2000, 3),
             "bi-scrm-M30-c0.6": ("scrm", 2000, 30), "bi-scrm-M60-c0.6": ("scrm", 2000, 60),
             "bi7000-scrm-c0.6": ("scrm", 7000, 3), "bi-scrm-freest-M60-c0.6": ("scrm", 2000, 60),
             "bi-scrm-metropolis1-M60-c0.6": ("scrm", 2000, 60)}
    pairs = ((0, 0), (0, 1), (1, 1))
    measured = {name: estimators.Case(os.path.join(out, name), packlab, pairs=pairs, r_max=12.0,
                                      bin_widths=(estimators.PAPER_DR,))
                for name in cases if os.path.isdir(os.path.join(out, name))}
    rows = []
    for name, case in measured.items():
        method, n, shakes = cases[name]
        for pair in pairs:
            v, se = case.contact_value(pair)
            row = {"case": name, "method": method, "particles": case.particles, "final_shakes": shakes,
                   "realizations": case.realizations, "pair": f"g{pair[0] + 1}{pair[1] + 1}", "contact_value": v,
                   "contact_value_se": se}
            reference = measured.get("bi-scrm-M60-c0.6")
            if reference is not None and name.startswith("bi-scrm-M") and case.realizations == reference.realizations:
                row["ratio_to_M60"], row["ratio_to_M60_se"] = case.ratio(reference, pair, paired=True)
            row["gap_R"], row["gap_R_se"] = case.extremum(pair, *GAPS[pair], "min")
            if pair == (0, 0):
                for label, (lo, hi) in G11_PEAKS.items():
                    row[f"peak_{label}"], row[f"peak_{label}_se"] = case.extremum(pair, lo, hi, "max")
            rows.append(row)
    if rows:
        columns = ["case", "method", "particles", "final_shakes", "realizations", "pair", "contact_value",
                   "contact_value_se", "ratio_to_M60", "ratio_to_M60_se", "gap_R", "gap_R_se"]
        for label in G11_PEAKS:
            columns += [f"peak_{label}", f"peak_{label}_se"]
        write_csv(os.path.join(data, "scrm_bimodal.csv"), columns, rows)
    return {(r["case"], r["pair"]): r for r in rows}


def contact_vs_dr_figure(contact_rows, path):
    """g+(2a) against the bin width, per c and case: the paper's claim is a flat line."""
    from packlab.plot._common import subplots
    fig, axes = subplots(1, 3, width=10.0, height=3.4)
    styles = {"ls": ("LS (CRM)", "k", "o"), "metropolis (N_sh = 150)": ("SCRM, paper's rule", "C0", "s"),
              "freest (N_sh = 150)": ("SCRM, freest direction", "C3", "^"),
              "metropolis (N_sh = 1)": ("SCRM, Metropolis N_sh = 1", "C2", "v")}
    for ax, c in zip(axes, C_VALUES):
        for key, (label, color, marker) in styles.items():
            rows = [r for r in contact_rows if r["c"] == c and r["growth_rate"] == 0.02 and r["final_shakes"] in (10, "")
                    and r["blocks_per_cycle"] in (5, "") and (r["method"] == key or r["move_rule"] == key)]
            if not rows:
                continue
            ax.errorbar([r["dr"] for r in rows], [r["contact_value"] for r in rows],
                        yerr=[r["contact_value_se"] for r in rows], color=color, marker=marker, ms=4, label=label)
        ax.set_xscale("log")
        ax.set_xlabel("bin width dr / a")
        ax.set_title(f"c = {c}")
    axes[0].set_ylabel("g+(2a)")
    axes[0].legend(fontsize=7)
    save(fig, path)



PAPER_DROP = {"0.575": 43, "0.6": 21, "0.63": 4}


def report(path):
    with open(path) as f:
        return json.load(f)


def main(out, docs):
    data = os.path.join(docs, "data")
    mono, contact_rows, mono_rows = mono_data(out, data)
    if contact_rows:
        contact_vs_dr_figure(contact_rows, os.path.join(docs, "img", "scrm_contact_vs_dr.png"))
    bimodal_rows = bimodal_data(out, data)
    lines = ["## Monodisperse: contact value g(2a+) (dr = 0.01 a), SE over the realizations", "",
             "| case | P | g(2a+) | drop vs LS | paper drop | max g near contact (at R) | gap R | window variance |",
             "|---|---|---|---|---|---|---|---|"]
    for name, case in mono.items():
        row = mono_rows[name]
        c = row["c"]
        ls = mono.get(ls_reference(name, c))
        drop = ""
        if ls is not None and row["method"] == "scrm":
            ratio, rse = case.ratio(ls)
            drop = f"{100 * (1 - ratio):.1f} ± {100 * rse:.1f} %"
        lines.append(f"| {name} | {row['realizations']} | {row['contact_value']:.2f} ± {row['contact_value_se']:.2f} | "
                     f"{drop} | {PAPER_DROP[c]} % | {row['max_near_contact']:.2f} ({row['max_near_contact_R']:.2f}) | "
                     f"{row['gap_R']:.2f} ± {row['gap_R_se']:.2f} | "
                     f"{row['window_variance']:.3f} ± {row['window_variance_se']:.3f} |")
    for c in C_VALUES:
        ls = os.path.join(out, f"mono-ls-c{c}", "rdf")
        sc = os.path.join(out, f"mono-scrm-c{c}", "rdf")
        if not (os.path.exists(ls) and os.path.exists(sc)):
            continue
        rl, rs = report(os.path.join(ls, "report.json"))["results"], report(os.path.join(sc, "report.json"))["results"]
        fig = rdf_plot.figure([os.path.join(ls, "rdf.csv"), os.path.join(sc, "rdf.csv")], float(c),
                              [f"LS (CRM), P = {rl['realizations']}", f"SCRM, P = {rs['realizations']}"])
        save(fig, os.path.join(docs, f"scrm-mono-c{c}.png"))
        fig = windows.figure([os.path.join(ls, "windows.csv"), os.path.join(sc, "windows.csv")], ["LS (CRM)", "SCRM"])
        save(fig, os.path.join(docs, f"scrm-windows-c{c}.png"))
    lines += ["", "## Bimodal (size ratio 0.313, volume ratio 0.333, c = 0.6): partial RDFs", "",
              "| run | pair | g(sigma+) | PY | peaks R_km | first gap R_km |", "|---|---|---|---|---|---|"]
    for run in ("bi-ls-c0.6", "bi-scrm-c0.6", "bi7000-scrm-c0.6"):
        path = os.path.join(out, run, "rdf", "report.json")
        if not os.path.exists(path):
            continue
        res = report(path)["results"]
        for p in res["pairs"]:
            name = f"g{p['k'] + 1}{p['m'] + 1}"
            gap_r = bimodal_rows.get((run, name), {}).get("gap_R", float("nan"))
            lines.append(f"| {run} (P = {res['realizations']}) | {name} | {p['contact_value']:.2f} | "
                         f"{p['percus_yevick']:.2f} | {', '.join(f'{x:.2f}' for x in p['peaks_R_km'])} | "
                         f"{gap_r:.2f} |")
    parts = [os.path.join(out, r, "rdf", "rdf_partial.csv") for r in ("bi-ls-c0.6", "bi-scrm-c0.6", "bi7000-scrm-c0.6")]
    have = [p for p in parts if os.path.exists(p)]
    if have:
        labels = [p.split(os.sep)[-3] for p in have]
        save(rdf_partial.figure(have, labels, 10.0), os.path.join(docs, "scrm-bimodal-partial.png"))
    lines += ["", "## Simple cubic lattice: shell count at R = 2", "", "| dR | I(2) | g+(2, dR) | paper g+ |",
              "|---|---|---|---|"]
    paper = {"0.1": 9.55, "0.01": 95.5, "0.005": 190.9, "0.003": 318}
    for dr in ("0.1", "0.01", "0.005", "0.003"):
        d = os.path.join(out, f"sc-dr{dr}")
        if not os.path.exists(d):
            continue
        t = read_csv(os.path.join(d, "rdf.csv"))
        k = min(range(len(t["R"])), key=lambda q: abs(t["R"][q] - 2.0))
        g = report(os.path.join(d, "report.json"))["results"]["contact_value"]
        lines.append(f"| {dr} | {t['I'][k]:.6g} | {g:.4g} | {paper[dr]} |")
    lines += ["", "## Fast compression of 10,000 spheres to jamming (reduced pressure 1e12)", "",
              "| G | phi_J | collisions | LS seconds | collisions/s | events/s |", "|---|---|---|---|---|---|"]
    for g in ("0.02", "0.04", "0.1", "0.3", "1", "3"):
        path = os.path.join(out, f"jam-G{g}", "report.json")
        if not os.path.exists(path):
            continue
        r = report(path)["results"]
        lines.append(f"| {g} | {r['volume_fraction']:.4f} | {r['collisions']} | {r['ls_seconds']:.1f} | "
                     f"{r['collisions_per_second']:.3g} | {r['events_per_second']:.3g} |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else os.path.join(HERE, "..", "..", "docs"))
