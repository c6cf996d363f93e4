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
import re

import matplotlib

matplotlib.use("Agg")  # headless: no display needed
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import FixedLocator, FuncFormatter, MaxNLocator, NullFormatter  # noqa: E402

ERROR = "err_runout_end"  # the error the study's Pareto front and order use

# Okabe & Ito's eight colours, told apart with every common colour-vision
# deficiency: the categorical colours of every chart here (series, methods,
# mechanism classes). Cell sizes, an ordered quantity, take one sequential
# colormap instead (CELL_COLOURS), dark for the finest cell.
OKABE_ITO = ("#0072B2", "#E69F00", "#009E73", "#D55E00", "#CC79A7", "#56B4E9", "#F0E442",
             "#000000")
CELL_COLOURS = "viridis"
plt.rcParams.update({"axes.prop_cycle": matplotlib.cycler(color=OKABE_ITO[:6]),
                     "legend.fontsize": 8, "axes.titlesize": 11, "axes.labelsize": 10})
LINESTYLES = ("-", "--", "-.", ":")  # particles per cell, fewest first
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*")  # cell sizes, coarsest first
FIGURES = []  # every figure written, latest last (tests/study_charts_check.py inspects them)

# Readable names of the numbers a study reports and of the scene keys it
# sweeps: (name, unit, factor from the CSV's value to the unit's).
METRICS = {"runout_end": ("toe runout at the end", "m"),
           "peak_toe_velocity": ("peak toe velocity", "m/s"),
           "final_length": ("length at the end", "m")}
KEYS = {"sensitivity": ("sensitivity $S_t$", "", 1.0),
        "shear_strength": ("interface shear strength τ", "kPa", 1e-3),
        "su0": ("undrained shear strength $s_{u0}$", "kPa", 1e-3),
        "xi95": ("softening parameter $ξ_{95}$", "", 1.0),
        "band_thickness": ("band thickness $t_s$", "m", 1.0),
        "slope_angle": ("slope angle", "deg", 1.0),
        "cell": ("cell size h", "m", 1.0),
        "ppc": ("particles per cell per direction", "", 1.0),
        "domain_x_max": ("far end of the domain", "m", 1.0)}


def metric_name(metric):
    """'runout_t5' -> 'toe runout at t = 5 s'; the study's columns in words."""
    metric = metric.replace("err_", "")
    time = re.fullmatch(r"runout_t([\d.]+)", metric)
    if time:
        return "toe runout at t = %s s" % time.group(1)
    return METRICS.get(metric, (metric.replace("_", " "), ""))[0]


def key_name(key):
    """(axis label, factor) of a scene key by its table path: its last part
    looked up in KEYS ('material.clay.sensitivity' -> 'sensitivity $S_t$ [-]'),
    else that part in words."""
    last = key.split(".")[-1]
    name, unit, factor = KEYS.get(last, (last.replace("_", " "), "", 1.0))
    return (name + (" [%s]" % unit if unit else " [-]")), factor


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


def panel_label(row):
    """What a run's panel shows: the method, its shape functions and
    backend (and domain where the study has several)."""
    if row["method"] == "dam":
        label = "depth-averaged model"
    else:
        label = "MPM, %s" % ("GIMP" if row["shape"] == "gimp" else row["shape"])
    if row["backend"] != "cpu":
        label += ", " + row["backend"].upper()
    if row.get("_many_domains"):
        label += ", x to %g m" % row["domain_x_max"]
    return label


def ppc_label(ppc):
    return "%d x %d particles per cell" % (ppc, ppc)


def series_label(row):
    """Runs of one series differ only by cell size."""
    label = panel_label(row)
    if row["method"] != "dam":
        label += ", %d x %d particles" % (row["ppc"], row["ppc"])
    return label


def group(rows):
    """Finished runs by series label, each sorted by cell size."""
    series = {}
    for row in rows:
        if row["status"] == "ok":
            series.setdefault(series_label(row), []).append(row)
    return {k: sorted(v, key=lambda r: r["cell"]) for k, v in sorted(series.items())}


def series_styles(rows):
    """{series label: colour}, one Okabe-Ito colour per series in order."""
    return {name: OKABE_ITO[k % len(OKABE_ITO)] for k, name in enumerate(group(rows))}


