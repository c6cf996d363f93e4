#!/usr/bin/python3
"""Charts of a `runout study` folder (docs/study.md), rendered headless.

    study_charts.py STUDY_DIR OUT_PREFIX [--title TEXT] [--slopes]
                    [--exceedance] [--mechanism-map KEY_X KEY_Y]

writes OUT_PREFIX_error_vs_wall.png (one point per run, the Pareto front the
study marked joined), OUT_PREFIX_convergence.png (error against cell size per
series, with the observed order the study fitted) and OUT_PREFIX_runout.png
(the toe runout history of every run). With --slopes (a study over
--slope-angle) it writes OUT_PREFIX.png instead: the MPM and the
depth-averaged model against the slope angle, and prints their table.
With --exceedance (a study with --sample) it writes OUT_PREFIX_exceedance.png:
the probability that the runout exceeds x, with its 95 % confidence band
from the sample size; with --mechanism-map (a study with --set over two
keys) OUT_PREFIX_mechanism_map.png: the mechanism class of each point.
The functions take the rows of read_study() so other charts can reuse them.
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
            if key not in ("id", "method", "backend", "shape", "scene", "status", "note",
                           "mechanism", "reference"):
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


def label(ax, xlabel, ylabel, title):
    """Labels, grid and legend of one panel."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def write(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def save(fig, ax, path, xlabel, ylabel, title):
    """A one-panel chart, labelled, written to path."""
    label(ax, xlabel, ylabel, title)
    write(fig, path)


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


def read_columns(path, names):
    """The named columns of a run's history.csv, as lists of floats."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return [[float(r[name]) for r in rows] for name in names]


def read_history(path):
    """time and runout columns of a run's history.csv."""
    return tuple(read_columns(path, ("time", "runout")))


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


# The DAM against the MPM over slope angles: what is compared, and the
# relative difference beyond which the two are said to disagree.
SLOPE_METRICS = (("runout_end", "toe runout"), ("centroid_travel", "centroid travel"),
                 ("final_length", "length"), ("max_thickness_end", "max thickness"))
DISAGREE = 0.2


def finest_by_angle(study_dir, rows, method):
    """{slope angle: the method's finest finished run there}, each with the
    max_thickness at its end and the travel of its centroid along the base
    read from its history.csv."""
    runs = {}
    for r in rows:
        if r["method"] == method and r["status"] == "ok":
            runs.setdefault(r["slope_angle"], []).append(r)
    # Smallest cell, then most particles per cell (the DAM has none: NaN).
    finest = lambda r: (r["cell"], -r["ppc"] if math.isfinite(r["ppc"]) else 0)  # noqa: E731
    best = {angle: min(rs, key=finest) for angle, rs in runs.items()}
    for r in best.values():
        thickness, centroid = read_columns(
            os.path.join(study_dir, "runs", r["id"], "history.csv"), ("max_thickness", "centroid_s"))
        r["max_thickness_end"] = thickness[-1]
        r["centroid_travel"] = centroid[-1] - centroid[0]
    return best


def disagreement_spans(angles, diffs, limit=DISAGREE):
    """The angle ranges where |diff| > limit, ends interpolated linearly
    between the measured angles (the first and last measured angle bound it)."""
    spans, start = [], None
    for k, (a, d) in enumerate(zip(angles, diffs)):
        over = abs(d) > limit
        if over and start is None:
            start = a if k == 0 else crossing(angles[k - 1], diffs[k - 1], a, d, limit)
        if not over and start is not None:
            spans.append((start, crossing(angles[k - 1], diffs[k - 1], a, d, limit)))
            start = None
    if start is not None:
        spans.append((start, angles[-1]))
    return spans


def crossing(a0, d0, a1, d1, limit):
    """The angle between a0 and a1 where |diff| passes limit, linearly."""
    e0, e1 = abs(d0) - limit, abs(d1) - limit
    return a0 + (a1 - a0) * e0 / (e0 - e1)


