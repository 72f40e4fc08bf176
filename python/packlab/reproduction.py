"""The reproduction table of the four papers (docs/reproduction.md): one row per headline number,
the paper's value beside packlab's, collected from the data files under docs/data that the study
scripts write, and rendered into docs/reproduction.md.

    python3 -m packlab.reproduction collect [DATA] [--out CSV]   # DATA/*.csv -> DATA/reproduction.csv
    python3 -m packlab.reproduction render CSV MD                # the tables between the markers of MD

Columns of the CSV: key, paper, quantity, source (equation / table / figure), paper_value,
paper_scatter (empty where the paper gives none), packlab_value, packlab_sd (SD over the
realizations; for a value read off a curve averaged over the realizations, as the SCRM paper's
are, the standard error of that average), realizations, particles, paper_particles, within, note.

**The rule for ``within``** (`within`): |packlab - paper| <= sqrt(s_paper^2 + s_packlab^2), with
s_paper the paper's stated scatter or, where it gives none, half a unit of the last digit it
prints, and s_packlab packlab_sd (0 for one realization). "yes" / "no"; "n/a" where packlab has
no value yet or the paper prints no number; "bound" rows (the paper gives an upper bound) are
"yes" when packlab's value minus its SD lies below it."""

import argparse
import csv
import math
import os
import statistics
import sys

from packlab.plot.bd_table2 import PAPER as BD_TABLE2
from packlab.tables import atomic_output

COLUMNS = ["key", "paper", "quantity", "source", "paper_value", "paper_scatter", "packlab_value", "packlab_sd",
           "realizations", "particles", "paper_particles", "within", "note"]

# doh-elastic-properties Table 2, VEM rows: N_V -> (a, C, G'_p [MPa], its SD over six orientations [MPa]).
DOH_TABLE2_VEM = {1000: (0.594, 4.68, 1.73, 0.383), 2000: (0.521, 4.71, 1.83, 0.136), 4000: (0.467, 4.69, 1.62, 0.190),
                  8000: (0.418, 4.69, 1.32, 0.237), 13000: (0.399, 4.69, 1.32, 0.267), 16000: (0.392, 4.61, 1.17, 0.231)}

VEM, DOH, OPAL = "vem-void-expansion-method", "doh-elastic-properties", "bpm-inverse-opals"
SCRM = "scrm-bimodal-packs"
# scrm-bimodal-packs §4.2, Fig. 9: the peaks of g11 of the bimodal pack (size ratio 0.313).
SCRM_G11_PEAKS = ("2.64", "3.464", "4.0", "4.54")


