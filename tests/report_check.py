#!/usr/bin/python3
"""`runout report` opened in a real headless browser (Debian's chromium):
a short coarse run of the default scene with one figure in its figures/
folder, its report.html loaded from disk with no network; every image of
the page must have loaded (the page marks its body data-images="N/M"), it
must hold the two charts and the figure, and its screenshot must not be
blank. A folder that is not a finished run is refused with 66.

    report_check.py RUNOUT SOURCE_DIR

Exits 77 (skipped) where chromium is missing.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

from PIL import Image

runout, source = sys.argv[1], sys.argv[2]
chromium = shutil.which("chromium")
if not chromium:
    print("no chromium (Debian: apt-get install chromium): skipped")
    sys.exit(77)
# As root (CI) chromium runs only without its sandbox; no GPU, and /dev/shm
# may be small in a container.
BROWSER = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
           "--hide-scrollbars", "--virtual-time-budget=10000"]


def run(args, **kw):
    return subprocess.run(args, capture_output=True, text=True, timeout=240, **kw)


with tempfile.TemporaryDirectory() as d:
    out = os.path.join(d, "run")
    r = run([runout, "run", "--cell", "1.0", "--ppc", "2", "--end", "4", "--threads", "1",
             "--quiet", "--out", out])
    assert r.returncode == 0, r.stdout + r.stderr
    os.makedirs(os.path.join(out, "figures"))
    shutil.copy(os.path.join(source, "docs", "images", "case3_0.1m_4x4.png"),
                os.path.join(out, "figures", "runout_morphology.png"))

    r = run([runout, "report", out])
    assert r.returncode == 0, r.stdout + r.stderr
    page = os.path.join(out, "report.html")
    assert r.stdout.strip() == page, r.stdout
    html = open(page, encoding="utf-8").read()
    sources = re.findall(r'src="([^"]*)"', html)
    assert sources and all(s.startswith("data:") for s in sources), "every image inline"

    dom = run(BROWSER + ["--dump-dom", "file://" + page]).stdout
    marks = re.search(r'<body data-images="(\d+)/(\d+)"', dom)
    assert marks, "the page's check did not run: " + dom[:300]
    loaded, images = int(marks.group(1)), int(marks.group(2))
    print(f"images loaded: {loaded} of {images}")
    assert images >= 3 and loaded == images, (loaded, images)
    for heading in ("Result", "Motion", "Mechanism, frame by frame", "Figures", "Scene"):
        assert f"<h2>{heading}</h2>" in dom, heading

    shot = os.path.join(d, "shot.png")
    run(BROWSER + ["--window-size=1280,2000", "--screenshot=" + shot, "file://" + page])
    with Image.open(shot) as image:
        grey = image.convert("L")
        colours = len(set(grey.getdata()))
        lo, hi = grey.getextrema()
    print(f"screenshot: {colours} grey levels, {lo} to {hi}")
    assert colours > 16 and hi - lo > 128, "the page renders blank"

    empty = os.path.join(d, "empty")
    os.makedirs(empty)
    r = run([runout, "report", empty])
    assert r.returncode == 66, (r.returncode, r.stdout + r.stderr)
    assert "summary.json" in r.stderr, r.stderr
print("report check passed")
