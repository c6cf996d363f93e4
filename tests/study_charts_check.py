#!/usr/bin/python3
"""scripts/study_charts.py's charts on synthetic studies of known answer:
the exceedance steps, the DKW band's half-width, and the mechanism map's
pick of the finest run per point; and every chart, drawn, judged as a
reader would: every axis labelled in words (no CSV column or scene key
path), log axes ticked in plain numbers over most of their length, no two
texts overlapping, at most 10 entries a legend and no two entries alike,
colours from the colour-blind-safe palette, greys or the one sequential
colormap.

    study_charts_check.py SOURCE_DIR
"""
import csv
import math
import os
import re
import sys
import tempfile

import matplotlib.colors as mcolors

sys.path.insert(0, os.path.join(sys.argv[1], "scripts"))
import study_charts  # noqa: E402

# P(X > x) after each sorted value: 3 of 4 above the smallest, then 2, 1, 0.
x, p = study_charts.exceedance([4.0, 1.0, 3.0, 2.0])
assert x == [1.0, 2.0, 3.0, 4.0], x
assert p == [0.75, 0.5, 0.25, 0.0], p
# Massart's DKW: P(sup |F_n - F| > eps) <= 2 exp(-2 n eps^2) = alpha.
eps = study_charts.dkw_epsilon(64, 0.05)
assert abs(2 * math.exp(-2 * 64 * eps * eps) - 0.05) < 1e-12, eps
assert abs(eps - 0.16976) < 1e-4, eps

with tempfile.TemporaryDirectory() as d:
    columns = ["id", "method", "status", "cell", "ppc", "su0", "tau", "mechanism", "runout_end"]
    rows = [
        # two cells at one point: the finer one's class is the point's
        ["a", "mpm", "ok", "0.8", "2", "2000", "500", "elongation", "30"],
        ["b", "mpm", "ok", "0.4", "2", "2000", "500", "spreading", "31"],
        ["c", "mpm", "ok", "0.8", "2", "3000", "500", "block sliding", "20"],
        ["d", "mpm", "failed", "0.8", "2", "3000", "1000", "", ""],
        ["e", "dam", "ok", "0.8", "", "3000", "1000", "", "10"],
    ]
    with open(os.path.join(d, "study.csv"), "w", newline="") as f:
        csv.writer(f).writerows([columns] + rows)
    study = study_charts.read_study(d)
    classes = study_charts.chart_mechanism_map(study, "su0", "tau", os.path.join(d, "map.png"))
    assert classes == {(2000.0, 500.0): "spreading", (3000.0, 500.0): "block sliding",
                       (3000.0, 1000.0): "failed"}, classes
    n, band = study_charts.chart_exceedance(study, os.path.join(d, "exc.png"))
    assert n == 4 and abs(band - study_charts.dkw_epsilon(4)) < 1e-15, (n, band)
    for chart in ("map.png", "exc.png"):
        assert os.path.getsize(os.path.join(d, chart)) > 1000, chart
# --- Every chart, judged by looking at it --------------------------------

VIRIDIS = [mcolors.to_hex(c) for c in
           study_charts.plt.get_cmap(study_charts.CELL_COLOURS)(range(256))]
SAFE = {mcolors.to_hex(c) for c in study_charts.OKABE_ITO} | set(VIRIDIS)


def safe_colour(c):
    """An Okabe-Ito colour, a grey, or one of the sequential colormap's."""
    r, g, b, a = mcolors.to_rgba(c)
    return a == 0 or (abs(r - g) < 1e-6 and abs(g - b) < 1e-6) or mcolors.to_hex(c) in SAFE


def raw_key(text):
    """A CSV column or scene key path left in a label: a word with an
    underscore or a dotted path outside $math$ ('runout_end',
    'base.shear_strength')."""
    plain = re.sub(r"\$[^$]*\$", "", text)
    return re.search(r"[A-Za-z0-9]_[A-Za-z0-9]|[a-z]\.[a-z]", plain)


