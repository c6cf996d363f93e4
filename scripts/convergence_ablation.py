#!/usr/bin/python3
"""The ablation of docs/convergence.md: each numerical candidate alone, on
coarse case 2 and on the column collapse, at several Courant numbers.

Runs `runout run` on variants of a scene (one key changed in a copy),
two at a time, and writes one CSV row per run: scene, variant, Courant,
toe runout at the end time, steps, wall time. Usage:

  scripts/convergence_ablation.py [--runout build/engine/runout] [--out DIR]
                                  [--only case2|column] [--variant TEXT] [--jobs 2]
"""
import argparse
import concurrent.futures
import csv
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# scene file, CLI arguments, end time
SCENES = {
    "case2": ("scenes/case2_elongation_noslip.toml", ["--cell", "0.5", "--ppc", "2", "--end", "12"]),
    "column": ("scenes/column_collapse_tresca.toml", []),
}

# variant name -> {(table, key): value as TOML text}; each changes one thing
# against the default (FLIP with XPIC(5) every 40 P-wave cell crossings,
# deforming domains, volumetric smoothing, no gravity ramp).
VARIANTS = {
    "default (FLIP, XPIC(5) every 40 cell crossings)": {},
    "pure FLIP (no scheduled XPIC)": {("solver", "xpic_cells"): "0"},
    "FLIP, PIC share over 200 cell crossings": {("solver", "pic_cells"): "200"},
    "APIC": {("solver", "transfer"): '"apic"'},
    "XPIC(5) every step": {("solver", "transfer"): '"xpic"'},
    "per-step blend, flip 0.99": {("solver", "transfer"): '"pic_flip"', ("solver", "flip"): "0.99"},
    "fixed domains (uGIMP)": {("grid", "domain"): '"fixed"'},
    "no volumetric smoothing": {("solver", "volumetric_smoothing"): "false"},
    "gravity ramp 0.5 s": {("gravity", "ramp"): "0.5"},
}
CASE2_ONLY = {
    "frictional, tau = 1 GPa": {("base", "interface"): '"frictional"',
                                ("base", "shear_strength"): "1.0e9"},
}
COURANTS = (0.1, 0.2, 0.25)


def set_key(text, table, key, value):
    """Sets `key = value` in [table] of a TOML text, adding the table if needed."""
    lines = text.split("\n")
    start = next((i for i, l in enumerate(lines) if l.strip() == f"[{table}]"), None)
    if start is None:
        return text + f"\n[{table}]\n{key} = {value}\n"
    end = next((i for i in range(start + 1, len(lines)) if lines[i].lstrip().startswith("[")),
               len(lines))
    for i in range(start + 1, end):
        if re.match(rf"\s*{re.escape(key)}\s*=", lines[i]):
            lines[i] = f"{key} = {value}"
            return "\n".join(lines)
    lines.insert(start + 1, f"{key} = {value}")
    return "\n".join(lines)


def run_one(runout, out, scene, variant, changes, courant):
    path, args = SCENES[scene]
    text = open(os.path.join(ROOT, path)).read()
    for (table, key), value in changes.items():
        text = set_key(text, table, key, value)
    text = set_key(text, "time", "courant", str(courant))
    # The runout at the end time, not at an earlier at-rest stop.
    text = set_key(text, "time", "rest_fraction", "0")
    tag = re.sub(r"[^a-z0-9]+", "_", f"{scene}_{variant}_{courant}".lower())
    scene_file = os.path.join(out, tag + ".toml")
    with open(scene_file, "w") as f:
        f.write(text)
    folder = os.path.join(out, tag)
    start = time.monotonic()
    proc = subprocess.run([runout, "run", scene_file, "--out", folder, "--quiet", "--threads", "1",
                           *args], capture_output=True, text=True)
    wall = time.monotonic() - start
    if proc.returncode != 0:
        return [scene, variant, courant, "failed", proc.returncode, f"{wall:.1f}"]
    with open(os.path.join(folder, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    last = rows[-1]
    return [scene, variant, courant, f"{float(last['runout']):.4f}", last["step"], f"{wall:.1f}"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--runout", default=os.path.join(ROOT, "build/engine/runout"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out/ablation"))
    ap.add_argument("--only", choices=sorted(SCENES))
    ap.add_argument("--variant", help="only the variants whose name contains this text")
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    jobs = []
    for scene in SCENES:
        if a.only and scene != a.only:
            continue
        variants = dict(VARIANTS, **(CASE2_ONLY if scene == "case2" else {}))
        for variant, changes in variants.items():
            if a.variant and a.variant not in variant:
                continue
            for courant in COURANTS:
                jobs.append((scene, variant, changes, courant))
    writer = csv.writer(sys.stdout)
    writer.writerow(["scene", "variant", "courant", "runout_m", "steps", "wall_s"])
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        for row in pool.map(lambda j: run_one(a.runout, a.out, *j), jobs):
            writer.writerow(row)
            sys.stdout.flush()


if __name__ == "__main__":
    main()
