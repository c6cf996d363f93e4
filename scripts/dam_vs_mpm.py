#!/usr/bin/python3
"""The DAM against the coarse MPM on cases 1 to 4 and the escarpment.

    /usr/bin/python3 scripts/dam_vs_mpm.py [--runout BIN] [--out DIR] [--images DIR]

Runs, for each scene, the coarse MPM (--cell 1 --ppc 2) and the DAM in
elements of the scene's cell size (--elements) with both longitudinal stresses (Rankine and K = 1),
with both shear-rate estimates where the clay is rate-dependent, one thread
each and one at a time (wall times are part of the result). Writes
DIR/dam_vs_mpm.csv (one row per run), one chart per scene
(IMAGES/dam_vs_mpm_<scene>.png: runout, toe velocity and length against
time) and prints the rows of the table in docs/dam.md ("DAM against the coarse MPM").
BIN defaults to $RUNOUT_BUILD/engine/runout (RUNOUT_BUILD: <repo>/build).
"""
import argparse
import csv
import os
import subprocess
import sys
import time
import tomllib

import matplotlib
import numpy as np

matplotlib.use("Agg")  # headless: no display needed
import matplotlib.pyplot as plt  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (scene, label in the table, end time of the MPM run or None for the
# scene's own, the DAM's elements: the body's length over the scene's cell,
# finer than the DAM's default, as the table was measured). The escarpment's MPM run stops at 60 s, as in the table's
# first version: its toe has stopped by 40 s and the scene's other 140 s
# would cost minutes of MPM on one thread (case 3's scene ends at 60 s).
# The DAM runs to the scenes' own end times.
SCENES = [
    ("case1_elongation", "1 elongation", None, 487),
    ("case2_elongation_noslip", "2 no-slip", None, 487),
    ("case3_block_sliding", "3 block sliding", 60.0, 487),
    ("case4_spreading", "4 spreading", None, 487),
    ("escarpment", "escarpment", 60.0, 615),
]
STRESSES = [("rankine", "Rankine"), ("hydrostatic", "K = 1")]

COLUMNS = [
    "scene", "run", "method", "earth_pressure", "shear_rate", "end_s",
    "at_rest", "toe_velocity_end", "runout_end", "runout_10s", "runout_20s",
    "runout_60s", "peak_toe_velocity", "peak_toe_velocity_time",
    "final_length", "max_thickness", "centroid_travel", "steps", "wall_s",
]


def rate_dependent(scene_path):
    """Whether a material of the scene has a rate term: `plug` is refused
    without one (docs/dam.md, "Shear strain rate")."""
    with open(scene_path, "rb") as f:
        scene = tomllib.load(f)
    return any(m.get("eta", 0.0) > 0.0 for m in scene.get("material", []))


def dam_scene(scene_path, stress, out_dir):
    """A copy of the scene with the DAM's longitudinal stress chosen."""
    name = os.path.splitext(os.path.basename(scene_path))[0]
    path = os.path.join(out_dir, f"{name}_{stress}.toml")
    with open(scene_path) as f:
        text = f.read()
    with open(path, "w") as f:
        f.write(text.rstrip("\n") + f'\n\n[dam]\nearth_pressure = "{stress}"\n')
    return path


def run(runout, args, out):
    """One run, alone on one thread; its wall time and whether it ended at rest."""
    start = time.perf_counter()
    done = subprocess.run(
        [runout, "run", *args, "--threads", "1", "--quiet", "--out", out],
        cwd=REPO, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"runout {' '.join(args)}: exit {done.returncode}\n{done.stderr}")
    return wall, "came to rest" in done.stdout


def read_history(out):
    with open(os.path.join(out, "history.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def runout_at(h, t):
    """Runout at time t; None when the run came to rest before t (the table
    leaves that cell blank: the runout at the end stands for it)."""
    if t > h["time"][-1]:
        return None
    return float(np.interp(t, h["time"], h["runout"]))


def measure(h):
    peak = int(np.argmax(h["toe_velocity"]))
    return {
        "end_s": h["time"][-1],
        "toe_velocity_end": h["toe_velocity"][-1],
        "runout_end": h["runout"][-1],
        "runout_10s": runout_at(h, 10.0),
        "runout_20s": runout_at(h, 20.0),
        "runout_60s": runout_at(h, 60.0),
        "peak_toe_velocity": h["toe_velocity"][peak],
        "peak_toe_velocity_time": h["time"][peak],
        "final_length": h["length"][-1],
        "max_thickness": h["max_thickness"][-1],
        "centroid_travel": h["centroid_s"][-1] - h["centroid_s"][0],
        "steps": int(h["step"][-1]),
    }


def runs_of(scene, mpm_end, elements, out_dir):
    """(run label, method, stress, shear rate, runout arguments, output folder)."""
    scene_path = os.path.join(REPO, "scenes", scene + ".toml")
    mpm = ["scenes/" + scene + ".toml", "--method", "mpm", "--cell", "1", "--ppc", "2"]
    if mpm_end is not None:
        mpm += ["--end", f"{mpm_end:g}"]
    runs = [("MPM", "mpm", "", "", mpm, os.path.join(out_dir, scene, "mpm"))]
    rates = ["linear", "plug"] if rate_dependent(scene_path) else [None]
    for stress, stress_label in STRESSES:
        copy = dam_scene(scene_path, stress, out_dir)
        for rate in rates:
            args = [copy, "--method", "dam", "--elements", str(elements)]
            label = "DAM " + stress_label
            folder = f"dam_{stress}"
            if rate is not None:
                args += ["--shear-rate", rate]
                label += " " + rate
                folder += "_" + rate
            runs.append((label, "dam", stress, rate or "", args,
                         os.path.join(out_dir, scene, folder)))
    return runs


def cell(value, digits):
    if value is None:
        return ""
    if abs(value) >= 1000:
        return f"{value:.0f}"
    return f"{value:.{digits}f}"


def markdown_row(case_label, row, show_60s):
    end = f"{row['end_s']:.1f}".removesuffix(".0")
    if not row["at_rest"]:
        end += f" ({row['toe_velocity_end']:.2f} m/s)"
    runout = cell(row["runout_end"], 1)
    if show_60s and row["end_s"] > 60.0 + 1e-9:
        runout += f" ({cell(row['runout_60s'], 1)} at 60 s)"
    return "| " + " | ".join([
        case_label, row["run"], end, runout,
        cell(row["runout_10s"], 1), cell(row["runout_20s"], 1),
        f"{row['peak_toe_velocity']:.2f} ({row['peak_toe_velocity_time']:.1f})",
        cell(row["final_length"], 1), cell(row["max_thickness"], 2),
        cell(row["centroid_travel"], 1)]) + " |"


def same_history(a, b):
    with open(os.path.join(a, "history.csv"), "rb") as f, \
            open(os.path.join(b, "history.csv"), "rb") as g:
        return f.read() == g.read()


def chart(path, title, histories):
    fig, axes = plt.subplots(1, 3, figsize=(15, 4))
    for label, h in histories:
        style = {"color": "black", "linewidth": 2} if label == "MPM" else {}
        for ax, key in zip(axes, ("runout", "toe_velocity", "length")):
            ax.plot(h["time"], h[key], label=label, **style)
    for ax, ylabel in zip(axes, ("runout [m]", "toe velocity [m/s]", "length [m]")):
        ax.set(xlabel="time [s]", ylabel=ylabel)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main():
    build = os.environ.get("RUNOUT_BUILD", os.path.join(REPO, "build"))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runout", default=os.path.join(build, "engine", "runout"))
    parser.add_argument("--out", default=os.path.join(REPO, "out", "dam_vs_mpm"))
    parser.add_argument("--images", default=os.path.join(REPO, "docs", "images"))
    args = parser.parse_args()
    runout = os.path.abspath(args.runout)
    out_dir = os.path.abspath(args.out)
    os.makedirs(out_dir, exist_ok=True)

    rows, table = [], []
    for scene, case_label, mpm_end, elements in SCENES:
        shown = []  # (row, history, folder) per line of the chart and row of the table
        for label, method, stress, rate, run_args, folder in runs_of(scene, mpm_end, elements, out_dir):
            wall, at_rest = run(runout, run_args, folder)
            print(f"{scene}: {label}: {wall:.1f} s", file=sys.stderr)
            h = read_history(folder)
            row = {"scene": scene, "run": label, "method": method,
                   "earth_pressure": stress, "shear_rate": rate,
                   "at_rest": at_rest, "wall_s": wall, **measure(h)}
            rows.append(row)
            # A rate the base and the layer never feel (case 3: the interface
            # is weaker than the clay) gives the same run with either
            # estimate: one line and one table row for both.
            linear = shown[-1] if rate == "plug" else None
            if linear and same_history(linear[2], folder):
                linear[0]["run"] = linear[0]["run"].replace(" linear", " (linear = plug)")
                continue
            shown.append((dict(row), h, folder))
        for i, (row, _, _) in enumerate(shown):
            table.append(markdown_row(case_label if i == 0 else "", row, mpm_end is not None))
        chart(os.path.join(args.images, f"dam_vs_mpm_{scene}.png"),
              f"{scene}: DAM against the coarse MPM (--cell 1 --ppc 2)",
              [(row["run"], h) for row, h, _ in shown])

    with open(os.path.join(out_dir, "dam_vs_mpm.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: ("" if row[k] is None else
                                 f"{row[k]:.6g}" if isinstance(row[k], float) else row[k])
                             for k in COLUMNS})

    print("| case | run | end [s] | runout [m] | at 10 s | at 20 s | peak toe velocity "
          "[m/s] (at s) | final length [m] | max thickness [m] | centroid travel [m] |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    print("\n".join(table))


if __name__ == "__main__":
    main()
