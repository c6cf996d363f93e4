#!/usr/bin/python3
"""Chart of the small case 4 slide's runout against cell size, local and
regularised softening (docs/study.md, "Case 4 runout against cell size").

    regularisation_chart.py TEST_BINARY OUT.png

runs TEST_BINARY (the build's tests/test_regularisation) on its mesh test,
reads the runouts it prints and draws them, with the test's 5 % band
(max - min within 5 % of the mean) around the regularised mean.
"""
import re
import subprocess
import sys

from study_charts import plt, save

LINE = re.compile(r"h = ([\d.]+) m, 2 x 2: runout regularised ([\d.]+) m, local ([\d.]+) m")


def measure(binary):
    """(cells, local runouts, regularised runouts) from the test's output."""
    out = subprocess.run([binary, "--gtest_filter=Regularisation.ASmallSlide*"], check=True,
                         capture_output=True, text=True).stdout
    rows = [LINE.search(line).groups() for line in out.splitlines() if LINE.search(line)]
    if not rows:
        sys.exit("no runouts in the output of " + binary)
    cells = [float(r[0]) for r in rows]
    return cells, [float(r[2]) for r in rows], [float(r[1]) for r in rows]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    cells, local, regularised = measure(sys.argv[1])
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    ax.plot(cells, local, "o-", label="local softening")
    ax.plot(cells, regularised, "s-", label="regularised, t_s = 0.1 m, l = 3 cells")
    mean = sum(regularised) / len(regularised)
    ax.axhspan(mean * 0.975, mean * 1.025, alpha=0.15, label="5 % band round the regularised mean")
    ax.invert_xaxis()  # finer to the right
    save(fig, ax, sys.argv[2], "cell size h [m]", "runout at t = 12 s [m]",
         "small case 4 slide: runout against cell size")


if __name__ == "__main__":
    main()
