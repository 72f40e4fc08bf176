#!/usr/bin/env python3
"""The M study (scrm-bimodal-packs.txt §4.2, Figs. 12-13) under the two other readings of the
shake move (docs/reproduction.md, `scrm.m_study_*`): the runs of
examples/study/scrm_mstudy_rules.toml (bimodal, c = 0.6, N = 2000, M = 3 and 60, the "freest"
rule and the one-trial Metropolis move, seeds 1-16), measured with the paper's estimator
(examples/scrm/estimators.py: K-function with every periodic image, right difference over dr =
0.01 a, bootstrap SE over the realizations). Writes

  DATA/scrm_mstudy_rules.csv   per rule, M and pair of classes: the contact value and its SE;
                               for M = 3 the paired ratio g+(M = 3) / g+(M = 60) of the same
                               seeds and its SE (the paper: 12 % between the two for g11)

usage: PYTHONPATH=python:build/python /usr/bin/python3 examples/scrm/mstudy_rules.py STUDY_OUT [DATA]"""

import os
import sys

import packlab
from packlab.studies import finished_tasks
from packlab.tables import write_table

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import estimators  # noqa: E402

PAIRS = ((0, 0), (0, 1), (1, 1))


def link_cases(out):
    """{(rule, M): case folder} with r<seed> links to the study's runs (estimators.Case reads
    r*/packing.xyz)."""
    cases = {}
    for t in finished_tasks(out):
        rule = "freest" if t["move-rule"] == "freest" else f"metropolis{t['max-trials']}"
        key = (rule, int(t["final-shakes"]))
        case = os.path.join(out, "cases", f"bi-scrm-{rule}-M{key[1]}-c0.6")
        os.makedirs(case, exist_ok=True)
        link = os.path.join(case, f"r{t['seed']}")
        if os.path.islink(link):
            os.remove(link)
        os.symlink(os.path.relpath(os.path.join(out, "runs", f"scrm-{t['task']}"), case), link)
        cases[key] = case
    return cases


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    data = argv[2] if len(argv) > 2 else os.path.join(HERE, "..", "..", "docs", "data")
    cases = {k: estimators.Case(v, packlab, pairs=PAIRS, r_max=2.2, bin_widths=(estimators.PAPER_DR,))
             for k, v in link_cases(argv[1]).items()}
    columns = ["move_rule", "final_shakes", "realizations", "pair", "contact_value", "contact_value_se",
               "ratio_to_M60", "ratio_to_M60_se"]
    rows = []
    for (rule, shakes), case in sorted(cases.items()):
        reference = cases.get((rule, 60))
        for pair in PAIRS:
            v, se = case.contact_value(pair)
            row = {"move_rule": rule, "final_shakes": shakes, "realizations": case.realizations,
                   "pair": f"g{pair[0] + 1}{pair[1] + 1}", "contact_value": v, "contact_value_se": se,
                   "ratio_to_M60": "", "ratio_to_M60_se": ""}
            if shakes != 60 and reference is not None and reference.realizations == case.realizations:
                row["ratio_to_M60"], row["ratio_to_M60_se"] = case.ratio(reference, pair, paired=True)
                if pair == (0, 0):
                    print(f"{rule}: g11(2+) M = {shakes} / M = 60 = {row['ratio_to_M60']:.4f} "
                          f"+- {row['ratio_to_M60_se']:.4f} ({case.realizations} seeds)")
            rows.append(row)
    path = os.path.join(data, "scrm_mstudy_rules.csv")
    write_table(path, {c: [r[c] for r in rows] for c in columns},
                "examples/scrm/mstudy_rules.py: bimodal SCRM (c = 0.6, N = 2000, size ratio 0.313, small/large volume "
                "0.25/0.75) with M final shakes under two other move rules; contact values by the paper's estimator "
                "(dr = 0.01 a), bootstrap SE; ratios paired over the same seeds")
    print(f"wrote {path} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
