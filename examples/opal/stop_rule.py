#!/usr/bin/env python3
"""Where the quasi-static compression's stop rules end a run (docs/static-solver.md,
"Uniaxial compression"): from the `curve.csv` of a static `test compress` run (one point per
break: the envelope), the peak and its break, the last point, and the break at which each rule
would have stopped the run had it been run to the end of that curve with `stop_drop`:

  past the peak  the stress after a break below stop_drop x peak at a strain >= the peak's
  bound          max_strain x the stress per unit strain below stop_drop x peak (no later point
                 can come back above it: the stress per unit strain never rises)

and the peak the run would have reported had it stopped where the past-the-peak rule first holds
(below the curve's peak where the stress climbs past it again later: a stop_drop too close to 1).

It follows the loop of src/packlab/mechanics/static_compression.cpp: the point after break i lies
on the network after i break events, and the test after break i compares that network's stress
per unit strain, at the last break's strain, with the peak of the points up to i.

usage: stop_rule.py [--stop-drop F] [--max-strain E] OUT RUN_DIR...   (one row per run into OUT,
       a CSV; defaults 0.85 and 0.06, examples/study/opal_porosity_paper.toml and silica.toml)"""

import argparse
import csv
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))
from packlab.tables import write_table  # noqa: E402


def stops(strain, stress, stop_drop, max_strain):
    """(peak, its point, first point where the past-the-peak rule holds, the same for the bound,
    the peak of the points up to the first), points as indices of the curve (None where a rule
    never holds within it)."""
    peak, at_peak, strain_at_peak = 0.0, 0, 0.0
    past, bound, peak_at_past = None, None, None
    for i in range(1, len(strain) - 1):
        if stress[i] > peak:
            peak, at_peak, strain_at_peak = stress[i], i, strain[i]
        per_strain = stress[i + 1] / strain[i + 1]
        if past is None and strain[i] >= strain_at_peak and strain[i] * per_strain < stop_drop * peak:
            past, peak_at_past = i, peak
        if bound is None and max_strain * per_strain < stop_drop * peak:
            bound = i
        if past is not None and bound is not None:
            break
    return peak, at_peak, past, bound, peak_at_past


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--stop-drop", type=float, default=0.85)
    parser.add_argument("--max-strain", type=float, default=0.06)
    parser.add_argument("out")
    parser.add_argument("runs", nargs="+")
    args = parser.parse_args(argv[1:])
    columns = ["run", "points", "broken_bonds", "peak_mpa", "peak_break", "strain_at_peak", "last_strain",
               "last_stress_over_peak", "stop_past_the_peak_break", "stop_bound_break", "peak_mpa_at_past_stop"]
    table = {c: [] for c in columns}
    for run in args.runs:
        with open(os.path.join(run, "curve.csv")) as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
        strain = [float(r["strain"]) for r in rows]
        stress = [float(r["stress"]) for r in rows]
        broken = [int(float(r["broken_bonds"])) for r in rows]
        peak, at_peak, past, bound, peak_at_past = stops(strain, stress, args.stop_drop, args.max_strain)
        values = [os.path.basename(os.path.normpath(run)), len(rows), broken[-1], peak * 1e-6, broken[at_peak],
                  strain[at_peak], strain[-1], stress[-1] / peak,
                  broken[past] if past is not None else "", broken[bound] if bound is not None else "",
                  peak_at_past * 1e-6 if past is not None else ""]
        for c, v in zip(columns, values):
            table[c].append(v)
        print(f"{values[0]}: peak {peak * 1e-6:.1f} MPa at break {broken[at_peak]}; past-the-peak rule at break "
              f"{values[8] or '-'}, bound at break {values[9] or '-'} of {broken[-1]}")
    write_table(args.out, table, f"examples/opal/stop_rule.py --stop-drop {args.stop_drop:g} --max-strain "
                f"{args.max_strain:g}: where each stop rule of the static compression ends these runs' curves")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