def cell_styles(cells):
    """{cell size: (colour, marker)}: the sequential colormap from the
    finest (dark) to the coarsest cell (light green, short of its pale
    yellow end), a marker per cell, coarsest first."""
    cells = sorted(set(cells))
    cmap = plt.get_cmap(CELL_COLOURS)
    n = len(cells)
    return {h: (cmap(0.8 * k / max(1, n - 1)), MARKERS[(n - 1 - k) % len(MARKERS)])
            for k, h in enumerate(cells)}


def reference_name(rows):
    """What the study's errors are measured against, in words."""
    refs = {r.get("reference", "") for r in rows if r["status"] == "ok"} - {""}
    if refs == {"analytic-block"}:
        return "the rigid block (exact)"
    ids = {r["id"]: r for r in rows}
    if len(refs) == 1 and next(iter(refs)) in ids:
        ref = ids[next(iter(refs))]
        return "%s, h = %g m" % (series_label(ref), ref["cell"])
    return "the finest run"


def usable(row, metric=ERROR):
    return row["status"] == "ok" and row[metric] > 0 and math.isfinite(row[metric])


def nice_log_ticks(lo, hi, wanted=4):
    """Round values between lo and hi for a log axis: the decades, then
    1-2-5, then finer mantissas, the first set with at least `wanted`; on
    a range of under a factor 4, evenly spaced round values (0.8, 0.9, 1,
    1.1), as a linear axis has."""
    if hi < 4 * lo:
        return [v for v in MaxNLocator(nbins=wanted + 1, steps=[1, 2, 2.5, 5, 10])
                .tick_values(lo, hi) if lo <= v <= hi]
    mantissas = ((1,), (1, 2, 5), (1, 1.5, 2, 3, 5, 7), (1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8))
    ticks = []
    for mants in mantissas:
        ticks = sorted({round(m * 10 ** e, 12) for e in range(math.floor(math.log10(lo)) - 1,
                                                               math.ceil(math.log10(hi)) + 1)
                        for m in mants if lo <= m * 10 ** e <= hi})
        if len(ticks) >= wanted:
            break
    return ticks


def tick_text(v):
    return "%g" % float("%.3g" % v)


def readable_log_axis(ax, axis, values=None):
    """Plain numbers (0.25, 1.5, 40) on a log axis instead of 10^k and
    2 x 10^-1: at the given values (the cell sizes swept), else at round
    ones spread over the whole axis; minor ticks unlabelled."""
    a = ax.xaxis if axis == "x" else ax.yaxis
    lo, hi = sorted(ax.get_xlim() if axis == "x" else ax.get_ylim())
    ticks = sorted(set(values)) if values else nice_log_ticks(lo, hi)
    a.set_major_locator(FixedLocator(ticks))
    a.set_major_formatter(FuncFormatter(lambda v, _: tick_text(v)))
    a.set_minor_formatter(NullFormatter())
    (ax.set_xlim if axis == "x" else ax.set_ylim)(lo, hi)


def label(ax, xlabel, ylabel, title, legend=True):
    """Labels, grid and legend of one panel."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="major", alpha=0.3)
    if legend:
        ax.legend()


def write(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    FIGURES.append(fig)


def save(fig, ax, path, xlabel, ylabel, title):
    """A one-panel chart, labelled, written to path."""
    label(ax, xlabel, ylabel, title)
    write(fig, path)


def error_label(metric):
    return "relative error of the %s [%%]" % metric_name(metric)


def cell_legend(ax, cells, loc, title="cell size h", colour=True, marker=True, **kw):
    """A legend of the cell sizes alone, added beside the panel's others."""
    styles = cell_styles(cells)
    handles = [Line2D([], [], color=styles[h][0] if colour else "0.35",
                      marker=styles[h][1] if marker else None, ls="-" if not marker else "",
                      label="%g m" % h) for h in sorted(styles, reverse=True)]
    return ax.add_artist(ax.legend(handles=handles, title=title, title_fontsize=8, loc=loc, **kw))


