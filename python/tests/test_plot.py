"""packlab.plot figures from tables written by Python (packlab.write_table)."""

import matplotlib

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
