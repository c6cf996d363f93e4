#!/usr/bin/python3
"""Draws runs' runout and toe velocity histories and their final profiles.

  scripts/history_chart.py OUT.png LABEL=HISTORY.csv[,PROFILE.csv] ...

HISTORY.csv is a run's history.csv, PROFILE.csv one of its profile_*.csv
(docs/output.md); each run gets a line in each panel.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        rows = [l for l in f if not l.startswith("#")]
    return list(csv.DictReader(rows))


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    fig, (a, b, c) = plt.subplots(1, 3, figsize=(15, 4))
    for spec in sys.argv[2:]:
        label, paths = spec.split("=", 1)
        history, *profile = paths.split(",")
        h = read(history)
        t = [float(r["time"]) for r in h]
        a.plot(t, [float(r["runout"]) for r in h], label=label)
        b.plot(t, [float(r["toe_velocity"]) for r in h], label=label)
        if profile:
            p = read(profile[0])
            c.plot([float(r["s"]) for r in p], [float(r["thickness"]) for r in p], label=label)
    a.set(xlabel="time [s]", ylabel="runout [m]")
    b.set(xlabel="time [s]", ylabel="toe velocity [m/s]")
    c.set(xlabel="s along the base [m]", ylabel="thickness [m] (final frame)")
    for ax in (a, b, c):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[1], dpi=100)


if __name__ == "__main__":
    main()