def overlap(a, b):
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def signature(handle):
    """How a legend entry looks: colour, line style and marker."""
    if hasattr(handle, "get_linestyle") and hasattr(handle, "get_marker"):
        return ("line", mcolors.to_hex(handle.get_color()), str(handle.get_linestyle()),
                str(handle.get_marker()), mcolors.to_hex(handle.get_markerfacecolor()))
    face = [list(c) for c in mcolors.to_rgba_array(handle.get_facecolor())] or [[0, 0, 0, 0]]
    face = face[0]
    paths = handle.get_paths() if hasattr(handle, "get_paths") else []
    shape = tuple(map(tuple, paths[0].vertices.round(2))) if paths else ()
    return ("patch", mcolors.to_hex(face), len(shape), shape)


def judge(fig, name, max_entries=10):
    """The chart's faults, as a list of sentences (empty: none)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    faults = []
    texts = [fig._suptitle] if fig._suptitle else []
    entries = []
    for ax in fig.axes:
        texts += [ax.title, ax.xaxis.label, ax.yaxis.label]
        for axis, which in ((ax.xaxis, "x"), (ax.yaxis, "y")):
            labels = [t for t in axis.get_ticklabels() if t.get_visible() and t.get_text()]
            if labels and not axis.label.get_text().strip():
                faults.append("%s: a %s axis with tick labels and no name" % (name, which))
            if any("10^" in t.get_text() or "times" in t.get_text() for t in labels):
                faults.append("%s: %s tick labels as powers of ten" % (name, which))
            boxes = [t.get_window_extent(renderer) for t in labels]
            if any(overlap(p, q) for k, p in enumerate(boxes) for q in boxes[k + 1:]):
                faults.append("%s: %s tick labels overlap" % (name, which))
            if axis.get_scale() == "log" and labels:
                span = ax.get_window_extent(renderer)
                length = span.width if which == "x" else span.height
                pos = [(b.x0 + b.x1) / 2 if which == "x" else (b.y0 + b.y1) / 2 for b in boxes]
                if len(labels) < 3 or max(pos) - min(pos) < 0.5 * length:
                    faults.append("%s: %s log axis labelled over under half its length"
                                  % (name, which))
        marks = [t for t in ax.texts if t.get_visible() and t.get_text()]
        boxes = [t.get_window_extent(renderer) for t in marks]
        for k, p in enumerate(boxes):
            for q, t in zip(boxes[k + 1:], marks[k + 1:]):
                if overlap(p, q):
                    faults.append("%s: texts overlap: %r, %r" % (name, marks[k].get_text(),
                                                                 t.get_text()))
        texts += marks
        for artist in ax.lines + ax.collections:
            colours = [artist.get_color()] if hasattr(artist, "get_color") and \
                not hasattr(artist, "get_facecolor") else list(artist.get_facecolor())
            faults += ["%s: colour %s is not colour-blind-safe" % (name, mcolors.to_hex(c))
                       for c in colours if not safe_colour(c)]
        legends = [a for a in ax.artists + ax.get_children()
                   if isinstance(a, study_charts.matplotlib.legend.Legend)]
        for legend in {id(g): g for g in legends}.values():
            labels = [t.get_text() for t in legend.get_texts()]
            if len(labels) > max_entries:
                faults.append("%s: a legend of %d entries" % (name, len(labels)))
            texts += legend.get_texts() + [legend.get_title()]
            entries += [(signature(h), lab) for h, lab in zip(legend.legend_handles
                                                               if hasattr(legend, "legend_handles")
                                                               else legend.legendHandles, labels)]
    looks = {}
    for sig, lab in entries:
        if sig in looks and looks[sig] != lab:
            faults.append("%s: legend entries %r and %r look alike" % (name, looks[sig], lab))
        looks[sig] = lab
    for t in texts:
        if t.get_text() and raw_key(t.get_text()):
            faults.append("%s: a raw key in %r" % (name, t.get_text()))
    return faults


def history(path, t_end, a, offset):
    """A history.csv of a block sliding at a from t = 0, `offset` ahead."""
    os.makedirs(path)
    with open(os.path.join(path, "history.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time", "runout", "max_thickness", "centroid_s"])
        for k in range(51):
            t = t_end * k / 50
            w.writerow([t, 0.5 * a * t * t + offset * t / t_end, 2.0, 7.0 + 0.5 * a * t * t])


COLUMNS = ["id", "method", "backend", "shape", "cell", "ppc", "domain_x_max", "slope_angle",
           "status", "wall_s", "end_time", "runout_end", "err_runout_end", "pareto",
           "observed_order", "reference", "final_length", "max_thickness", "mechanism"]


def write_study(d, rows):
    with open(os.path.join(d, "study.csv"), "w", newline="") as f:
        csv.writer(f).writerows([COLUMNS] + [[r.get(c, "") for c in COLUMNS] for r in rows])


faults = []
with tempfile.TemporaryDirectory() as d:
    # The verification's matrix: 2 shapes x 2 particles per cell x 4 cells,
    # errors that repeat from series to series (points on top of each
    # other), the rigid block as the reference.
    rows = []
    for shape in ("gimp", "linear"):
        for ppc in (1, 2):
            for k, h in enumerate((1, 0.5, 0.25, 0.125)):
                rid = "mpm_cpu_%s_h%g_ppc%d" % (shape, h, ppc)
                err = 0.008 + 0.001 * k
                rows.append({"id": rid, "method": "mpm", "backend": "cpu", "shape": shape,
                             "cell": h, "ppc": ppc, "domain_x_max": 100, "status": "ok",
                             "wall_s": 0.1 * 4 ** k * ppc, "end_time": 5,
                             "runout_end": 10.9 * (1 + err), "err_runout_end": err,
                             "pareto": int(k == 0), "observed_order": -0.2,
                             "reference": "analytic-block", "mechanism": "undetermined"})
                history(os.path.join(d, "runs", rid), 5.0, 0.87, 0.1 + 0.01 * k)
    write_study(d, rows)
    study = study_charts.read_study(d)
    for r in study:
        r["_many_domains"] = False
    t = [5.0 * k / 50 for k in range(51)]
    for chart, args in (
            (study_charts.chart_error_vs_wall, (study, os.path.join(d, "e.png"), "block")),
            (study_charts.chart_convergence, (study, os.path.join(d, "c.png"), "block")),
            (study_charts.chart_runout_history,
             (d, study, os.path.join(d, "r.png"), "block", (t, [0.435 * x * x for x in t])))):
        chart(*args)
        faults += judge(study_charts.FIGURES[-1], "verification " + chart.__name__)
    # 16 runs and a reference: at most 4 cells + 2 particle counts + 1 line.
    runout = study_charts.FIGURES[-1]
    entries = sum(len(g.get_texts()) for ax in runout.axes for g in [ax.get_legend()] if g)
    assert entries <= 7, "the runout chart has %d legend entries" % entries

with tempfile.TemporaryDirectory() as d:
    # A case study: the MPM and the depth-averaged model at five cells,
    # the finest MPM run the reference.
    rows = []
    for method in ("mpm", "dam"):
        for k, h in enumerate((1.6, 1.2, 0.8, 0.6, 0.4)):
            rid = "%s_cpu_%sh%g%s" % (method, "gimp_" if method == "mpm" else "", h,
                                      "_ppc2" if method == "mpm" else "")
            err = 0.0 if rid == "mpm_cpu_gimp_h0.4_ppc2" else \
                0.02 / (k + 1) if method == "mpm" else 0.0075
            rows.append({"id": rid, "method": method, "backend": "cpu",
                         "shape": "gimp" if method == "mpm" else "", "cell": h,
                         "ppc": 2 if method == "mpm" else "", "domain_x_max": 600,
                         "status": "ok",
                         "wall_s": 0.7 + (60 / 4 ** (4 - k) if method == "mpm" else 0),
                         "end_time": 20, "runout_end": 86.7 * (1 + err), "err_runout_end": err,
                         "pareto": 0, "observed_order": 1.9 if method == "mpm" else 0.01,
                         "reference": "mpm_cpu_gimp_h0.4_ppc2", "mechanism": "block sliding"})
            history(os.path.join(d, "runs", rid), 20.0, 0.43, 86.7 * err)
    write_study(d, rows)
    study = study_charts.read_study(d)
    for r in study:
        r["_many_domains"] = False
    for chart, args in (
            (study_charts.chart_error_vs_wall, (study, os.path.join(d, "e.png"), "case")),
            (study_charts.chart_convergence, (study, os.path.join(d, "c.png"), "case")),
            (study_charts.chart_runout_history, (d, study, os.path.join(d, "r.png"), "case"))):
        chart(*args)
        faults += judge(study_charts.FIGURES[-1], "case " + chart.__name__)

with tempfile.TemporaryDirectory() as d:
    # The slope study: both methods at three angles.
    rows = []
    for method in ("mpm", "dam"):
        for angle in (2, 10, 30):
            rid = "%s_a%g" % (method, angle)
            rows.append({"id": rid, "method": method, "backend": "cpu", "shape": "gimp",
                         "cell": 0.4, "ppc": 2 if method == "mpm" else "", "slope_angle": angle,
                         "status": "ok", "wall_s": 1, "end_time": 20,
                         "runout_end": 30 * angle * (1.1 if method == "dam" else 1),
                         "final_length": 70, "mechanism": "block sliding"})
            history(os.path.join(d, "runs", rid), 20.0, 0.3 * angle, 1.0)
    write_study(d, rows)
    study = study_charts.read_study(d)
    study_charts.chart_dam_vs_mpm(d, study, os.path.join(d, "s.png"), "slopes")
    faults += judge(study_charts.FIGURES[-1], "dam against mpm")

with tempfile.TemporaryDirectory() as d:
    # The mechanism map over the keys of scripts/study case4-mechanism-map:
    # its axes named in words, with units, ticked in kPa.
    rows = []
    for st in (1, 5, 10, 20, 40):
        for tau in (500, 1000, 2000, 4000):
            rows.append({"id": "p%g_%g" % (st, tau), "method": "mpm", "shape": "gimp",
                         "cell": 0.8, "ppc": 2, "status": "ok", "runout_end": 40000 / tau,
                         "mechanism": "spreading" if st == 40 else "elongation"})
    cols = COLUMNS + ["material.clay.sensitivity", "base.shear_strength"]
    with open(os.path.join(d, "study.csv"), "w", newline="") as f:
        csv.writer(f).writerows([cols] + [[r.get(c, "") for c in COLUMNS]
                                          + [r["id"][1:].split("_")[0], r["id"].split("_")[1]]
                                          for r in rows])
    study = study_charts.read_study(d)
    study_charts.chart_mechanism_map(study, "material.clay.sensitivity", "base.shear_strength",
                                     os.path.join(d, "m.png"), "map")
    fig = study_charts.FIGURES[-1]
    faults += judge(fig, "mechanism map")
    ax = fig.axes[0]
    assert ax.get_xlabel() == "sensitivity $S_t$ [-]", ax.get_xlabel()
    assert ax.get_ylabel() == "interface shear strength τ [kPa]", ax.get_ylabel()
    assert [t.get_text() for t in ax.get_yticklabels()] == ["0.5", "1", "2", "4"], \
        [t.get_text() for t in ax.get_yticklabels()]
    study_charts.chart_exceedance(study, os.path.join(d, "x.png"))
    faults += judge(study_charts.FIGURES[-1], "exceedance")

assert not faults, "\n".join(faults)

print("study charts: exceedance, DKW band and mechanism map as expected; %d charts drawn, "
      "judged without a fault" % len(study_charts.FIGURES))
