"""The figures of states/figures.py and the state files of states/, end to
end in headless ParaView: a coarse engine run (and a second, coarser one
to compare with), every figure rendered by pvbatch under xvfb-run, and each
PNG checked: it exists, has the asked size, is not blank (pixel standard
deviation) and shows the colours figures.json says it draws (the colour
map's end colours, from its scale bar; the curves' colours). Then each
states/*.pvsm is loaded on the run (states/load_state.py) and must still
hold its Runout filters (LoadState drops unknown ones with a warning only).

Run by pvpython (for VTK's PNG reader and numpy):
  pvpython tests/figures_check.py figures|states SOURCE_DIR RUNOUT_CLI PLUGIN PVBATCH
Exits 77 (skipped) without xvfb-run or pvbatch.
"""
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

SIZE = [640, 320]
XVFB = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24 -noreset"]


def png_pixels(path):
    """(width, height, n x 3 uint8 array) of a PNG, read by VTK."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())
    return width, height, pixels[:, :3].astype(int)


def check_png(path, size, colours, failures):
    import numpy
    if not os.path.isfile(path):
        failures.append(f"{path}: missing")
        return
    width, height, pixels = png_pixels(path)
    if [width, height] != list(size):
        failures.append(f"{path}: {width}x{height}, asked {size[0]}x{size[1]}")
    spread = float(pixels.std())
    if spread < 10.0:
        failures.append(f"{path}: blank (pixel standard deviation {spread:.1f})")
    found = []
    for colour in colours:
        near = int((numpy.abs(pixels - numpy.array(colour)).max(axis=1) <= 24).sum())
        found.append(near)
        if near < 8:
            failures.append(f"{path}: {near} pixels of the colour {colour}")
    print(f"{os.path.basename(path)}: {width}x{height}, std {spread:.1f}, "
          f"pixels near {colours}: {found}")


def run(command, **kwargs):
    print("+", " ".join(command), flush=True)
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, **kwargs)
    print(result.stdout)
    if result.returncode != 0:
        print(f"ERROR: exit {result.returncode}")
        sys.exit(1)
    return result.stdout


def main():
    mode, source, cli, plugin, pvbatch = sys.argv[1:6]
    if not shutil.which("xvfb-run") or not pvbatch or not os.path.isfile(pvbatch):
        print("no xvfb-run or pvbatch: skipped")
        sys.exit(77)
    work = tempfile.mkdtemp(prefix="runout_figures_")
    try:
        fine = os.path.join(work, "cell1")
        run([cli, "run", "--cell", "1.0", "--ppc", "2", "--end", "6", "--out", fine, "-q"])
        failures = []
        if mode == "figures":
            coarse = os.path.join(work, "cell2")
            run([cli, "run", "--cell", "2.0", "--ppc", "2", "--end", "6", "--out", coarse,
                 "-q"])
            run(XVFB + [pvbatch, os.path.join(source, "states", "figures.py"), fine,
                        "--plugin", plugin, "--size", f"{SIZE[0]}x{SIZE[1]}",
                        "--animation", "--compare", coarse, "--labels", "cell 1 m,cell 2 m"])
            folder = os.path.join(fine, "figures")
            with open(os.path.join(folder, "figures.json")) as f:
                summary = json.load(f)
            manifest = summary["figures"]
            # The contours at the frame nearest the peak toe velocity (the
            # frames are 1 s apart), not at rest.
            if abs(summary["contour_time"] - summary["peak_toe_velocity_time"]) > 0.5:
                failures.append(f"velocity contours at {summary['contour_time']} s, the "
                                f"peak toe velocity at {summary['peak_toe_velocity_time']} s")
            names = [entry["png"] for entry in manifest]
            for wanted in ("morphology.png", "history.png"):
                if wanted not in names:
                    failures.append(f"{wanted} not rendered")
            velocity = [n for n in names if n.startswith("velocity_t")]
            animation = [n for n in names if n.startswith("animation/")]
            if len(velocity) != 4:
                failures.append(f"{len(velocity)} velocity pictures, 4 by default")
            contours = [n for n in names if n.startswith("velocity_contours_t")]
            bands = [n for n in names if n.startswith("strain_bands_t")]
            if len(contours) != 1 or len(bands) != 4:
                failures.append(f"{len(contours)} velocity contour pictures (1 by default), "
                                f"{len(bands)} strain and band pictures (4)")
            if len(animation) != 7:  # frames at 0, 1, ..., 6 s
                failures.append(f"{len(animation)} animation frames, 7 frames in the run")
            on_disk = sorted(os.path.relpath(p, folder)
                             for p in glob.glob(os.path.join(folder, "**", "*.png"),
                                                recursive=True))
            if on_disk != sorted(names):
                failures.append(f"PNGs on disk {on_disk} != figures.json {sorted(names)}")
            for entry in manifest:
                # Particle pictures are cropped to the slide: the asked
                # width, at most the asked height.
                if entry["size"][0] != SIZE[0] or entry["size"][1] > SIZE[1]:
                    failures.append(f"{entry['png']}: {entry['size']}, asked {SIZE}")
                check_png(os.path.join(folder, entry["png"]), entry["size"], entry["colours"],
                          failures)
        else:
            for state in sorted(glob.glob(os.path.join(source, "states", "*.pvsm"))):
                png = os.path.join(work, os.path.basename(state) + ".png")
                run(XVFB + [pvbatch, os.path.join(source, "states", "load_state.py"),
                            state, fine, "--plugin", plugin, "--png", png,
                            "--size", f"{SIZE[0]}x{SIZE[1]}"])
                # The states colour the particles with Viridis (its scale bar).
                check_png(png, SIZE, [[68, 1, 84], [253, 231, 37]], failures)
        for failure in failures:
            print("ERROR:", failure)
        sys.exit(1 if failures else 0)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
