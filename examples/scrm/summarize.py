"""Tables and figures of examples/scrm/run_paper.sh: contact values and peaks of the averaged
RDFs against the paper's values, the jamming densities, and the PNGs shown in docs/scrm.md.
usage: /usr/bin/python3 examples/scrm/summarize.py OUT [DOCS_DIR]"""

import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))

from packlab.plot import read_csv, save  # noqa: E402
from packlab.plot import rdf as rdf_plot  # noqa: E402
from packlab.plot import rdf_partial, windows  # noqa: E402

PAPER_DROP = {"0.575": 43, "0.6": 21, "0.63": 4}


def report(path):
    with open(path) as f:
        return json.load(f)


def gap(rdf_csv, lo=2.3, hi=3.2):
    """Position of the minimum of g between the first and second shell (smoothed over 5 bins)."""
    d = read_csv(rdf_csv)
    r, g = d["R"], d["g"]
    best, where = 1e9, None
    for k in range(2, len(r) - 2):
        if lo <= r[k] <= hi:
            s = sum(g[k - 2:k + 3]) / 5
            if s < best:
                best, where = s, r[k]
    return where, best


def near_contact_max(rdf_csv, hi=2.1):
    d = read_csv(rdf_csv)
    best = max((g, r) for r, g in zip(d["R"], d["g"]) if r <= hi)
    return best[0], best[1]


def partial_gaps(csv):
    """Minima (smoothed over 5 bins) of g11 in R_11 [2.1, 2.5] and of g12, g22 in R_km [2.6, 4]."""
    d = read_csv(csv)
    out = {}
    for (k, m), (lo, hi) in {(0, 0): (2.1, 2.5), (0, 1): (2.6, 4.0), (1, 1): (2.6, 4.0)}.items():
        rows = [q for q in range(len(d["k"])) if int(d["k"][q]) == k and int(d["m"][q]) == m]
        x = [d["R_km"][q] for q in rows]
        g = [d["g"][q] for q in rows]
        best = min((sum(g[q - 2:q + 3]) / 5, x[q]) for q in range(2, len(x) - 2) if lo <= x[q] <= hi)
        out[f"g{k + 1}{m + 1}"] = best[1]
    return out


def main(out, docs):
    lines = ["## Monodisperse: contact value g(2a+) (dr = 0.01 a) and peaks", "",
             "| c | LS g(2a+) | SCRM g(2a+) | drop | paper drop | PY g(2a+) | max g near contact LS / SCRM (at R) "
             "| LS peaks R | SCRM peaks R | SCRM gap R |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for c in ("0.575", "0.6", "0.63"):
        ls = os.path.join(out, f"mono-ls-c{c}", "rdf")
        sc = os.path.join(out, f"mono-scrm-c{c}", "rdf")
        if not (os.path.exists(ls) and os.path.exists(sc)):
            continue
        rl, rs = report(os.path.join(ls, "report.json"))["results"], report(os.path.join(sc, "report.json"))["results"]
        gl, gs = rl["contact_value"], rs["contact_value"]
        where, _ = gap(os.path.join(sc, "rdf.csv"))
        ml, rml = near_contact_max(os.path.join(ls, "rdf.csv"))
        ms, rms = near_contact_max(os.path.join(sc, "rdf.csv"))
        lines.append(f"| {c} | {gl:.2f} | {gs:.2f} | {100 * (1 - gs / gl):.0f} % | {PAPER_DROP[c]} % | "
                     f"{rl['pairs'][0]['percus_yevick']:.2f} | {ml:.1f} ({rml:.2f}) / {ms:.1f} ({rms:.2f}) | "
                     f"{', '.join(f'{p:.2f}' for p in rl['peaks_R'])} | "
                     f"{', '.join(f'{p:.2f}' for p in rs['peaks_R'])} | {where:.2f} |")
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
        gaps = partial_gaps(os.path.join(out, run, "rdf", "rdf_partial.csv"))
        for p in res["pairs"]:
            name = f"g{p['k'] + 1}{p['m'] + 1}"
            lines.append(f"| {run} (P = {res['realizations']}) | {name} | {p['contact_value']:.2f} | "
                         f"{p['percus_yevick']:.2f} | {', '.join(f'{x:.2f}' for x in p['peaks_R_km'])} | "
                         f"{gaps[name]:.2f} |")
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