def chart_dam_vs_mpm(study_dir, rows, path, title=""):
    """Runout, length and max thickness at the end against the slope angle
    for the MPM and the DAM (finest run of each per angle), and their
    relative difference (DAM - MPM) / MPM, the angles where the runouts
    differ by more than DISAGREE shaded. Returns the table's rows."""
    mpm, dam = finest_by_angle(study_dir, rows, "mpm"), finest_by_angle(study_dir, rows, "dam")
    angles = sorted(set(mpm) & set(dam))
    keys = [metric for metric, _ in SLOPE_METRICS]
    fig, axes = plt.subplot_mosaic([keys[0:2], keys[2:4], ["diff", "diff"]], figsize=(10, 10),
                                   sharex=True)
    table = []
    for a in angles:
        diffs = [(dam[a][m] - mpm[a][m]) / mpm[a][m] for m, _ in SLOPE_METRICS]
        table.append((a, mpm[a], dam[a], diffs))
    for metric, name in SLOPE_METRICS:
        ax = axes[metric]
        for method, runs in (("MPM", mpm), ("DAM", dam)):
            ax.plot(angles, [runs[a][metric] for a in angles], "o-", label=method)
        if metric in ("runout_end", "centroid_travel", "final_length"):
            ax.set_yscale("log")
        label(ax, "", name + " [m]", name + " at the end")
    ax = axes["diff"]
    for k, (_, name) in enumerate(SLOPE_METRICS):
        ax.plot(angles, [100 * t[3][k] for t in table], "o-", label=name)
    runout_diffs = [t[3][0] for t in table]
    for n, (lo, hi) in enumerate(disagreement_spans(angles, runout_diffs)):
        ax.axvspan(lo, hi, color="tab:red", alpha=0.12,
                   label="runouts differ > %d %%" % (100 * DISAGREE) if n == 0 else None)
    for y in (-100 * DISAGREE, 100 * DISAGREE):
        ax.axhline(y, color="k", ls=":", lw=1)
    ax.set_yscale("symlog", linthresh=100 * DISAGREE)
    label(ax, "slope angle [deg]", "(DAM - MPM) / MPM [%]", "relative difference")
    fig.suptitle(title or "DAM against MPM over slope angles")
    write(fig, path)
    return table


def print_slope_table(table):
    """The table of chart_dam_vs_mpm as Markdown."""
    print("| slope [deg] | " + " | ".join("MPM %s [m] | DAM %s [m] | difference" % (n, n)
                                          for _, n in SLOPE_METRICS)
          + " | MPM end [s] | DAM end [s] | MPM wall [s] | DAM wall [s] |")
    print("|" + " --- |" * (1 + 3 * len(SLOPE_METRICS) + 4))
    for a, m, d, diffs in table:
        cells = ["%g" % a]
        for (metric, _), diff in zip(SLOPE_METRICS, diffs):
            cells += ["%.3g" % m[metric], "%.3g" % d[metric], "%+.0f %%" % (100 * diff)]
        cells += ["%.3g" % m["end_time"], "%.3g" % d["end_time"], "%.3g" % m["wall_s"],
                  "%.2g" % d["wall_s"]]
        print("| " + " | ".join(cells) + " |")


def dkw_epsilon(n, alpha=0.05):
    """Half-width of the Dvoretzky-Kiefer-Wolfowitz band: with probability
    1 - alpha the true distribution function lies within it of the
    empirical one everywhere (Massart's constant), whatever the
    distribution."""
    return math.sqrt(math.log(2.0 / alpha) / (2.0 * n))


def exceedance(values):
    """(x, P(X > x)) of the sample as a step function: x sorted, and after
    the k-th smallest value (k from 1) the fraction above it, 1 - k / n."""
    x = sorted(values)
    n = len(x)
    return x, [1.0 - (k + 1) / n for k in range(n)]


def chart_exceedance(rows, path, title="", metric="runout_end", alpha=0.05):
    """P(runout > x) of the finished runs, its 1 - alpha DKW band shaded;
    the title says how many of the study's runs that is (a run that blew
    up has no runout to count). Returns (n, epsilon)."""
    values = [r[metric] for r in rows if r["status"] == "ok" and math.isfinite(r[metric])]
    n, ran = len(values), sum(r["status"] != "skipped" for r in rows)
    if n == 0:
        raise SystemExit("no finished run has a %s" % metric)
    x, p = exceedance(values)
    eps = dkw_epsilon(n, alpha)
    # As steps (each value holds until the next x): 1 left of the smallest
    # value, a drop of 1 / n at each.
    pad = 0.05 * (x[-1] - x[0] or abs(x[0]) or 1.0)
    xs, ps = [x[0] - pad] + x, [1.0] + p
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    ax.fill_between(xs, [max(0.0, q - eps) for q in ps], [min(1.0, q + eps) for q in ps],
                    step="post", color="tab:blue", alpha=0.2,
                    label="%d %% band (DKW, n = %d: ±%.2f)" % (100 * (1 - alpha), n, eps))
    ax.step(xs, ps, where="post", color="tab:blue", lw=1.5, label="empirical P(%s > x)" % metric)
    ax.set_ylim(0, 1.02)
    save(fig, ax, path, "%s x [m]" % metric, "probability of exceedance",
         "%s (%d of %d runs finished)" % (title or "Probability that the runout exceeds x", n, ran))
    return n, eps