def chart_error_vs_wall(rows, path, title="", metric=ERROR):
    """One point per run: the series by colour, the cell size by marker (no
    text at the points, so nothing overlaps), each series joined from its
    coarsest to its finest cell; the study's Pareto front dashed."""
    fig, ax = plt.subplots(figsize=(8.4, 4.6))
    colours = series_styles(rows)
    cells = cell_styles(r["cell"] for r in rows if usable(r, metric))
    for name, runs in group(rows).items():
        pts = sorted((r for r in runs if usable(r, metric)), key=lambda r: -r["cell"])
        if not pts:
            continue
        ax.plot([r["wall_s"] for r in pts], [100 * r[metric] for r in pts], "-", lw=1.2,
                color=colours[name], alpha=0.8, label=name)
        for r in pts:
            ax.plot(r["wall_s"], 100 * r[metric], ls="", marker=cells[r["cell"]][1], ms=7,
                    mfc=colours[name], mec="k", mew=0.5)
    front = sorted((r for r in rows if r.get("pareto") == 1 and usable(r, metric)),
                   key=lambda r: r["wall_s"])
    if front:
        ax.plot([r["wall_s"] for r in front], [100 * r[metric] for r in front], "k--", lw=1,
                label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.margins(0.08)
    readable_log_axis(ax, "x")
    readable_log_axis(ax, "y")
    label(ax, "wall time per run, one thread [s]", error_label(metric),
          title or "Error against cost", legend=False)
    cell_legend(ax, cells, "upper left", colour=False, bbox_to_anchor=(1.02, 0.45))
    ax.legend(title="errors against\n" + reference_name(rows), title_fontsize=8,
              loc="lower left", bbox_to_anchor=(1.02, 0.5))
    write(fig, path)


def chart_convergence(rows, path, title="", metric=ERROR):
    """Error against cell size per series, the fitted e = C h^p dotted in
    the series' colour, p in the legend; the axes ticked at the cells."""
    fig, ax = plt.subplots(figsize=(8.4, 4.6))
    colours = series_styles(rows)
    cells = set()
    for name, runs in group(rows).items():
        pts = [r for r in runs if usable(r, metric)]
        if not pts:
            continue
        h = [r["cell"] for r in pts]
        e = [100 * r[metric] for r in pts]
        cells.update(h)
        p = pts[0]["observed_order"]
        ax.loglog(h, e, "o-", color=colours[name],
                  label=name + ("  (p = %.2f)" % p if math.isfinite(p) else ""))
        if math.isfinite(p) and len(pts) > 1:
            # The fitted e = C h^p through the points' geometric mean.
            log_c = sum(math.log(ei) - p * math.log(hi) for hi, ei in zip(h, e)) / len(h)
            ax.loglog(h, [math.exp(log_c) * hi ** p for hi in h], ":", color=colours[name])
    ax.plot([], [], "k:", label="fitted $C\,h^p$")
    ax.margins(0.08)
    readable_log_axis(ax, "x", sorted(cells))
    readable_log_axis(ax, "y")
    label(ax, "cell size h [m]", error_label(metric), title or "Convergence", legend=False)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0),
              title="errors against\n" + reference_name(rows), title_fontsize=8)
    write(fig, path)


def read_columns(path, names):
    """The named columns of a run's history.csv, as lists of floats."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return [[float(r[name]) for r in rows] for name in names]


def read_history(path):
    """time and runout columns of a run's history.csv."""
    return tuple(read_columns(path, ("time", "runout")))


