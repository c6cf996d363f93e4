#!/usr/bin/python3
"""scripts/study_charts.py's probabilistic charts on a synthetic study of
known answer: the exceedance steps, the DKW band's half-width, and the
mechanism map's pick of the finest run per point.

    study_charts_check.py SOURCE_DIR
"""
import csv
import math
import os
import sys
import tempfile

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
print("study charts: exceedance, DKW band and mechanism map as expected")
