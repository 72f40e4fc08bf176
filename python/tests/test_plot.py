"""packlab.plot figures from tables written by Python (packlab.write_table)."""

import matplotlib
import pytest

matplotlib.use("Agg")

import packlab
import packlab.plot.relax


def test_relax_figure_from_python_history(tmp_path):
    p = packlab.generate_random(particles=60, radius=0.25e-6, phi=0.6, seed=1)
    r = packlab.relax(p, normal_stiffness=1000, shear_stiffness=10, density=3690, steps=300, tolerance=0)
    log = packlab.write_table(tmp_path / "relax.csv", r.history, comment="packlab.relax test")
    assert packlab.read_table(log)["step"][0] == 0
    fig = packlab.plot.relax.figure(log)
    packlab.plot.save(fig, tmp_path / "relax.png")
    assert (tmp_path / "relax.png").stat().st_size > 1000


def test_vem_study_figures_from_tables(tmp_path):
    # The tables examples/vem/study_tables.py writes, with two tiny synthetic runs.
    import packlab.plot.vem_study as vem_study

    (tmp_path / "study.csv").write_text(
        "# synthetic\n"
        "name,structural,voids,n,phi_s,kn_ratio,q_i,q_i_unc,cn_i,slope,slope_unc,phi_total_i,q_n13\n"
        "n050_seed1,1000,500,0.5,0.4,0.1,1.0,0.01,3.0,50,2,0.6,0.79\n"
        "stiffness_kns1e3_knv1e-3,1000,500,0.5,0.4,1e-6,0.9,0.02,2.1,20,3,0.54,0.71\n")
    (tmp_path / "curves.csv").write_text(
        "name,q,cn,phi_total\n" + "".join(f"n050_seed1,{q / 10},{q / 5},{0.4 + q / 100}\n" for q in range(12)))
    study = packlab.plot.read_csv(tmp_path / "study.csv")
    curves = packlab.plot.read_csv(tmp_path / "curves.csv")
    for name, fig in [("studies", vem_study.studies(study, curves)), ("stiffness", vem_study.stiffness(study))]:
        packlab.plot.save(fig, tmp_path / f"{name}.png")
        assert (tmp_path / f"{name}.png").stat().st_size > 1000


def test_bd_table2_figures_from_tables(tmp_path):
    # The tables examples/bd/time_series.sh and examples/bd/fig5.sh write, synthetic values.
    import packlab.plot.bd_table2 as bd_table2

    (tmp_path / "time.csv").write_text(
        "surface_potential_mV,particles,time_diffusion_times,bonds_bd,largest_cluster_fraction,a,b,C,"
        "storage_modulus_Pa,storage_modulus_std_Pa\n"
        "0,8000,0.05,18824,1.0,0.37,0.01,4.7,9e5,4e4\n0,8000,1.0,25034,1.0,0.49,-0.01,5.5,3.5e6,4e4\n"
        "15,8000,3.0,21315,1.0,0.49,-0.02,5.3,3.4e6,6e4\n")
    (tmp_path / "fig5.csv").write_text(
        "# HO = a, HE = b\nk_n_N_per_m,G_HO_Pa,G_HO_std_Pa,G_HE_Pa,G_HE_std_Pa,ratio_HE_HO\n"
        "50,1.7e6,2e4,1.7e6,3e4,0.97\n100,3.5e6,4e4,3.4e6,6e4,0.97\n")
    (tmp_path / "coordination.csv").write_text(
        "surface_potential_mV,time_diffusion_times,mean_coordination_bonds\n"
        "0,0,0\n0,0.02,3.7\n0,0.05,4.7\n12,0,0\n12,0.1,4.7\n12,0.2,5.4\n")
    for which in ("time", "fig5", "coordination"):
        fig = bd_table2.figure(which, tmp_path / f"{which}.csv")
        packlab.plot.save(fig, tmp_path / f"{which}.png")
        assert (tmp_path / f"{which}.png").stat().st_size > 1000
    fig = bd_table2.figure("fig5", tmp_path / "fig5.csv")
    assert "0.97" in fig.axes[0].get_title()


def test_bd_table2_crossing_time(tmp_path):
    # The time a BD log's 2 bonds / N first reaches the paper's C (examples/bd/coordination_series.sh,
    # slip_matched.sh): linear interpolation between the two log rows that bracket it.
    from packlab.plot.bd_table2 import PAPER, crossing_time

    rows = [(0.0, 0.0), (0.5, 2.0), (1.0, 4.0), (1.5, 5.0), (2.0, 6.0)]
    assert crossing_time(rows, 4.5) == pytest.approx(1.25)
    assert crossing_time(rows, 3.0) == pytest.approx(0.75)
    # the crossing exactly on a row: that row's time (c0 < target <= c1), not the next pair's start
    assert crossing_time(rows, 4.0) == pytest.approx(1.0)
    assert crossing_time([(0.0, 0.0), (0.25, 1.0), (0.75, 3.0)], 3.0) == 0.75
    # never reaching the target, a log that starts at it, or one that only falls through it: None
    assert crossing_time(rows, 6.5) is None
    assert crossing_time([(0.0, 4.5), (1.0, 5.0)], 4.5) is None
    assert crossing_time([(0.0, 5.0), (1.0, 4.0)], 4.5) is None
    assert crossing_time([], 4.5) is None and crossing_time([(0.0, 1.0)], 1.0) is None
    # only the first upward crossing counts
    assert crossing_time([(0.0, 0.0), (1.0, 5.0), (2.0, 4.0), (3.0, 6.0)], 4.5) == pytest.approx(0.9)
    # a bd_log.csv file (path or str), with the target from the paper's table
    log = tmp_path / "bd_log.csv"
    log.write_text("step,time_s,reduced_time,bonds,mean_coordination,clusters,largest_cluster,msd_m2\n"
                   "0,0,0,0,0,1000,1,0\n100,1e-4,0.01,2000,4,300,50,1e-15\n200,2e-4,0.02,2520,5.04,20,900,2e-15\n")
    assert PAPER[0][1] == 4.52 and PAPER[15][1] == 4.97
    assert crossing_time(log, PAPER[0][1]) == pytest.approx(0.015)
    assert crossing_time(str(log), PAPER[15][1]) == pytest.approx(0.01 + 0.97 / 1.04 * 0.01)
    assert crossing_time(log, 5.08) is None