def _paper_rows():
    """key -> (paper, quantity, source, paper_value as printed, paper_scatter as printed, paper_particles)."""
    rows = {
        "vem.q_i_n13": (VEM, "q_i n^1/3 (mean over n)", "eq. 4, Fig. 2", "0.82", "0.01", "8000"),
        "vem.slope_n13": (VEM, "dCN/dq|_i n^1/3 (mean over n)", "eq. 6, Fig. 2", "9.16", "0.68", "8000"),
        "vem.phi_ti_over_n": (VEM, "Phi_T,i over n", "eq. 5, §3.1", "0.623", "0.009", "8000"),
        "vem.phi_ti_over_phis": (VEM, "Phi_T,i over Phi_S = 0.2-0.55 (n = 0.5)", "eq. 5, §3.2", "0.615", "0.005", "4000"),
        "vem.beta": (VEM, "beta of CN - CN_i = A (Phi_T - Phi_T,i)^beta", "eq. 9, Fig. 5", "0.37", "0.04", "8000"),
        "vem.eq10_kn_1e-6": (VEM, "q_i at K_n = 1e-6 (eq. 10: 0.02 ln K_n + 1.16)", "eq. 10, Fig. 7", "0.884", "", "8000"),
        "vem.eq10_kn_1e-5": (VEM, "q_i at K_n = 1e-5 (eq. 10)", "eq. 10, Fig. 7", "0.930", "", "8000"),
        "vem.eq10_kn_1e-4": (VEM, "q_i at K_n = 1e-4 (eq. 10)", "eq. 10, Fig. 7", "0.976", "", "8000"),
        "vem.plateau": (VEM, "q_i for K_n > 1e-4 (plateau)", "§3.4, Fig. 7", "1.022", "", "8000"),
        "vem.kink_kn": (VEM, "K_n^c where eq. 10 meets the plateau", "§3.4, Fig. 7", "5.4e-4", "", "8000"),
        "vem.eq11_slope": (VEM, "exponent b of dCN/dq|_i = A K_n^b (K_n <= 1e-4)", "eq. 11, Fig. 8", "0.2", "", "8000"),
    }
    for nv, (a, c, gp, sd) in DOH_TABLE2_VEM.items():
        rows[f"doh.a_nv{nv}"] = (DOH, f"DOH parameter a, VEM N_V = {nv}", "Table 2, eq. 6", f"{a:g}", "", "8000")
        rows[f"doh.c_nv{nv}"] = (DOH, f"coordination C, VEM N_V = {nv}", "Table 2", f"{c:g}", "", "8000")
        rows[f"doh.gp_nv{nv}"] = (DOH, f"G'_p [MPa], VEM N_V = {nv}", "Table 2", f"{gp:g}", f"{sd:g}", "8000")
    rows["doh.eq7_a0"] = (DOH, "a0 of G'_p = C (a - a0)^beta (VEM + BD)", "eq. 7, Fig. 6", "0.373", "0.001", "8000")
    rows["doh.eq7_beta"] = (DOH, "beta of eq. 7 (VEM + BD)", "eq. 7, Fig. 6", "0.187", "0.032", "8000")
    rows["doh.phase_angle"] = (DOH, "phase angle delta [rad], upper bound", "§3.1", "< 3.1e-4", "", "8000")
    for mv, (a, c, gp, sd) in BD_TABLE2.items():
        rows[f"doh.bd_a_psi{mv}"] = (DOH, f"DOH parameter a, BD psi_0 = {mv} mV", "Table 2, eq. 6", f"{a:g}", "", "8000")
        rows[f"doh.bd_c_psi{mv}"] = (DOH, f"coordination C, BD psi_0 = {mv} mV", "Table 2", f"{c:g}", "", "8000")
        rows[f"doh.bd_gp_psi{mv}"] = (DOH, f"G'_p [MPa], BD psi_0 = {mv} mV", "Table 2", f"{gp:g}", f"{sd:g}", "8000")
    rows["doh.ratio_he_ho"] = (DOH, "G'_p(15 mV) / G'_p(0 mV)", "§3.1, Fig. 5", "3.4", "", "8000")
    # bpm-inverse-opals §4 (Fig. 14): random pores, porosity 0.39-0.63, five samples each; the
    # 0.39 samples hold about 3.4 million particles.
    rows["opal.porosity_E_049"] = (OPAL, "E at porosity 0.49 [GPa], paper's bonds", "§4, Fig. 14", "6.3", "", "3.4e6")
    rows["opal.porosity_E_063"] = (OPAL, "E at porosity 0.63 [GPa], paper's bonds", "§4, Fig. 14", "3.3", "", "3.4e6")
    rows["opal.porosity_strength_049"] = (OPAL, "strength at porosity 0.49 [MPa]", "§4, Fig. 14", "92.9", "", "3.4e6")
    rows["opal.porosity_strength_063"] = (OPAL, "strength at porosity 0.63 [MPa]", "§4, Fig. 14", "46.7", "", "3.4e6")
    rows["opal.eq25_E0"] = (OPAL, "E0 of E = E0 (1 - eps)^m [GPa]", "eq. 25", "22.06", "", "3.4e6")
    rows["opal.eq25_m"] = (OPAL, "m of eq. 25", "eq. 25", "1.92", "", "3.4e6")
    rows["opal.eq24_b"] = (OPAL, "b of E = E0 exp(-b eps) (E0 of eq. 25)", "eq. 24", "2.99", "", "3.4e6")
    rows["opal.eq26_a"] = (OPAL, "sigma0 of strength = sigma0 exp(-b eps) [MPa]", "eq. 26", "576.3", "", "3.4e6")
    rows["opal.eq26_b"] = (OPAL, "b of eq. 26", "eq. 26", "3.85", "", "3.4e6")
    # The same rows from the porosity samples at D/d = 5.1, 6.7 and 9.2, extrapolated to the
    # paper's D/d = 51 (examples/opal/porosity_resolution.py).
    for key, base in (("porosity_E_049", "6.3"), ("porosity_E_063", "3.3"), ("porosity_strength_049", "92.9"),
                      ("porosity_strength_063", "46.7"), ("eq25_E0", "22.06"), ("eq25_m", "1.92"), ("eq24_b", "2.99"),
                      ("eq26_b", "3.85")):
        paper, quantity, source, value, scatter, paper_particles = rows[f"opal.{key}"]
        rows[f"opal.{key}_dd51"] = (paper, quantity + ", extrapolated to D/d = 51", source, value, scatter,
                                    paper_particles)
    # bpm-inverse-opals §2.1 and §3: the FCC opal of 8.05 um^2 x 2.01 um (80,000 particles and
    # 843,000 bonds per um^3: 1.3 million particles) with the calibrated bonds (6.53 GPa, 94.3
    # MPa), the pore-free bulk (Table 1, eq. 20) and the 20 nm titania coating (§4, Fig. 15).
    rows["opal.fba_porosity"] = (OPAL, "porosity of the initial force-biased packings", "§2.1", "0.38", "", "")
    rows["opal.coordination"] = (OPAL, "bonds per particle of the FCC opal model (\"average coordination number\")",
                                 "§2.1", "10.5", "", "1.3e6")
    rows["opal.E_paper_bonds"] = (OPAL, "E of the FCC opal [GPa], paper's bonds, largest D/d run", "§3", "1.7", "",
                                  "1.3e6")
    rows["opal.strength_paper_bonds"] = (OPAL, "strength of the FCC opal [MPa], paper's bonds, largest D/d run", "§3",
                                         "41.1", "", "1.3e6")
    rows["opal.size_study_E_dd51"] = (OPAL, "E of the FCC opal [GPa] extrapolated to the paper's D/d = 51", "§3",
                                      "1.7", "", "1.3e6")
    rows["opal.size_study_strength_dd51"] = (OPAL, "strength of the FCC opal [MPa] extrapolated to D/d = 51", "§3",
                                             "41.1", "", "1.3e6")
    rows["opal.K_E"] = (OPAL, "K_E = E_macro / E_b of the pore-free sample", "eq. 20, Table 1", "3.35", "", "")
    rows["opal.bulk_strength"] = (OPAL, "strength of the pore-free sample [MPa]", "§3, Table 1", "601", "", "")
    # The coatings (§4, Fig. 9): the text prints numbers for the 20 nm coating only (Fig. 15's
    # discussion); Fig. 9 plots the 10 and 34 nm ones, whose values are not in the text ("n/a").
    for nm, modulus, strength in (("10", "", ""), ("20", "5.96", "249"), ("34", "", "")):
        source = "§4, Fig. 15" if nm == "20" else "§4, Fig. 9"
        rows[f"opal.coating{nm}_E"] = (OPAL, f"E of the opal with {nm} nm titania [GPa], paper's bonds", source,
                                       modulus, "", "2.5e6")
        rows[f"opal.coating{nm}_strength"] = (OPAL, f"strength of the opal with {nm} nm titania [MPa]", source,
                                              strength, "", "2.5e6")
    # scrm-bimodal-packs §4 (N = 2000, P = 50-80 realizations, dr = 0.01 a, M = 10 global shakes).
    for c, key, drop in (("0.575", "c0575", "43"), ("0.6", "c060", "21"), ("0.63", "c063", "4")):
        rows[f"scrm.g2a_drop_{key}"] = (SCRM, f"drop of g(2a+) under shaking at c = {c} [%]", "§4.1, Figs. 1-2", drop,
                                        "", "2000")
    rows["scrm.gmax_change_c060"] = (SCRM, "max of g near contact, SCRM / LS, c = 0.6 (\"the CRM's peaks are always "
                                     "greater\")", "§4.1", "< 1", "", "2000")
    rows["scrm.dr_015_to_010"] = (SCRM, "change of g(2a+) from dr = 0.015 a to 0.01 a, SCRM c = 0.575 [%]", "§4.1",
                                  "3", "", "2000")
    for c, key in (("0.575", "c0575"), ("0.6", "c060"), ("0.63", "c063")):
        rows[f"scrm.mono_gap_{key}"] = (SCRM, f"first gap of g, SCRM c = {c} [R = r/a] (\"2.75a-2.85a\")",
                                        "§4.1, Figs. 1-2", "2.8", "0.05", "2000")
    rows["scrm.window_variance_ls"] = (SCRM, "variance of the window counts n_h (R_h = 2.5), LS, c = 0.6",
                                       "§4.1, Fig. 4", "", "", "2000")
    # Fig. 4 shows fewer windows with extreme counts after shaking, but no number: "n/a", and the
    # note says whether packlab sees a reduction.
    rows["scrm.window_variance_scrm"] = (SCRM, "window-count variance SCRM / LS, c = 0.6 (the paper: shaking trims "
                                         "the extreme counts)", "§4.1, Fig. 4", "", "", "2000")
    rows["scrm.bimodal_g11_drop"] = (SCRM, "drop of g11(2+) under shaking, bimodal c = 0.6 [%]", "§4.2, Fig. 8", "25",
                                     "", "2000")
    for peak in SCRM_G11_PEAKS:
        rows[f"scrm.bimodal_r11_peak_{peak}"] = (SCRM, f"peak of g11 near R11 = {peak}, SCRM", "§4.2, Fig. 9", peak,
                                                 "", "2000")
    rows["scrm.bimodal_gap_g11"] = (SCRM, "first gap of g11 [R11] (2 + lambda)", "§4.2, Fig. 9", "2.3", "", "2000")
    rows["scrm.bimodal_gap_g12"] = (SCRM, "first gap of g12 [R12] (1/lambda, \"observed as 3.3\")", "§4.2, Fig. 10",
                                    "3.3", "", "2000")
    rows["scrm.bimodal_gap_g22"] = (SCRM, "first gap of g22 [R22] (1/lambda, \"observed as 3.3\")", "§4.2, Fig. 11",
                                    "3.3", "", "2000")
    rows["scrm.m_study_g11_m3_vs_m60"] = (SCRM, "g11(2+) of M = 3 against M = 60 global shakes [%]", "§4.2, Figs. 12-13",
                                          "12", "", "2000")
    rows["scrm.m_study_g11_m30_vs_m60"] = (SCRM, "g11(2+) of M = 30 against M = 60 [%]", "§4.2", "< 0.2", "", "2000")
    rows["scrm.m_study_n7000"] = (SCRM, "g11(2+) of N = 7000, M = 3 against N = 2000, M = 60 [%] (\"close\")",
                                  "§4.2, Figs. 12-13", "", "", "7000")
    return rows


PAPER_ROWS = _paper_rows()


def half_last_digit(printed):
    """Half a unit of the last digit of a number as printed ("0.884" -> 0.0005, "5.4e-4" -> 0.05e-4)."""
    mantissa, _, exponent = printed.lower().partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 0.5 * 10.0 ** (-decimals) * 10.0 ** (int(exponent) if exponent else 0)


def within(paper_value, paper_scatter, value, sd):
    """The rule of the module docstring: "yes", "no" or "n/a"."""
    if value is None or (isinstance(value, float) and math.isnan(value)) or not paper_value:
        return "n/a"
    if paper_value.startswith("<"):  # a bound: within when packlab's value is below it by its SD
        return "yes" if abs(value) - (sd or 0.0) < float(paper_value[1:]) else "no"
    s_paper = float(paper_scatter) if paper_scatter else half_last_digit(paper_value)
    # (1 + 1e-9): a difference equal to the bound in decimal is not lost to binary rounding.
    return "yes" if abs(value - float(paper_value)) <= math.hypot(s_paper, sd or 0.0) * (1 + 1e-9) else "no"


