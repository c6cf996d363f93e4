#!/usr/bin/python3
"""Charts of a `runout study` folder (docs/study.md), rendered headless.

    study_charts.py STUDY_DIR OUT_PREFIX [--title TEXT]

writes OUT_PREFIX_error_vs_wall.png (one point per run, the Pareto front the
study marked joined), OUT_PREFIX_convergence.png (error against cell size per
series, with the observed order the study fitted) and OUT_PREFIX_runout.png
(the toe runout history of every run). The functions take the rows of
read_study() so other charts can reuse them.
"""
import argparse
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")  # headless: no display needed
import matplotlib.pyplot as plt  # noqa: E402

ERROR = "err_runout_end"  # the error the study's Pareto front and order use


def number(text):
    """A CSV cell as a float; NaN when empty."""
    try:
        return float(text)
    except ValueError:
        return math.nan


def read_study(study_dir):
    """study.csv as a list of dicts, numbers as floats where they parse."""
    with open(os.path.join(study_dir, "study.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        for key, value in list(row.items()):
            if key not in ("id", "method", "backend", "shape", "status", "note", "reference"):
                row[key] = number(value)
    return rows


def series_label(row):
    """Runs of one series differ only by cell size."""
    label = "DAM" if row["method"] == "dam" else "MPM %s ppc %d" % (row["shape"], row["ppc"])
    if row["backend"] != "cpu":
        label += " " + row["backend"]
    if row.get("_many_domains"):
        label += ", x to %g m" % row["domain_x_max"]
    return label


def group(rows):
    """Finished runs by series label, each sorted by cell size."""
    series = {}
    for row in rows:
        if row["status"] == "ok":
            series.setdefault(series_label(row), []).append(row)
    return {k: sorted(v, key=lambda r: r["cell"]) for k, v in sorted(series.items())}


def usable(row, metric=ERROR):
    return row["status"] == "ok" and row[metric] > 0 and math.isfinite(row[metric])


def save(fig, ax, path, xlabel, ylabel, title):
    """Labels, grid and legend of a chart, written to path."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def error_label(metric):
    return "relative error of %s" % metric.replace("err_", "")


def chart_error_vs_wall(rows, path, title="", metric=ERROR):
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for label, runs in group(rows).items():
        pts = [r for r in runs if usable(r, metric)]
        ax.scatter([r["wall_s"] for r in pts], [r[metric] for r in pts], label=label, s=28)
        for r in pts:
            ax.annotate("h=%g" % r["cell"], (r["wall_s"], r[metric]), fontsize=7,
                        xytext=(3, 3), textcoords="offset points")
    front = sorted((r for r in rows if r.get("pareto") == 1 and usable(r, metric)),
                   key=lambda r: r["wall_s"])
    if front:
        ax.plot([r["wall_s"] for r in front], [r[metric] for r in front], "k--", lw=1,
                label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    save(fig, ax, path, "wall time per run [s]", error_label(metric), title or "Error against cost")


def chart_convergence(rows, path, title="", metric=ERROR):
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for label, runs in group(rows).items():
        pts = [r for r in runs if usable(r, metric)]
        if not pts:
            continue
        h = [r["cell"] for r in pts]
        e = [r[metric] for r in pts]
        p = pts[0]["observed_order"]
        line = ax.loglog(h, e, "o-", label=label + ("  (p = %.2f)" % p if math.isfinite(p) else ""))
        if math.isfinite(p) and len(pts) > 1:
            # The fitted e = C h^p through the points' geometric mean.
            log_c = sum(math.log(ei) - p * math.log(hi) for hi, ei in zip(h, e)) / len(h)
            ax.loglog(h, [math.exp(log_c) * hi ** p for hi in h], ":", color=line[0].get_color())
    save(fig, ax, path, "cell size h [m]", error_label(metric), title or "Convergence")


def read_history(path):
    """time and runout columns of a run's history.csv."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return [float(r["time"]) for r in rows], [float(r["runout"]) for r in rows]


def chart_runout_history(study_dir, rows, path, title="", analytic=None):
    """Toe runout against time for every finished run; analytic: (t, s) lists."""
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for label, runs in group(rows).items():
        for r in runs:
            hist = os.path.join(study_dir, "runs", r["id"], "history.csv")
            if os.path.exists(hist):
                t, s = read_history(hist)
                ax.plot(t, s, lw=1.2, label="%s, h = %g" % (label, r["cell"]))
    if analytic:
        ax.plot(analytic[0], analytic[1], "k--", lw=1, label="rigid block (exact)")
    save(fig, ax, path, "time [s]", "toe runout [m]", title or "Runout history")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("study_dir")
    parser.add_argument("out_prefix")
    parser.add_argument("--title", default="")
    parser.add_argument("--block-acceleration", type=float,
                        help="draw the rigid block's s = a t^2 / 2 on the runout chart")
    args = parser.parse_args()
    rows = read_study(args.study_dir)
    domains = {r["domain_x_max"] for r in rows}
    for r in rows:
        r["_many_domains"] = len(domains) > 1
    prefix = args.title + ": " if args.title else ""
    chart_error_vs_wall(rows, args.out_prefix + "_error_vs_wall.png", prefix + "error against cost")
    chart_convergence(rows, args.out_prefix + "_convergence.png", prefix + "convergence")
    analytic = None
    if args.block_acceleration is not None:
        end = max(r["end_time"] for r in rows if r["status"] == "ok")
        t = [end * k / 50 for k in range(51)]
        analytic = (t, [0.5 * args.block_acceleration * x * x for x in t])
    chart_runout_history(args.study_dir, rows, args.out_prefix + "_runout.png",
                         prefix + "toe runout", analytic)


if __name__ == "__main__":
    main()
