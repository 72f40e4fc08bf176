#!/usr/bin/env python3
"""The adaptive rate of the dynamic compression test (`--elastic-speedup`, docs/opal.md,
"Adaptive rate"; issue #14): the FCC opals of examples/opal/run.sh (3,365 particles, the paper's
bonds; and with 3.6 nm of titania) compressed at the automatic rate throughout and with the plate
elastic_speedup times faster until the first bond breaks. E and the strength of each against the
constant-rate run, the steps and the CPU time. One more run, `paper-density100`, is the uncoated
opal at the constant automatic rate with 100 times the silica density (mass scaling): the
automatic rate is set per elastic-wave transit, so it runs the same steps to max_strain.

    adaptive_rate.py OUT_DIR DATA_CSV [--packlab packlab] [--speedups 4,10,20] [--coated-speedups 4,10]
                     [--workers 2] [--uncoated-only]

--uncoated-only runs the uncoated opal alone, at the automatic rate and at --speedups, without
the mass-scaling run (make bench: bench/run.sh, --speedups 10, about 2.5 CPU-minutes).

Runs are kept in OUT_DIR (a finished one is not run again); DATA_CSV gets one row per run:
docs/data/opal_adaptive_rate.csv. The CPU seconds are those of the process (/usr/bin/time is not
needed: resource.getrusage of the child), with `workers` runs side by side on the machine.
"""

import argparse
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))
from packlab.tables import read_table, write_table  # noqa: E402

CONFIG = os.path.join(HERE, "silica.toml")
SAMPLES = {
    # name: (pore options of `build opal` as in run.sh)
    "paper": [],
    "coated": ["--coating", "3.6e-9"],
}