# Colours and markers of the mechanism classes (summary.json's names).
MECHANISMS = {"elongation": ("tab:blue", "o"), "block sliding": ("tab:green", "s"),
              "spreading": ("tab:red", "^"), "undetermined": ("tab:gray", "x"),
              "": ("k", "."), "failed": ("k", "X")}


def chart_mechanism_map(rows, key_x, key_y, path, title=""):
    """The mechanism class at each (key_x, key_y) of the study: per point,
    the finest finished MPM run (smallest cell, most particles per cell).
    Returns {(x, y): mechanism}."""
    best = {}
    for r in rows:
        if r["method"] != "mpm" or r["status"] not in ("ok", "failed"):
            continue
        point = (r[key_x], r[key_y])
        rank = (r["cell"], -r["ppc"])
        if point not in best or rank < best[point][0]:
            best[point] = (rank, r)
    classes = {p: (r["mechanism"] if r["status"] == "ok" else "failed") for p, (_, r) in best.items()}
    xs, ys = sorted({p[0] for p in classes}), sorted({p[1] for p in classes})
    fig, ax = plt.subplots(figsize=(7.4, 4.4))
    for name in MECHANISMS:
        pts = [p for p, c in classes.items() if c == name]
        if pts:
            colour, marker = MECHANISMS[name]
            ax.scatter([p[0] for p in pts], [p[1] for p in pts], s=90, c=colour, marker=marker,
                       label=name or "not classified")
    # Keys swept over decades (a sensitivity of 1 to 40) read better on a
    # log axis, ticked at the values swept; the legend goes beside the map.
    for log, ticks, names, values in ((ax.set_xscale, ax.set_xticks, ax.set_xticklabels, xs),
                                      (ax.set_yscale, ax.set_yticks, ax.set_yticklabels, ys)):
        if min(values) > 0 and max(values) >= 8 * min(values):
            log("log")
        ticks(values)
        names(["%g" % v for v in values])
    ax.minorticks_off()
    ax.margins(0.1)
    label(ax, key_x, key_y, title or "Mechanism map")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    write(fig, path)
    return classes


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("study_dir")
    parser.add_argument("out_prefix")
    parser.add_argument("--title", default="")
    parser.add_argument("--block-acceleration", type=float,
                        help="draw the rigid block's s = a t^2 / 2 on the runout chart")
    parser.add_argument("--slopes", action="store_true",
                        help="a study over --slope-angle: the DAM against the MPM, OUT_PREFIX.png")
    parser.add_argument("--exceedance", action="store_true",
                        help="a sampled study: P(runout > x) with its confidence band")
    parser.add_argument("--mechanism-map", nargs=2, metavar=("KEY_X", "KEY_Y"),
                        help="the mechanism class over two keys of the study")
    args = parser.parse_args()
    rows = read_study(args.study_dir)
    if args.exceedance or args.mechanism_map:
        if args.exceedance:
            n, eps = chart_exceedance(rows, args.out_prefix + "_exceedance.png", args.title)
            print("exceedance: %d runs, DKW 95 %% band ±%.3f" % (n, eps))
        if args.mechanism_map:
            classes = chart_mechanism_map(rows, *args.mechanism_map,
                                          args.out_prefix + "_mechanism_map.png", args.title)
            for (x, y), c in sorted(classes.items()):
                print("%g, %g: %s" % (x, y, c))
        return
    if args.slopes:
        print_slope_table(chart_dam_vs_mpm(args.study_dir, rows, args.out_prefix + ".png",
                                           args.title))
        return
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