def read_table(path):
    """A CSV under docs/data as a list of dicts (``#`` comment lines skipped); [] if missing."""
    if not os.path.isfile(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def mean_sd(values):
    values = [float(v) for v in values]
    if not values:
        return None, None
    return statistics.mean(values), (statistics.stdev(values) if len(values) > 1 else 0.0)


def _ours(value, sd, realizations, particles, note):
    return {"packlab_value": value, "packlab_sd": sd, "realizations": realizations, "particles": particles, "note": note}


def vem_values(data):
    """The VEM paper's rows: the n-series of vem_doh_ns8000.csv (paper size, end point stage3)
    and the Phi_S-series of vem_phi_ns4000.csv (the paper's N_S = 4000) where they exist, else
    the reduced-size studies of vem_study.csv; the stiffness series from vem_study.csv."""
    out = {}
    big = [r for r in read_table(os.path.join(data, "vem_doh_ns8000.csv")) if r["end"] == "stage3"]
    study = read_table(os.path.join(data, "vem_study.csv"))
    if big:
        voids = sorted({int(r["voids"]) for r in big})
        series, particles, what = big, "8000", f"N_S = 8000, N_V = {voids[0]}-{voids[-1]}, seeds " + ", ".join(
            sorted({r["seed"] for r in big}))
    else:
        names = {"n025", "n050_seed1", "n050_seed2", "n050_seed3", "n100", "n200"}
        series, particles, what = [r for r in study if r["name"] in names], "1000", "N_S = 1000, n = 0.25-2"
    if series:
        k = len(series)
        for key, column in (("vem.q_i_n13", "q_n13"), ("vem.slope_n13", "slope_n13"),
                            ("vem.phi_ti_over_n", "phi_total_i"), ("vem.beta", "beta")):
            m, s = mean_sd(r[column] for r in series)
            out[key] = _ours(m, s, k, particles, f"{what}; mean and SD over the runs, as the paper's over n")
    phis = sorted(read_table(os.path.join(data, "vem_phi_ns4000.csv")), key=lambda r: float(r["phi_s"]))
    if phis:
        m, s = mean_sd(r["phi_total_i"] for r in phis)
        out["vem.phi_ti_over_phis"] = _ours(m, s, len(phis), "4000", "N_S = 4000, N_V = 2000, Phi_S = " + ", ".join(
            r["phi_s"] for r in phis) + ", seed 1; mean and SD over Phi_S, as the paper's")
    else:
        phis = [r for r in study if r["name"].startswith("phi") or r["name"].startswith("n050_seed")]
        phis = [r for r in phis if r["time_step_rule"] == "stiffness_sum"]
        if phis:
            m, s = mean_sd(r["phi_total_i"] for r in phis)
            out["vem.phi_ti_over_phis"] = _ours(m, s, len(phis), "1000",
                                                "N_S = 1000, n = 0.5, Phi_S = 0.2-0.55 (seeds 1-3 at 0.4)")
    stiff = {}
    for r in study:
        if r["name"].startswith("stiffness_kns1e3") or (r["name"] == "n050_seed1"):
            stiff[float(r["kn_ratio"])] = (float(r["q_i"]), float(r["slope"]))
    for kn, key in ((1e-6, "vem.eq10_kn_1e-6"), (1e-5, "vem.eq10_kn_1e-5"), (1e-4, "vem.eq10_kn_1e-4")):
        if kn in stiff:
            out[key] = _ours(stiff[kn][0], 0.0, 1, "1000", "N_S = 1000, n = 0.5, k_n,S = 1e3 N/m, seed 1")
    low = sorted(kn for kn in stiff if kn <= 1e-4 * (1 + 1e-9))
    high = sorted(kn for kn in stiff if kn > 1e-4 * (1 + 1e-9))
    if high:
        m, s = mean_sd(stiff[kn][0] for kn in high)
        out["vem.plateau"] = _ours(m, s, len(high), "1000", f"mean q_i over K_n = {', '.join(f'{k:g}' for k in high)}")
    if len(low) >= 2 and high:
        # The paper's estimator: q_i = A ln K_n + B fitted for K_n <= 1e-4, the plateau its mean
        # above; K_n^c where the two meet.
        xs = [math.log(kn) for kn in low]
        ys = [stiff[kn][0] for kn in low]
        slope, intercept = _line(xs, ys)
        plateau = statistics.mean(stiff[kn][0] for kn in high)
        out["vem.kink_kn"] = _ours(math.exp((plateau - intercept) / slope), 0.0, 1, "1000",
                                   f"q_i = {slope:.4f} ln K_n + {intercept:.3f} over K_n <= 1e-4 meets {plateau:.3f}")
        xs_slope = [math.log(stiff[kn][1]) for kn in low]
        b, _ = _line(xs, xs_slope)
        out["vem.eq11_slope"] = _ours(b, 0.0, 1, "1000", "log-log line through the slopes at K_n <= 1e-4: " + ", ".join(
            f"{stiff[kn][1]:.0f}" for kn in low))
    return out


def _line(xs, ys):
    mx, my = statistics.mean(xs), statistics.mean(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    return slope, my - slope * mx


def doh_values(data):
    """Table 2's VEM rows (vem_doh_ns8000.csv: the structures stopped at the paper's C, with their
    stage III values in the note; else the seed-1 stage III structures of shear_table2_ns8000.csv),
    the BD rows at the paper's C (bd_seeds_ns8000.csv), the eq. 7 fit over both sets
    (doh_fig6_cmatched_fit.csv, else bd_fig6_fit_ns8000.csv) and the phase angle
    (shear_phase_angle_ns8000.csv, else shear_table2.csv)."""
    out = {}
    table = read_table(os.path.join(data, "vem_doh_ns8000.csv"))
    note = "VEM stopped at stage III (strain energy 1e-3); static solver, six orientations"
    if table:
        # Each structure stopped where its CN reaches the paper's C (as the BD rows): the rule the
        # paper's constant C suggests; the stage III values (the VEM paper's stop) in the note.
        ends = {}
        for r in table:
            ends.setdefault((int(r["voids"]), r["end"]), []).append(r)
        for nv in sorted({nv for nv, _ in ends}):
            matched, stage3 = ends.get((nv, "cmatched"), []), ends.get((nv, "stage3"), [])
            rs = matched or stage3
            for key, column, scale in (("a", "a", 1.0), ("c", "coordination", 1.0), ("gp", "storage_modulus", 1e-6)):
                m, s = mean_sd(float(r[column]) * scale for r in rs)
                text = ("VEM structure where CN first reaches the paper's C" + (
                    " (C matched by that choice)" if key == "c" else "") if matched else note) + \
                    "; static solver, six orientations; SD over seeds"
                if matched and stage3:
                    sm, ss = mean_sd(float(r[column]) * scale for r in stage3)
                    text += f"; at stage III (the VEM paper's stop): {sm:.4g}" + (f" ± {ss:.2g}" if len(stage3) > 1 else "")
                out[f"doh.{key}_nv{nv}"] = _ours(m, s, len(rs), "8000", text)
    else:
        for r in read_table(os.path.join(data, "shear_table2_ns8000.csv")):
            nv = int(r["voids"])
            out[f"doh.a_nv{nv}"] = _ours(float(r["a"]), 0.0, 1, "8000", note + "; seed 1")
            out[f"doh.c_nv{nv}"] = _ours(float(r["coordination"]), 0.0, 1, "8000", note + "; seed 1")
            out[f"doh.gp_nv{nv}"] = _ours(float(r["storage_modulus"]) * 1e-6, 0.0, 1, "8000",
                                          note + f"; seed 1 (SD over the six orientations {float(r['std']) * 1e-6:.3f})")
    matched_fit = read_table(os.path.join(data, "doh_fig6_cmatched_fit.csv"))
    fits = matched_fit or read_table(os.path.join(data, "bd_fig6_fit_ns8000.csv"))
    for r in fits:
        if r["data"] == "this work: VEM + BD":
            what = f"fit over {r['points']} structures (VEM + BD" + (
                ", all at the paper's C)" if matched_fit else ")")
            out["doh.eq7_a0"] = _ours(float(r["a0"]), 0.0, 1, "8000", what)
            out["doh.eq7_beta"] = _ours(float(r["beta"]), 0.0, 1, "8000", what)
    rates = read_table(os.path.join(data, "shear_phase_angle_ns8000.csv"))
    phases = [abs(float(r["phase_angle"])) for r in read_table(os.path.join(data, "shear_table2.csv"))
              if r["label"].startswith("this work")]
    if rates:
        slow = max(rates, key=lambda r: int(r["steps_per_cycle"]))
        out["doh.phase_angle"] = _ours(float(slow["phase_angle_max_abs"]), 0.0, 1, "8000",
                                       f"largest |delta| over 3 cycles of {int(slow['steps_per_cycle'])} steps, "
                                       "N_V = 2000 structure, z:x (examples/reproduction/phase_angle.sh); " + ", ".join(
                                           f"{int(r['steps_per_cycle'])} steps: {float(r['phase_angle_max_abs']):.2g}"
                                           for r in rates))
    elif phases:
        out["doh.phase_angle"] = _ours(max(phases), 0.0, len(phases), "1000",
                                       "largest |delta| of the dynamic test over six N_S = 1000 structures at 10000-40000 "
                                       "steps per cycle (delta falls as 1/T; the static solver has 0)")
    out.update(bd_values(data))
    return out


def bd_at_paper_c(seeds_csv):
    """Per potential: the seeds' rows at the time whose mean C is nearest the paper's (the rule of
    docs/bd.md and examples/bd/fig6.py): mV -> (time, [rows])."""
    groups = {}
    for r in read_table(seeds_csv):
        groups.setdefault((int(round(float(r["surface_potential_mV"]))), round(float(r["time_diffusion_times"]), 6)),
                          []).append(r)
    chosen = {}
    for mv in sorted({mv for mv, _ in groups}):
        if mv not in BD_TABLE2:
            continue
        times = [(t, rs) for (m, t), rs in groups.items() if m == mv]
        chosen[mv] = min(times, key=lambda tr: abs(statistics.mean(float(r["C"]) for r in tr[1]) - BD_TABLE2[mv][1]))
    return chosen


def bd_values(data):
    out = {}
    chosen = bd_at_paper_c(os.path.join(data, "bd_seeds_ns8000.csv"))
    for mv, (time, rs) in chosen.items():
        note = f"N = 8000, central bonds, stopped at t = {time:g} a^2/D_0 where C reaches the paper's"
        for key, column, scale in (("a", "a", 1.0), ("c", "C", 1.0), ("gp", "storage_modulus_Pa", 1e-6)):
            m, s = mean_sd(float(r[column]) * scale for r in rs)
            out[f"doh.bd_{key}_psi{mv}"] = _ours(m, s, len(rs), "8000", note)
    if 0 in chosen and 15 in chosen:
        by_seed = {r["seed"]: float(r["storage_modulus_Pa"]) for r in chosen[0][1]}
        ratios = [float(r["storage_modulus_Pa"]) / by_seed[r["seed"]] for r in chosen[15][1] if r["seed"] in by_seed]
        m, s = mean_sd(ratios)
        out["doh.ratio_he_ho"] = _ours(m, s, len(ratios), "8000", "per seed, BD gels at the paper's C")
    return out


def opal_values(data):
    """The opal paper's porosity rows (§4, Fig. 14, eq. 24-26) from the study over the paper's
    range (opal_porosity_paper*.csv, examples/opal/porosity_tables.py): E and strength at pore
    fractions 0.49 and 0.63 (mean and SD over the seeds), and the paper's estimator for the laws:
    eq. 25 fitted with E0 free over all samples, eq. 24 with E0 held at eq. 25's (the paper's
    eq. 24 and 25 share E0 = 22.06 GPa), eq. 26 free; eps = the pore volume fraction."""
    out = {}
    levels = read_table(os.path.join(data, "opal_porosity_paper_levels.csv"))
    samples = read_table(os.path.join(data, "opal_porosity_paper.csv"))
    if not levels or not samples:
        return out
    moduli = read_table(os.path.join(data, "opal_porosity_paper_modulus.csv")) or samples  # E only

    def span(rows):
        counts = sorted(int(r["particles"]) for r in rows)
        return f"{counts[0]}-{counts[-1]}"

    particles = {"E": span(moduli), "strength": span(samples)}
    what = "the paper's sample scaled by 150/762 (pores 138 nm packed at 150 nm, D/d = 9.2), paper's bonds, static solver"
    for r in levels:
        f = float(r["pore_fraction"])
        for level in ("049", "063"):
            if abs(f - int(level) / 100) < 1e-9:
                # E over the E-only samples where the study has them (modulus_samples), the
                # strength over the compressed ones (samples).
                n_strength = int(r["samples"])
                n_modulus = int(r.get("modulus_samples") or n_strength)
                for key, column, scale, n in (("E", "youngs_modulus", 1e-9, n_modulus),
                                              ("strength", "strength", 1e-6, n_strength)):
                    if n and r[column]:
                        note = f"{what}; pore fraction {float(r['pore_fraction_of_box']):.3f}, {n} seeds"
                        out[f"opal.porosity_{key}_{level}"] = _ours(float(r[column]) * scale,
                                                                   float(r[column + "_sd"]) * scale, n,
                                                                   particles[key], note)
    fits = read_table(os.path.join(data, "opal_porosity_paper_fits.csv"))

    def per_seed(quantity, law, held, column, scale=1.0):
        rows = [r for r in fits if r["eps"] == "pore_fraction_of_box" and r["quantity"] == quantity and
                r["law"] == law and r["e0_held"] == held and r["seed"] != "all"]
        m, s = mean_sd([float(r[column]) * scale for r in rows])
        # What each seed's fit is over ("0.39-0.63 (6)": the range and the number of pore fractions).
        over = rows[0].get("pore_fractions", "") if rows else ""
        return m, s, len(rows), over

    for key, args in (("opal.eq25_E0", ("youngs_modulus", "power", "0", "e0", 1e-9)),
                      ("opal.eq25_m", ("youngs_modulus", "power", "0", "exponent")),
                      ("opal.eq24_b", ("youngs_modulus", "exponential", "shared", "exponent")),
                      ("opal.eq26_a", ("strength", "exponential", "0", "e0", 1e-6)),
                      ("opal.eq26_b", ("strength", "exponential", "0", "exponent"))):
        m, s, n, over = per_seed(*args)
        if not n:
            continue
        if "(" in over:
            count, span = int(over.split("(")[1].rstrip(")")), over.split(" ")[0]
        else:  # a fits table without the column: over the levels
            fractions = sorted(float(r["pore_fraction"]) for r in levels)
            count, span = len(fractions), f"{fractions[0]:g}-{fractions[-1]:g}"
        note = (f"{what}; fitted per seed over its {count} pore fractions {span}"
                f"{'' if count == 6 else ' (the paper: six, 0.39-0.63)'}, mean and SD over the seeds"
                f"{' (E only: the first linear solve)' if args[0] == 'youngs_modulus' else ''}")
        out[key] = _ours(m, s, n, particles["E" if args[0] == "youngs_modulus" else "strength"],
                         note + ("; E0 held at eq. 25's" if key == "opal.eq24_b" else ""))
    return out


def _resolution_levels(measured):
    """Of the measured levels of a resolution table: the D/d values, the particle counts'
    span (means per level) and the most seeds of a level."""
    ratios = sorted({float(r["d_over_d"]) for r in measured})
    counts = sorted(float(r["particles"]) for r in measured)
    return ratios, f"{counts[0]:.0f}-{counts[-1]:.0f} (means per level)", max(int(r["seeds"]) for r in measured)


def opal_porosity_resolution_values(data):
    """The `_dd51` rows: the porosity samples at three resolutions (opal_porosity_resolution.csv,
    examples/opal/porosity_resolution.py) extrapolated to the paper's D/d = 51 by q = q_inf +
    c d/D (the uncertainty adds half the spread of the laws 1/x^2, 1/sqrt(x))."""
    out = {}
    rows = read_table(os.path.join(data, "opal_porosity_resolution.csv"))
    measured = [r for r in rows if r["scale"] and not r["scale"].startswith("D/d") and r["pore_fraction"]]
    if not measured:
        return out | opal_porosity_resolution_modulus_values(data)
    ratios, span, seeds = _resolution_levels(measured)
    scales = sorted({float(r["scale"]) for r in measured})
    what = (f"the random-pore samples at D/d = {', '.join(f'{x:g}' for x in ratios)} (the paper's sample scaled by "
            f"150 s/762, s = {', '.join(f'{x:g}' for x in scales)}: the same pore count and box in units of the pore "
            f"spacing), paper's bonds, static solver, up to {seeds} packings per level; q = q_inf + c d/D taken at "
            "D/d = 51, SD: fit error and the spread of the laws 1/x^2, 1/sqrt(x)")
    for r in rows:
        if not r["scale"].startswith("D/d"):
            continue
        if r["pore_fraction"]:
            level = f"{round(float(r['pore_fraction']) * 100):03d}"
            for column, name, scale in (("youngs_modulus", "E", 1e-9), ("strength", "strength", 1e-6)):
                if r[column + "_mean"]:
                    at = [float(m[column + "_mean"]) * scale for m in measured
                          if m["pore_fraction"] == r["pore_fraction"]]
                    out[f"opal.porosity_{name}_{level}_dd51"] = _ours(
                        float(r[column + "_mean"]) * scale, float(r[column + "_sd"]) * scale, int(r["seeds"]), span,
                        f"{what} (values there: {', '.join(f'{v:.3g}' for v in at)})")
        elif r["law"] in ("eq25_m", "eq24_b", "eq26_b") and f"opal.{r['law']}_dd51" not in out:
            # The first row of a law: over the pore fractions every scale holds (a comparison
            # range, 0.49-0.63, follows it).
            at = [float(m["law_mean"]) for m in rows if m["law"] == r["law"] and m["fitted_over"] == r["fitted_over"]
                  and not m["scale"].startswith("D/d")]
            out[f"opal.{r['law']}_dd51"] = _ours(
                float(r["law_mean"]), float(r["law_sd"]), int(r["seeds"]), span,
                f"{what}; fitted per seed over pore fractions {r['fitted_over']} at each D/d "
                f"(values there: {', '.join(f'{v:.3g}' for v in at)})")
    return out | opal_porosity_resolution_modulus_values(data)


def opal_porosity_resolution_modulus_values(data):
    """E over the paper's whole range at three resolutions, from the E-only samples
    (opal_porosity_resolution_modulus.csv, examples/opal/porosity_resolution.py --modulus; five
    seeds, six pore fractions) taken to D/d = 51: the `opal.porosity_E_*_dd51`, `opal.eq25_m_dd51`
    and `opal.eq24_b_dd51` rows, in place of those of the compressed samples where it has them."""
    out = {}
    rows = read_table(os.path.join(data, "opal_porosity_resolution_modulus.csv"))
    measured = [r for r in rows if not r["scale"].startswith("D/d") and r["pore_fraction"]]
    if not measured:
        return out
    ratios, span, seeds = _resolution_levels(measured)
    what = (f"E-only random-pore samples (the first linear solve) at D/d = {', '.join(f'{x:g}' for x in ratios)}, "
            f"paper's bonds, static solver, {seeds} seeds per level; q = q_inf + c d/D taken at D/d = 51, SD: fit "
            "error and the spread of the laws 1/x^2, 1/sqrt(x)")
    for r in rows:
        if not r["scale"].startswith("D/d"):
            continue
        if r["pore_fraction"]:
            level = f"{round(float(r['pore_fraction']) * 100):03d}"
            if level not in ("049", "063"):  # the paper's values (Fig. 14)
                continue
            at = [float(m["youngs_modulus_mean"]) * 1e-9 for m in measured if m["pore_fraction"] == r["pore_fraction"]]
            out[f"opal.porosity_E_{level}_dd51"] = _ours(
                float(r["youngs_modulus_mean"]) * 1e-9, float(r["youngs_modulus_sd"]) * 1e-9, int(r["seeds"]), span,
                f"{what} (values there: {', '.join(f'{v:.3g}' for v in at)})")
        elif r["law"] in ("eq25_E0", "eq25_m", "eq24_b"):
            scale = 1e-9 if r["law"] == "eq25_E0" else 1.0  # [GPa]
            at = [float(m["law_mean"]) * scale for m in rows
                  if m["law"] == r["law"] and not m["scale"].startswith("D/d")]
            out[f"opal.{r['law']}_dd51"] = _ours(
                float(r["law_mean"]) * scale, float(r["law_sd"]) * scale, int(r["seeds"]), span,
                f"{what}; fitted per seed over pore fractions {r['fitted_over']} at each D/d "
                f"(values there: {', '.join(f'{v:.3g}' for v in at)})")
    return out


def _seed_list(seeds):
    """1-3 for a run of consecutive seeds, else 1, 2, 5."""
    if len(seeds) > 1 and seeds == list(range(seeds[0], seeds[-1] + 1)):
        return f"{seeds[0]}-{seeds[-1]}"
    return ", ".join(str(x) for x in seeds)


def opal_structure_values(data):
    """The opal paper's rows of the FCC opal, the bulk and the coating (§2.1, §3, §4) from the
    studies of docs/opal.md: the resolution study (opal_resolution.csv, D/d = 9.2-24.5, three
    packings each, static solver) at its largest D/d and extrapolated to the paper's 51
    (opal_resolution_extrapolation.csv, examples/opal/resolution_extrapolation.py), and the
    reduced-resolution runs of examples/opal/run.sh (opal_runs.csv: one sample each)."""
    out = {}
    resolution = read_table(os.path.join(data, "opal_resolution.csv"))
    if resolution:
        def at_largest(column, scale=1.0):
            rows = [r for r in resolution if r[column]]
            largest = max(float(r["pore_to_particle_diameter"]) for r in rows)
            rows = [r for r in rows if float(r["pore_to_particle_diameter"]) == largest]
            m, s = mean_sd([float(r[column]) * scale for r in rows])
            n = sorted(int(r["particles"]) for r in rows)
            b = sorted(round(float(r["bonds"])) for r in rows) if all(r.get("bonds") for r in rows) else []
            return m, s, len(rows), f"{n[0]}-{n[-1]}", largest, (f", {b[0]}-{b[-1]} bonds" if b else "")

        for key, column in (("opal.E_paper_bonds", "youngs_modulus_gpa"), ("opal.strength_paper_bonds", "strength_mpa")):
            m, s, n, particles, largest, bonds = at_largest(column)
            out[key] = _ours(m, s, n, particles, f"FCC opal at D/d = {largest:g} (the largest with this quantity; paper: "
                                                 f"51){bonds}, paper's bonds, static solver; three FBA packings; the trend "
                                                 "over D/d is the size_study row")
    extrapolation = read_table(os.path.join(data, "opal_resolution_extrapolation.csv"))
    counts = sorted(int(r["particles"]) for r in resolution)
    span = f"{counts[0]}-{counts[-1]}" if counts else ""
    for key, quantity in (("opal.size_study_E_dd51", "youngs_modulus_gpa"),
                          ("opal.size_study_strength_dd51", "strength_mpa"), ("opal.coordination", "bonds_per_particle")):
        rows = [r for r in extrapolation if r["quantity"] == quantity and r["law"] == "estimate"]
        if rows:
            r = rows[0]
            out[key] = _ours(float(r["at_target"]), float(r["standard_error"]), int(r["samples"]), span,
                             f"q = q_inf + c d/D fitted to {r['samples']} samples at D/d = 9.2-{float(r['largest_d_over_d']):g}"
                             " and taken at D/d = 51; SD = fit error and the spread of the laws 1/x^2 and 1/sqrt(x) "
                             "(examples/opal/resolution_extrapolation.py)" +
                             ("; bonds within 1.75 d per particle (the paper's 843,000 bonds / 80,000 particles per "
                              "um^3 = 10.5; bonded neighbours are twice that)" if quantity == "bonds_per_particle" else ""))
    runs = {r["run"]: r for r in read_table(os.path.join(data, "opal_runs.csv"))}
    out.update(opal_coating_values(data))
    out.update(opal_bulk_values(data))
    if "opal.bulk_strength" in out and "bulk_compressive" in runs:
        out["opal.bulk_strength"]["note"] += (
            f"; {float(runs['bulk_compressive']['strength']) * 1e-6:.0f} MPa with eq. 16 on compressed bonds too "
            f"(examples/opal/run.sh, one {runs['bulk_compressive']['particles']}-particle sample)")
    # Each of the two bulk rows from run.sh's single sample where the bulk study lacks it.
    if "bulk" in runs:
        bulk = runs["bulk"]
        note = (f"pore-free FBA sample, porosity 0.38, {bulk['particles']} particles, periodic sides, E_b 6.53 GPa "
                "(examples/opal/run.sh)")
        if "opal.K_E" not in out:
            out["opal.K_E"] = _ours(float(bulk["youngs_modulus"]) / float(bulk["bond_youngs_modulus"]), 0.0, 1,
                                    bulk["particles"], note)
        compressive = runs.get("bulk_compressive")
        if "opal.bulk_strength" not in out:
            out["opal.bulk_strength"] = _ours(
                float(bulk["strength"]) * 1e-6, 0.0, 1, bulk["particles"],
                note + "; eq. 16 on stretched bonds only (MUSEN)" +
                (f"; {float(compressive['strength']) * 1e-6:.0f} MPa with eq. 16 on compressed bonds too"
                 if compressive else ""))
    if "coated" in runs and "opal.coating20_E" not in out:
        coated = runs["coated"]
        note = (f"FCC opal at D/d = 9.2 with 3.6 nm of titania (20 nm x 138/762), density "
                f"{float(coated['density']):.0f} kg/m^3 (paper 668), paper's bonds, one sample (examples/opal/run.sh)")
        out["opal.coating20_E"] = _ours(float(coated["youngs_modulus"]) * 1e-9, 0.0, 1, coated["particles"], note)
        out["opal.coating20_strength"] = _ours(float(coated["strength"]) * 1e-6, 0.0, 1, coated["particles"], note)
    return out


def opal_fba_values(data):
    """The FBA packings behind the opal studies (opal_fba_packings.csv, examples/opal/fba_tables.py):
    their porosity, mean and SD over every packing; {} without the table."""
    rows = read_table(os.path.join(data, "opal_fba_packings.csv"))
    if not rows:
        return {}
    porosity = [float(r["porosity"]) for r in rows]
    m, sd = mean_sd(porosity)
    counts = sorted(int(r["particles"]) for r in rows)
    studies = sorted({r["study"] for r in rows})
    targets = sorted({float(r["target_porosity"]) for r in rows})
    contacts = statistics.fmean(float(r["contacts_per_particle"]) for r in rows)
    note = (f"{len(rows)} packings of 15 nm spheres ({', '.join(studies)}), target porosity "
            f"{', '.join(f'{t:g}' for t in targets)}: reached {min(porosity):.6f}-{max(porosity):.6f}, the largest "
            f"overlap left {max(float(r['max_overlap']) for r in rows):.2g} of the diameter (the FBA's tolerance 1e-3), "
            f"{contacts:.2f} contacts per particle within 0.01 d; the FBA stops at its target, so this row checks "
            "that it gets there without overlaps, not a measured property")
    return {"opal.fba_porosity": _ours(m, sd, len(rows), f"{counts[0]}-{counts[-1]}", note)}


def opal_coating_values(data):
    """The coating rows from the coated opals at D/d = 9.2-24.5 (examples/opal/coating_tables.py):
    each coating's E and strength extrapolated to the paper's D/d = 51 as the uncoated opal's
    size_study rows are; where a quantity was measured at one D/d only, its mean and SD there.
    The 20 nm rows' notes add the test of the density (examples/opal/coating_density.toml: the
    coating thinned at each D/d to the paper's 668 kg/m^3) where its tables exist.
    {} when the study's tables are missing."""
    out = {}
    samples = read_table(os.path.join(data, "opal_coating_resolution.csv"))
    estimates = {(int(float(r["coating_nm"])), r["quantity"]): r
                 for r in read_table(os.path.join(data, "opal_coating_extrapolation.csv")) if r["law"] == "estimate"}
    density_samples = read_table(os.path.join(data, "opal_coating_density.csv"))
    density_estimates = {r["quantity"]: r for r in read_table(os.path.join(data, "opal_coating_density_extrapolation.csv"))
                         if r["law"] == "estimate"}

    def density_test(quantity, unit):
        """The same quantity with the coating thinned to the paper's density: at D/d = 51 and
        at each D/d run (means over the packings)."""
        used = [s for s in density_samples if s[quantity]]
        if not used:
            return ""
        ratios = sorted({float(s["pore_to_particle_diameter"]) for s in used})
        means = [statistics.fmean(float(s[quantity]) for s in used if float(s["pore_to_particle_diameter"]) == x)
                 for x in ratios]
        densities = [statistics.fmean(float(s["density_kg_m3"]) for s in used
                                      if float(s["pore_to_particle_diameter"]) == x) for x in ratios]
        at = ", ".join(f"{m:.4g}" for m in means)
        low, high = f"{min(densities):.0f}", f"{max(densities):.0f}"
        text = (f"; with the coating thinned at each D/d to the paper's density (examples/opal/coating_density.toml; "
                f"{low if low == high else low + '-' + high} kg/m^3): {at} {unit} at D/d = "
                + ", ".join(f"{x:g}" for x in ratios))
        r = density_estimates.get(quantity)
        if r is not None:
            text += f", {float(r['at_target']):.4g} +- {float(r['standard_error']):.2g} {unit} at D/d = 51"
        return text
    for nm in sorted({int(float(s["coating_nm"])) for s in samples}):
        for quantity, name, unit in (("youngs_modulus_gpa", "E", "GPa"), ("strength_mpa", "strength", "MPa")):
            used = [s for s in samples if int(float(s["coating_nm"])) == nm and s[quantity]]
            if not used:
                continue
            counts = sorted(int(s["particles"]) for s in used)
            ratios = sorted({float(s["pore_to_particle_diameter"]) for s in used})
            top = [s for s in used if float(s["pore_to_particle_diameter"]) == ratios[-1]]
            top_mean, top_sd = mean_sd([float(s[quantity]) for s in top])
            density = statistics.fmean(float(s["density_kg_m3"]) for s in top)
            seeds_at = {x: sorted({int(float(s["seed"])) for s in used if float(s["pore_to_particle_diameter"]) == x})
                        for x in ratios}
            all_seeds = sorted(set().union(*seeds_at.values()))
            what = (f"FCC opal with {nm} nm of titania scaled with the pores (L_coat = {nm} nm x D / 762 nm), titania "
                    f"bonds of Table 1, paper's silica bonds, static solver, FBA seeds {_seed_list(all_seeds)} at D/d = "
                    + ", ".join(f"{x:g}" for x in ratios)
                    + "".join(f" (at {x:g} seeds {_seed_list(seeds_at[x])} only)" for x in ratios
                              if seeds_at[x] != all_seeds))
            r = estimates.get((nm, quantity))
            if r is not None:
                out[f"opal.coating{nm}_{name}"] = _ours(
                    float(r["at_target"]), float(r["standard_error"]), int(r["samples"]), f"{counts[0]}-{counts[-1]}",
                    what + "; q = q_inf + c d/D taken at D/d = 51 (SD: fit error and the spread of the laws 1/x^2, "
                    f"1/sqrt(x), examples/opal/coating_tables.py); at D/d = {ratios[-1]:g}: {top_mean:.4g} +- "
                    f"{top_sd:.2g} {unit} ({len(top)} samples), density {density:.0f} kg/m^3 (paper, 20 nm: 668)"
                    + (density_test(quantity, unit) if nm == 20 else ""))
            else:
                out[f"opal.coating{nm}_{name}"] = _ours(
                    top_mean, top_sd, len(top), f"{counts[0]}-{counts[-1]}",
                    what + f"; not extrapolated (too few D/d with this quantity), the mean at D/d = {ratios[-1]:g}, "
                    f"density {density:.0f} kg/m^3 (paper, 20 nm: 668)")
    return out


def opal_bulk_values(data):
    """K_E and the bulk strength from the pore-free samples of examples/opal/bulk_study.toml
    (several packings per size): the largest size that has each quantity; {} without the table."""
    levels = [r for r in read_table(os.path.join(data, "opal_bulk_study.csv")) if r["seed"] == "mean"]
    out = {}

    def at_largest(column):
        rows = [r for r in levels if r[column]]
        return max(rows, key=lambda r: float(r["side_nm"])) if rows else None

    def others(column, scale, digits):
        return ", ".join(f"{float(r[column]) * scale:.{digits}g} +- {float(r[column + '_sd']) * scale:.2g} at "
                         f"{int(float(r['side_nm']))} nm" for r in levels if r[column])

    samples = read_table(os.path.join(data, "opal_bulk_study.csv"))

    def count(side, column):
        return sum(1 for r in samples if r["seed"] != "mean" and r["side_nm"] == side and r[column])

    for key, column, scale in (("opal.K_E", "bulk_factor", 1.0), ("opal.bulk_strength", "strength_mpa", 1.0)):
        r = at_largest(column)
        if r is None:
            continue
        side = int(float(r["side_nm"]))
        packings = count(r["side_nm"], column)
        out[key] = _ours(float(r[column]) * scale, float(r[column + "_sd"]) * scale, packings,
                         f"{float(r['particles']):.0f}",
                         f"pore-free FBA silica (porosity 0.38, periodic sides), {side} x {side} x "
                         f"{float(r['height_nm']):.0f} nm, E_b 6.53 GPa, sigma_max 94.3 MPa (eq. 16 on stretched bonds "
                         f"only), static solver, {packings} packings (examples/opal/bulk_study.toml); by size: "
                         + others(column, scale, 4))
    return out


def _cell(row, column):
    """A number of a table row; NaN where the row leaves it empty."""
    return float(row[column]) if row.get(column) not in (None, "") else math.nan


def _ratio(a, b, column):
    """row a / row b in `column`, with the SD of independent estimates from `column`_se."""
    r = _cell(a, column) / _cell(b, column)
    return r, r * math.hypot(_cell(a, column + "_se") / _cell(a, column), _cell(b, column + "_se") / _cell(b, column))


def scrm_values(data):
    """The SCRM paper's rows from examples/scrm/summarize.py's tables (scrm_mono.csv,
    scrm_contact_values.csv, scrm_bimodal.csv): SDs are standard errors over the realizations
    (bootstrap for positions), the uncertainty of the paper's own averaged curves."""
    out = {}
    mono = {r["case"]: r for r in read_table(os.path.join(data, "scrm_mono.csv"))}
    f = _cell
    rule = "the paper's rule (a point uniform in the 0.02a window, kept if free, up to N_sh = 150 tries)"
    for c, key in (("0.575", "c0575"), ("0.6", "c060"), ("0.63", "c063")):
        ls, sc = mono.get(f"mono-ls-c{c}"), mono.get(f"mono-scrm-c{c}")
        if not (ls and sc):
            continue
        r, sd = _ratio(sc, ls, "contact_value")
        note = (f"g(2a+) {f(ls, 'contact_value'):.2f} (LS, G = 0.02) -> {f(sc, 'contact_value'):.2f} (SCRM, M = 10, "
                f"{rule}); dr = 0.01 a, K-function with toroidal edge correction; SD = standard error over the P "
                "realizations")
        out[f"scrm.g2a_drop_{key}"] = _ours(100 * (1 - r), 100 * sd, sc["realizations"], sc["particles"], note)
        out[f"scrm.mono_gap_{key}"] = _ours(f(sc, "gap_R"), f(sc, "gap_R_se"), sc["realizations"], sc["particles"],
                                            "minimum of the averaged g (5-bin running mean) in R = 2.3-3.2; SD by "
                                            "bootstrap over the realizations")
        if c == "0.6":
            r, sd = _ratio(sc, ls, "max_near_contact")
            out["scrm.gmax_change_c060"] = _ours(
                r, sd, sc["realizations"], sc["particles"],
                f"max of the averaged g within R <= 2.1: LS {f(ls, 'max_near_contact'):.2f} at "
                f"{f(ls, 'max_near_contact_R'):.2f}, SCRM {f(sc, 'max_near_contact'):.2f} at "
                f"{f(sc, 'max_near_contact_R'):.2f}")
            out["scrm.window_variance_ls"] = _ours(f(ls, "window_variance"), f(ls, "window_variance_se"),
                                                   ls["realizations"], ls["particles"],
                                                   "the paper's Fig. 4 gives the histograms, no number; mean count "
                                                   f"{f(ls, 'window_mean'):.2f}")
            r, sd = _ratio(sc, ls, "window_variance")
            out["scrm.window_variance_scrm"] = _ours(r, sd, sc["realizations"], sc["particles"],
                                                     f"SCRM variance {f(sc, 'window_variance'):.3f} against LS "
                                                     f"{f(ls, 'window_variance'):.3f}: " +
                                                     ("a reduction" if r + sd < 1 else "no reduction (not reproduced)"))
    by_dr = {(r["case"], float(r["dr"])): r for r in read_table(os.path.join(data, "scrm_contact_values.csv"))}
    coarse, paper_dr = by_dr.get(("mono-scrm-c0.575", 0.015)), by_dr.get(("mono-scrm-c0.575", 0.01))
    if coarse and paper_dr:
        r, sd = _ratio(paper_dr, coarse, "contact_value")
        ls = [by_dr.get(("mono-ls-c0.575", dr)) for dr in (0.015, 0.01)]
        note = (f"g(2a+) {f(coarse, 'contact_value'):.2f} at dr = 0.015 a, {f(paper_dr, 'contact_value'):.2f} at 0.01 a "
                "(same realizations: the SD overstates the error); all bin widths in scrm_contact_values.csv")
        if all(ls):
            note += f"; LS: {100 * (f(ls[1], 'contact_value') / f(ls[0], 'contact_value') - 1):+.1f} %"
        out["scrm.dr_015_to_010"] = _ours(100 * (r - 1), 100 * sd, paper_dr["realizations"], paper_dr["particles"], note)
    bimodal = {(r["case"], r["pair"]): r for r in read_table(os.path.join(data, "scrm_bimodal.csv"))}
    ls, sc = bimodal.get(("bi-ls-c0.6", "g11")), bimodal.get(("bi-scrm-M60-c0.6", "g11"))
    if ls and sc:
        r, sd = _ratio(sc, ls, "contact_value")
        m10 = bimodal.get(("bi-scrm-c0.6", "g11"))
        out["scrm.bimodal_g11_drop"] = _ours(
            100 * (1 - r), 100 * sd, sc["realizations"], sc["particles"],
            f"g11(2+) {f(ls, 'contact_value'):.2f} (LS) -> {f(sc, 'contact_value'):.2f} (SCRM, M = 60)" +
            (f"; M = 10: {100 * (1 - f(m10, 'contact_value') / f(ls, 'contact_value')):.1f} %" if m10 else "") +
            "".join(f"; {label}, M = 60: {100 * (1 - f(other, 'contact_value') / f(ls, 'contact_value')):.1f} %"
                    for label, other in (("freest rule", bimodal.get(("bi-scrm-freest-M60-c0.6", "g11"))),
                                         ("one-trial Metropolis", bimodal.get(("bi-scrm-metropolis1-M60-c0.6", "g11"))))
                    if other))
        for peak in SCRM_G11_PEAKS:
            out[f"scrm.bimodal_r11_peak_{peak}"] = _ours(
                f(sc, f"peak_{peak}"), f(sc, f"peak_{peak}_se"), sc["realizations"], sc["particles"],
                "maximum of the averaged g11 (5-bin running mean, SCRM M = 60) near the paper's peak; empty: no maximum "
                "inside the interval (not resolved); SD by bootstrap")
        for pair in ("g11", "g12", "g22"):
            row = bimodal.get(("bi-scrm-M60-c0.6", pair))
            if row is None:
                continue
            out[f"scrm.bimodal_gap_{pair}"] = _ours(f(row, "gap_R"), f(row, "gap_R_se"), row["realizations"],
                                                    row["particles"], "minimum of the averaged partial g (SCRM, M = "
                                                    "60); SD by bootstrap")
    # The same M study under the two other move rules (examples/scrm/mstudy_rules.py), in the notes.
    rules = {(r["move_rule"], r["final_shakes"]): r for r in read_table(os.path.join(data, "scrm_mstudy_rules.csv"))
             if r["pair"] == "g11" and r["ratio_to_M60"]}
    for m in ("3", "30"):
        row = bimodal.get((f"bi-scrm-M{m}-c0.6", "g11"))
        if row and row.get("ratio_to_M60"):
            out[f"scrm.m_study_g11_m{m}_vs_m60"] = _ours(
                100 * (f(row, "ratio_to_M60") - 1), 100 * f(row, "ratio_to_M60_se"), row["realizations"],
                row["particles"], f"g11(2+) {f(row, 'contact_value'):.2f} at M = {m}, "
                f"{f(sc, 'contact_value'):.2f} at M = 60; the same seeds grow the same packings (paired)" +
                "".join(f"; {label}: {100 * (f(other, 'ratio_to_M60') - 1):.1f} +- "
                        f"{100 * f(other, 'ratio_to_M60_se'):.1f} % ({other['realizations']} seeds)"
                        for label, other in (("freest rule", rules.get(("freest", m))),
                                             ("one-trial Metropolis", rules.get(("metropolis1", m)))) if other))
    big = bimodal.get(("bi7000-scrm-c0.6", "g11"))
    if big and sc:
        r, sd = _ratio(big, sc, "contact_value")
        out["scrm.m_study_n7000"] = _ours(100 * (r - 1), 100 * sd, big["realizations"], big["particles"],
                                          f"g11(2+) {f(big, 'contact_value'):.2f} (N = 7000, M = 3) against "
                                          f"{f(sc, 'contact_value'):.2f} (N = 2000, M = 60); the paper: \"close\"")
    return out


def collect(data):
    """The rows of the reproduction table (dicts with COLUMNS) from the tables in folder ``data``:
    every key of PAPER_ROWS, with packlab's value where a table has it."""
    ours = {}
    ours.update(vem_values(data))
    ours.update(doh_values(data))
    ours.update(opal_values(data))
    ours.update(opal_porosity_resolution_values(data))
    ours.update(opal_structure_values(data))
    ours.update(opal_fba_values(data))
    ours.update(scrm_values(data))
    rows = []
    for key, (paper, quantity, source, value, scatter, paper_particles) in PAPER_ROWS.items():
        o = ours.get(key, {})
        v, sd = o.get("packlab_value"), o.get("packlab_sd")
        if isinstance(v, float) and math.isnan(v):
            v, sd = None, None  # measured but not resolved: the note says so
        if isinstance(sd, float) and math.isnan(sd):
            sd = None
        rows.append({"key": key, "paper": paper, "quantity": quantity, "source": source, "paper_value": value,
                     "paper_scatter": scatter, "packlab_value": "" if v is None else f"{v:.4g}",
                     "packlab_sd": "" if sd is None else f"{sd:.2g}", "realizations": o.get("realizations", ""),
                     "particles": o.get("particles", ""), "paper_particles": paper_particles,
                     "within": within(value, scatter, v, sd), "note": o.get("note", "not run yet")})
    return rows


def write_csv(rows, path):
    with atomic_output(path, ".reproduction-") as tmp:
        with open(tmp, "w", newline="") as f:
            f.write("# python3 -m packlab.reproduction collect docs/data (docs/reproduction.md); within: "
                    "|packlab - paper| <= sqrt(s_paper^2 + s_packlab^2), s_paper = the paper's scatter or half its last digit\n")
            w = csv.DictWriter(f, fieldnames=COLUMNS)
            w.writeheader()
            w.writerows(rows)
    return path


def markdown_table(rows):
    lines = ["| key | quantity | source | paper | packlab (SD) | runs | N (paper N) | within | note |",
             "|---|---|---|---|---|---|---|---|---|"]
    cell = lambda text: str(text).replace("|", "\\|")  # a | inside a cell would end it
    for r in rows:
        r = {k: cell(v) for k, v in r.items()}
        paper = r["paper_value"] + (f" ± {r['paper_scatter']}" if r["paper_scatter"] else "")
        ours = r["packlab_value"] + (f" ({r['packlab_sd']})" if r["packlab_sd"] not in ("", "0") else "")
        within_text = {"yes": "**yes**", "no": "no"}.get(r["within"], r["within"])
        lines.append(f"| `{r['key']}` | {r['quantity']} | {r['source']} | {paper} | {ours or '—'} | "
                     f"{r['realizations'] or '—'} | {r['particles'] or '—'} ({r['paper_particles']}) | {within_text} | "
                     f"{r['note']} |")
    return "\n".join(lines)


def render(csv_path, md_path):
    """Replaces, in md_path, the text between ``<!-- REPRODUCTION TABLE PAPER BEGIN -->`` and
    ``<!-- REPRODUCTION TABLE PAPER END -->`` by the rows of that paper (PAPER = the paper's name
    as in the CSV), and the summary between ``<!-- REPRODUCTION SUMMARY BEGIN/END -->``."""
    rows = read_table(csv_path)
    with open(md_path) as f:
        text = f.read()
    for paper in sorted({r["paper"] for r in rows}):
        text = _replace(text, f"REPRODUCTION TABLE {paper}", markdown_table([r for r in rows if r["paper"] == paper]))
    summary = ["| paper | rows | within | not within | n/a (no value yet, or no paper value) |",
               "|---|---|---|---|---|"]
    for paper in sorted({r["paper"] for r in rows}):
        rs = [r for r in rows if r["paper"] == paper]
        count = lambda w: sum(1 for r in rs if r["within"] == w)
        summary.append(f"| {paper} | {len(rs)} | {count('yes')} | {count('no')} | {count('n/a')} |")
    text = _replace(text, "REPRODUCTION SUMMARY", "\n".join(summary))
    text = _replace(text, "VEM END POINTS", end_points_table(os.path.dirname(os.path.abspath(csv_path))))
    with atomic_output(md_path, ".reproduction-") as tmp:
        with open(tmp, "w") as f:
            f.write(text)
    return md_path


def end_points_table(data):
    """Markdown: Table 2's VEM structures at both end points of vem_doh_ns8000.csv (stage III, the
    paper's C), mean ± SD over the seeds, beside the paper's a, C and G'_p."""
    rows = read_table(os.path.join(data, "vem_doh_ns8000.csv"))
    if not rows:
        return "(no runs of examples/reproduction/vem_doh_ns8000.sh in docs/data yet)"
    lines = ["| N_V | end | seeds | q_end | a (paper) | C (paper) | G'_p MPa (paper) | G'_p SD over orientations |",
             "|---|---|---|---|---|---|---|---|"]
    groups = {}
    for r in rows:
        groups.setdefault((int(r["voids"]), r["end"]), []).append(r)
    def fmt(values, digits):  # mean ± SD over the seeds; the value alone for one seed
        m, sd = mean_sd(values)
        return f"{m:.{digits}f}" + (f" ± {sd:.{digits}f}" if len(values) > 1 else "")
    for (nv, end), rs in sorted(groups.items(), key=lambda kv: (kv[0][0], kv[0][1] != "stage3")):
        # N_V = 400 (the VEM paper's n = 0.05) is not in Table 2: no paper values, C = 4.69 taken.
        a, c, gp, sd = (f"{v:g}" for v in DOH_TABLE2_VEM[nv]) if nv in DOH_TABLE2_VEM else ("—",) * 4
        lines.append(f"| {nv} | {'stage III' if end == 'stage3' else 'C = paper'} | {len(rs)} | "
                     f"{fmt([r['q_end'] for r in rs], 3)} | {fmt([r['a'] for r in rs], 3)} ({a}) | "
                     f"{fmt([r['coordination'] for r in rs], 2)} ({c}) | "
                     f"{fmt([float(r['storage_modulus']) * 1e-6 for r in rs], 3)} ({gp}" + (f" ± {sd}" if sd != "—" else "") + ") | "
                     f"{statistics.mean(float(r['std']) for r in rs) * 1e-6:.3f} |")
    return "\n".join(lines)


def _replace(text, marker, body):
    begin, end = f"<!-- {marker} BEGIN -->", f"<!-- {marker} END -->"
    if begin not in text or end not in text:
        return text
    head, rest = text.split(begin, 1)
    _, tail = rest.split(end, 1)
    return f"{head}{begin}\n{body}\n{end}{tail}"


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m packlab.reproduction", description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    c = sub.add_parser("collect", help="DATA/*.csv -> DATA/reproduction.csv")
    c.add_argument("data", nargs="?", default="docs/data")
    c.add_argument("--out", default=None)
    r = sub.add_parser("render", help="the tables of CSV into the markers of MD")
    r.add_argument("csv")
    r.add_argument("md")
    args = parser.parse_args(argv)
    if args.command == "collect":
        if not os.path.isdir(args.data):
            print(f"packlab.reproduction: data = {args.data}: not a folder", file=sys.stderr)
            return 2
        out = args.out or os.path.join(args.data, "reproduction.csv")
        write_csv(collect(args.data), out)
        print(f"wrote {out}")
    else:
        for path in (args.csv, args.md):
            if not os.path.isfile(path):
                print(f"packlab.reproduction: {path}: no such file", file=sys.stderr)
                return 2
        render(args.csv, args.md)
        print(f"wrote {args.md}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