def chart_runout_history(study_dir, rows, path, title="", analytic=None):
    """Toe runout against time of every finished run, one panel per method
    (and shape functions), the cell size by colour (one sequential map,
    darkest finest), the particles per cell by line style; below, each
    run's difference from the reference: analytic, the rigid block's
    (t, s) lists, or else the study's reference run."""
    import numpy as np
    ok = [r for r in rows if r["status"] == "ok"
          and os.path.exists(os.path.join(study_dir, "runs", r["id"], "history.csv"))]
    panels = sorted({panel_label(r) for r in ok})
    ppcs = sorted({r["ppc"] for r in ok if math.isfinite(r["ppc"])})
    cells = cell_styles(r["cell"] for r in ok)
    history = {r["id"]: read_history(os.path.join(study_dir, "runs", r["id"], "history.csv"))
               for r in ok}
    ref_ids = {r.get("reference", "") for r in ok} - {"", "analytic-block"}
    ref_id = next(iter(ref_ids)) if len(ref_ids) == 1 and next(iter(ref_ids)) in history else None
    if analytic:
        reference, ref_name = analytic, "rigid block (exact)"
    elif ref_id:
        ref = next(r for r in ok if r["id"] == ref_id)
        reference = history[ref_id]
        ref_name = "reference: %s, h = %g m" % (series_label(ref).replace("MPM, GIMP", "MPM GIMP"),
                                                ref["cell"])
    else:
        reference, ref_name = None, ""
    nrows = 2 if reference else 1
    size = (4.2 * len(panels) + 2.4, 3.2 * nrows + 0.6)
    fig, axes = plt.subplots(nrows, len(panels), figsize=size, sharex=True, sharey="row",
                             squeeze=False, gridspec_kw={"height_ratios": [1.6, 1][:nrows]})
    for col, panel in enumerate(panels):
        top = axes[0][col]
        for r in sorted((r for r in ok if panel_label(r) == panel), key=lambda r: -r["cell"]):
            t, s = history[r["id"]]
            style = LINESTYLES[ppcs.index(r["ppc"]) % len(LINESTYLES)] if math.isfinite(r["ppc"]) \
                else "-"
            colour = cells[r["cell"]][0]
            top.plot(t, s, ls=style, color=colour, lw=1.3)
            if reference and r["id"] != ref_id:
                d = np.asarray(s) - np.interp(t, reference[0], reference[1])
                axes[1][col].plot(t, d, ls=style, color=colour, lw=1.3)
        if reference:
            top.plot(reference[0], reference[1], color="k", ls=(0, (1, 1.5)), lw=1.4)
            axes[1][col].axhline(0, color="k", ls=(0, (1, 1.5)), lw=1.4)
        top.set_title(panel)
        for row in range(nrows):
            axes[row][col].grid(True, alpha=0.3)
        axes[-1][col].set_xlabel("time [s]")
    axes[0][0].set_ylabel("toe runout [m]")
    if reference:
        axes[1][0].set_ylabel("difference from the\nreference [m]" if not analytic
                              else "difference from the\nrigid block [m]")
    # One legend beside the panels: the cells, the particles per cell, the reference.
    handles = [Line2D([], [], color=cells[h][0], lw=2, label="h = %g m" % h)
               for h in sorted(cells, reverse=True)]
    if len(ppcs) > 1:
        handles += [Line2D([], [], color="0.3", ls=LINESTYLES[k % len(LINESTYLES)],
                           label=ppc_label(p)) for k, p in enumerate(ppcs)]
    if reference:
        handles.append(Line2D([], [], color="k", ls=(0, (1, 1.5)), lw=1.4, label=ref_name))
    axes[0][-1].legend(handles=handles, loc="upper left", bbox_to_anchor=(1.03, 1.0))
    fig.suptitle(title or "Runout history")
    write(fig, path)


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
    for k, (metric, name) in enumerate(SLOPE_METRICS):
        ax = axes[metric]
        for (method, runs), colour, marker in ((("MPM", mpm), OKABE_ITO[0], "o"),
                                               (("depth-averaged model", dam), OKABE_ITO[1], "s")):
            ax.plot(angles, [runs[a][metric] for a in angles], "-", marker=marker, color=colour,
                    ms=5, label=method)
        # Half-width panels over a full-width one: each is read on its own
        # angle axis, so each carries its tick labels and name.
        ax.xaxis.set_tick_params(labelbottom=True)
        label(ax, "slope angle [deg]", name + " [m]", name + " at the end", legend=k == 0)
        if metric in ("runout_end", "centroid_travel"):  # over two decades
            ax.set_yscale("log")
            readable_log_axis(ax, "y")
    ax = axes["diff"]
    for k, (_, name) in enumerate(SLOPE_METRICS):
        ax.plot(angles, [100 * t[3][k] for t in table], "-", marker=MARKERS[k], ms=5,
                color=OKABE_ITO[(2, 4, 3, 5)[k]], label=name)
    runout_diffs = [t[3][0] for t in table]
    for n, (lo, hi) in enumerate(disagreement_spans(angles, runout_diffs)):
        ax.axvspan(lo, hi, color=OKABE_ITO[3], alpha=0.12,
                   label="toe runouts differ by more than %d %%" % (100 * DISAGREE)
                   if n == 0 else None)
    for n, y in enumerate((-100 * DISAGREE, 100 * DISAGREE)):
        ax.axhline(y, color="k", ls=":", lw=1,
                   label="±%d %%" % (100 * DISAGREE) if n == 0 else None)
    largest = max((abs(d) for t in table for d in t[3]), default=0.0)
    if largest > 1.0:  # a difference over 100 %: a linear band of +-20 %, log beyond
        ax.set_yscale("symlog", linthresh=100 * DISAGREE)
        ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: tick_text(v)))
    else:
        ax.set_ylim(-125 * DISAGREE, 125 * DISAGREE)
    label(ax, "slope angle [deg]", "(DAM - MPM) / MPM [%]",
          "relative difference, depth-averaged model against MPM", legend=False)
    ax.legend(ncol=3, loc="lower right")
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
                    step="post", color=OKABE_ITO[0], alpha=0.2,
                    label="%d %% band (DKW, n = %d: ±%.2f)" % (100 * (1 - alpha), n, eps))
    ax.step(xs, ps, where="post", color=OKABE_ITO[0], lw=1.5,
            label="empirical P(X > x), X the %s" % metric_name(metric))
    # Runs still moving at their end (no stop time where others have one):
    # their runouts are lower bounds, marked where they sit on the steps.
    moving = [r[metric] for r in rows if r["status"] == "ok" and math.isfinite(r[metric])
              and not math.isfinite(r.get("stop_time", math.nan))]
    if 0 < len(moving) < n:
        ax.plot(moving, [sum(v > m for v in values) / n for m in moving], ">", ms=7,
                color=OKABE_ITO[3], mec="k", mew=0.5, ls="",
                label="still moving at the end (a lower bound), %d runs" % len(moving))
    ax.set_ylim(0, 1.02)
    save(fig, ax, path, "%s x [m]" % metric_name(metric), "probability of exceedance P(X > x)",
         "%s (%d of %d runs finished)" % (title or "Probability that the runout exceeds x", n, ran))
    return n, eps