def run(cmd):
    print("+", " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def build_models(out, packlab):
    packing = os.path.join(out, "fcc-packing")
    if not os.path.exists(os.path.join(packing, "packing.vtu")):
        run([packlab, "generate", "fba", "--box", "300e-9,259.81e-9,412.95e-9", "--diameter", "15e-9", "--porosity",
             "0.38", "--periodic", "xy", "--seed", "2", "--quiet", "--no-plots", "--out", packing])
    for name, extra in SAMPLES.items():
        model = os.path.join(out, name)
        if not os.path.exists(os.path.join(model, "opal.vtu")):
            run([packlab, "build", "opal", os.path.join(packing, "packing.vtu"), "--pores", "fcc", "--pore-diameter",
                 "138e-9", "--pore-spacing", "1.087", "--orientation", "111", "--quiet", *extra, "--out", model])


def compress(out, packlab, name, speedup, label=None, extra=()):
    """Runs one test (unless its report exists) and returns (report, CPU seconds or None)."""
    folder = os.path.join(out, label or f"{name}-x{speedup:g}")
    report = os.path.join(folder, "report.json")
    timing = os.path.join(folder, "cpu_seconds.txt")
    if not os.path.exists(report):
        cmd = [packlab, "test", "compress", os.path.join(out, name, "opal.vtu"), "--config", CONFIG, "--no-vtu",
               "--no-plots", "--quiet", "--elastic-speedup", f"{speedup:g}", *extra, "--out", folder]
        print("+", " ".join(cmd), flush=True)
        start = time.time()
        child = subprocess.Popen(cmd, stdout=subprocess.DEVNULL)
        _, status, usage = os.wait4(child.pid, 0)
        if status != 0:
            raise SystemExit(f"{' '.join(cmd)} failed ({status})")
        with open(timing, "w") as f:
            f.write(f"{usage.ru_utime + usage.ru_stime:.2f} {time.time() - start:.2f}\n")
    with open(report) as f:
        data = json.load(f)
    cpu = None
    if os.path.exists(timing):
        with open(timing) as f:
            cpu = float(f.read().split()[0])
    return data, cpu


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out")
    p.add_argument("data_csv")
    p.add_argument("--packlab", default="packlab")
    p.add_argument("--speedups", default="4,10,20", help="for the uncoated opal")
    p.add_argument("--coated-speedups", default="4,10", help="for the coated one (13 CPU minutes per run)")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--uncoated-only", action="store_true", help="no coated opal, no mass-scaling run")
    args = p.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    build_models(args.out, args.packlab)
    speedups = {name: [1.0] + [float(s) for s in text.split(",")]
                for name, text in (("paper", args.speedups), ("coated", args.coated_speedups))}
    # The long runs first, so that the two workers end together.
    jobs = [] if args.uncoated_only else [("coated", s, None, ()) for s in speedups["coated"]]
    jobs += [("paper", s, None, ()) for s in speedups["paper"]]
    if not args.uncoated_only:
        jobs.append(("paper", 1.0, "paper-density100", ("--density", "129700")))
    with ThreadPoolExecutor(args.workers) as pool:
        results = list(pool.map(lambda job: compress(args.out, args.packlab, *job), jobs))
    table = {k: [] for k in ("sample", "elastic_speedup", "youngs_modulus_gpa", "strength_mpa", "strain_at_peak",
                             "steps", "rolled_back_steps", "switch_strain", "broken_bonds",
                             "max_kinetic_to_strain_energy", "cpu_seconds", "modulus_change_percent",
                             "strength_change_percent", "steps_ratio", "effective_speedup",
                             "constant_rate_steps_to_switch")}
    base = {}
    strain_per_step = {}  # of the constant-rate run, from its curve (points' step, strain)
    for (name, s, label, _), (report, cpu) in zip(jobs, results):
        if s == 1.0 and label is None:
            base[name] = report
            curve = read_table(os.path.join(args.out, f"{name}-x1", "curve.csv"))
            strain_per_step[name] = (curve["strain"][2] - curve["strain"][1]) / (curve["step"][2] - curve["step"][1])
        ref = base[name]
        adaptive = report.get("adaptive_rate") or {}
        steps = report["steps"] + adaptive.get("rolled_back_steps", 0)
        table["sample"].append(label or name)
        table["elastic_speedup"].append(s)
        table["youngs_modulus_gpa"].append(report["youngs_modulus"] * 1e-9)
        table["strength_mpa"].append(report["strength"] * 1e-6)
        table["strain_at_peak"].append(report["strain_at_peak"])
        table["steps"].append(report["steps"])
        table["rolled_back_steps"].append(adaptive.get("rolled_back_steps", 0))
        switch = adaptive.get("switch_strain")
        table["switch_strain"].append(float("nan") if switch is None else switch)
        table["broken_bonds"].append(report["broken_bonds"])
        table["max_kinetic_to_strain_energy"].append(report["max_kinetic_to_strain_energy"])
        table["cpu_seconds"].append(float("nan") if cpu is None else cpu)
        table["modulus_change_percent"].append(100.0 * (report["youngs_modulus"] / ref["youngs_modulus"] - 1.0))
        table["strength_change_percent"].append(100.0 * (report["strength"] / ref["strength"] - 1.0))
        table["steps_ratio"].append(ref["steps"] / steps)
        table["effective_speedup"].append(adaptive.get("effective_speedup", 1.0))
        # Where the switch lies in the constant-rate run: the steps that the fast phase replaces.
        table["constant_rate_steps_to_switch"].append(
            float("nan") if switch is None else round(switch / strain_per_step[name]))
        print(f"{label or name} x{s:g}: E {report['youngs_modulus'] * 1e-9:.4f} GPa "
              f"({table['modulus_change_percent'][-1]:+.2f} %), strength {report['strength'] * 1e-6:.3f} MPa "
              f"({table['strength_change_percent'][-1]:+.2f} %), {steps} steps ({table['steps_ratio'][-1]:.2f}x "
              f"fewer), {table['cpu_seconds'][-1]:.1f} CPU s")
    write_table(args.data_csv, table,
                comment=f"examples/opal/adaptive_rate.py (--speedups {args.speedups} "
                + ("--uncoated-only" if args.uncoated_only else f"--coated-speedups {args.coated_speedups}")
                + f", {args.workers} runs side by side): the FCC opals of run.sh at the automatic rate (x1) and with --elastic-speedup")
    print(f"wrote {args.data_csv}")


if __name__ == "__main__":
    main()
