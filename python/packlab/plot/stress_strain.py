"""Compression test: stress-strain curve with the Young's modulus fit and the peak, or the
force-displacement curve (the ``curve.csv`` written by ``packlab test compress``). Several
curves may be given (e.g. two strain rates) and are drawn together; from Python a curve may
also be a dict of columns (as ``read_csv`` returns them: strain, stress, ...)."""

from packlab.plot._common import argument, new_figure, read_csv, run


def figure(curve_csvs, modulus=0.0, intercept=0.0, fit_begin=0.0, fit_end=0.0, force_displacement=False, labels=None):
    fig, ax = new_figure()
    if isinstance(curve_csvs, (str, dict)):
        curve_csvs = [curve_csvs]
    for k, path in enumerate(curve_csvs):
        data = path if isinstance(path, dict) else read_csv(path)
        if labels and k < len(labels):
            label = labels[k]
        else:
            label = path if len(curve_csvs) > 1 and not isinstance(path, dict) else None
        if force_displacement:
            ax.plot(data["displacement"] * 1e9, data["force"] * 1e6, label=label)
        else:
            ax.plot(data["strain"] * 100, data["stress"] * 1e-6, label=label)
            peak = data["stress"].argmax()
            ax.plot([data["strain"][peak] * 100], [data["stress"][peak] * 1e-6], "kv", ms=5)
    if force_displacement:
        ax.set_xlabel("plate displacement [nm]")
        ax.set_ylabel("plate force [µN]")
        ax.set_title("force–displacement")
    else:
        if modulus > 0 and fit_end > fit_begin:
            import numpy as np

            e = np.linspace(fit_begin, fit_end, 10)
            ax.plot(e * 100, (modulus * e + intercept) * 1e-6, "r--", lw=2,
                    label=f"E = {modulus * 1e-9:.3g} GPa")
        ax.set_xlabel("strain [%]")
        ax.set_ylabel("stress [MPa]")
        ax.set_title("stress–strain")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)
    return fig


def main(argv):
    return run("stress_strain", argv, figure, argument("curve_csv", nargs="+"),
               argument("--modulus", type=float, default=0.0), argument("--intercept", type=float, default=0.0),
               argument("--fit-begin", type=float, default=0.0), argument("--fit-end", type=float, default=0.0),
               argument("--force-displacement", action="store_true"), argument("--labels", nargs="*"))
