"""A collected field of a study against one of its swept options: the mean over the
realizations with error bars (standard error by default, or the SD), one line per value of a
second swept option when ``--by`` names one. Reads DIR/summary.csv of ``packlab study``
(docs/study.md)."""

from packlab.plot._common import UsageError, argument, new_figure, run


def _read(path):
    import csv

    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def _number(text):
    try:
        return float(text)
    except ValueError:
        return None


def figure(study_dir, x, y, by=None, errors="se", logx=False, logy=False):
    import os

    rows = _read(os.path.join(study_dir, "summary.csv"))
    if not rows:
        raise UsageError(f"{study_dir}/summary.csv has no rows")
    columns = list(rows[0])
    fields = sorted({c.rsplit("_", 1)[0] for c in columns if c.endswith("_mean")})
    swept = columns[:columns.index("tasks")]
    if x not in swept:
        raise UsageError(f"--x {x}: not a swept option of this study: must be one of {', '.join(swept) or '(none)'}")
    if y not in fields:
        raise UsageError(f"--y {y}: not a collected field: must be one of {', '.join(fields) or '(none)'}")
    if by is not None and by not in swept:
        raise UsageError(f"--by {by}: not a swept option of this study: must be one of {', '.join(swept)}")
    groups = {}
    for row in rows:
        if _number(row[f"{y}_mean"]) is None:
            continue  # no finished task at this point
        groups.setdefault(row[by] if by else None, []).append(row)
    fig, ax = new_figure()
    for label, group in groups.items():
        numeric = all(_number(r[x]) is not None for r in group)
        group.sort(key=lambda r: _number(r[x]) if numeric else r[x])
        xs = [_number(r[x]) if numeric else r[x] for r in group]
        means = [float(r[f"{y}_mean"]) for r in group]
        bars = [_number(r[f"{y}_{errors}"]) or 0.0 for r in group]
        ax.errorbar(xs, means, yerr=bars, fmt="o-", ms=4, capsize=3,
                    label=None if label is None else f"{by} = {label}")
    ax.set_xlabel(x)
    ax.set_ylabel(f"{y} (mean ± {'standard error' if errors == 'se' else 'SD'})")
    counts = sorted({r[f"{y}_count"] for g in groups.values() for r in g})
    ax.set_title(f"{os.path.basename(os.path.normpath(study_dir))}: {'/'.join(counts)} realizations per point",
                 fontsize=9)
    if logx:
        ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
    if by:
        ax.legend(fontsize=8)
    return fig


def main(argv):
    return run("study", argv, figure, argument("study_dir", help="the --out folder of packlab study"),
               argument("--x", required=True, help="a swept option (a column of summary.csv)"),
               argument("--y", required=True, help="a collected field (report.json path)"),
               argument("--by", default=None, help="a second swept option: one line per value"),
               argument("--errors", choices=("se", "sd"), default="se", help="error bars: standard error or SD"),
               argument("--logx", action="store_true"), argument("--logy", action="store_true"))