# Colours (Okabe-Ito) and markers of the mechanism classes (summary.json's names).
MECHANISMS = {"elongation": (OKABE_ITO[0], "o"), "block sliding": (OKABE_ITO[2], "s"),
              "spreading": (OKABE_ITO[3], "^"), "undetermined": ("0.55", "X"),
              "": ("k", "."), "failed": ("k", "x")}


def chart_mechanism_map(rows, key_x, key_y, path, title=""):
    """The mechanism class at each (key_x, key_y) of the study: per point,
    the finest finished MPM run (smallest cell, most particles per cell),
    its runout at the end written under it. The axes are named in words
    with units (key_name). Returns {(x, y): mechanism}."""
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
    (x_label, x_factor), (y_label, y_factor) = key_name(key_x), key_name(key_y)
    fig, ax = plt.subplots(figsize=(7.8, 4.6))
    for name in MECHANISMS:
        pts = [p for p, c in classes.items() if c == name]
        if pts:
            colour, marker = MECHANISMS[name]
            edge = {"edgecolors": "k", "linewidths": 0.5} if marker in "os^X" else {}
            ax.scatter([p[0] for p in pts], [p[1] for p in pts], s=110, c=colour, marker=marker,
                       label=name or "not classified", zorder=3, **edge)
    for p, (_, r) in best.items():
        runout = r.get("runout_end", math.nan)
        if r["status"] == "ok" and isinstance(runout, float) and math.isfinite(runout):
            ax.annotate(("%.0f m" if runout >= 10 else "%.1f m") % runout, p, xytext=(0, -15),
                        textcoords="offset points",
                        ha="center", va="center", fontsize=7, color="0.25")
    # Keys swept over decades (a sensitivity of 1 to 40) read better on a
    # log axis, ticked at the values swept, in the unit of the axis label.
    for log, ticks, names, values, factor in (
            (ax.set_xscale, ax.set_xticks, ax.set_xticklabels, xs, x_factor),
            (ax.set_yscale, ax.set_yticks, ax.set_yticklabels, ys, y_factor)):
        if min(values) > 0 and max(values) >= 8 * min(values):
            log("log")
        ticks(values)
        names([tick_text(v * factor) for v in values])
    ax.minorticks_off()
    ax.margins(0.12)
    label(ax, x_label, y_label, title or "Mechanism map", legend=False)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), title="mechanism",
              labelspacing=1.0, borderpad=0.8)
    ax.text(1.03, 0.02, "under each point:\nthe toe runout\nat the end", transform=ax.transAxes,
            fontsize=7, color="0.25", va="bottom")
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
