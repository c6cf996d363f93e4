"""Renders the standard figures of a runout study from a run's output
folder into OUT_DIR/figures/ (docs/figures.md):

  velocity_tNNN.NN.png   velocity magnitude on the particles at each chosen
                         time, one colour range for all, the base drawn;
  velocity_contours_tNNN.NN.png  speed contours at one time (--contour-time,
                         default the peak toe velocity's), framed on the slide then;
  morphology.png         the slide's upper surface (Runout Morphology,
                         Profile port) at t = 0 and the chosen times in one chart;
  strain_bands_tNNN.NN.png  plastic shear strain with the shear band
                         skeletons (Runout Shear Bands, each band's dip
                         marked) and the block outlines (Runout Horsts And
                         Grabens) over it, at each chosen time, one
                         colour range and exaggeration for all;
  history.png            runout and toe velocity against time from
                         history.csv, one curve per run (--compare);
  animation/velocity_NNNNN.png   with --animation: every frame's velocity;
  figures.json           what was rendered: each PNG, its size and the
                         colours it must show (the tests check them).

Usage (rendering needs an X server; Debian's ParaView has no offscreen one):
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvbatch states/figures.py \\
    OUT_DIR [--plugin RunoutPlugin.so] [--times t1,t2,...] [--contour-time T] [--size WxH] \\
    [--animation] [--compare DIR2 [DIR3 ...]] [--labels L1,L2,...]
scripts/figures finds pvbatch and the plugin and does this for you.
"""
import argparse
import builtins
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
from matplotlib import pyplot  # noqa: E402

import runout_pv  # noqa: E402

# The colours the figures use, so that the tests can look for them.
BAND_RED = [0.85, 0.0, 0.0]
BLOCK_INK = [0.15, 0.15, 0.15]
BASE_GREY = [0.45, 0.45, 0.45]
# One colour per curve (times of the morphology chart, runs of the history):
# Okabe and Ito's palette, told apart also by colour-blind readers, with
# dashes for a second cue.
CURVES = [[0.0, 0.0, 0.0], [0.90, 0.62, 0.0], [0.34, 0.71, 0.91], [0.0, 0.62, 0.45],
          [0.84, 0.37, 0.0], [0.0, 0.45, 0.70], [0.80, 0.47, 0.65], [0.6, 0.6, 0.6]]
DASHES = ["-", "--", "-.", ":"]
INK_CHART = [0.1, 0.1, 0.1]


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out_dir", help="a run's output folder (<name>.pvd, history.csv)")
    parser.add_argument("--plugin", help="RunoutPlugin.so (default: the build's, or "
                        "already loaded through PV_PLUGIN_PATH)")
    parser.add_argument("--times", help="comma-separated times (s); default: 4 spread "
                        "over the run")
    parser.add_argument("--contour-time", type=float,
                        help="time (s) of the velocity contours; default: the time of the "
                        "peak toe velocity (history.csv)")
    parser.add_argument("--size", default="1200x600", help="WxH of every PNG")
    parser.add_argument("--animation", action="store_true",
                        help="also every frame's velocity into figures/animation/")
    parser.add_argument("--compare", nargs="+", default=[], metavar="DIR",
                        help="more run folders whose histories to overlay")
    parser.add_argument("--labels", help="comma-separated labels of OUT_DIR and the "
                        "--compare folders (default: the folders' names)")
    return parser.parse_args()


def rgb255(colour):
    return [round(255 * c) for c in colour]


def map_ends(lut):
    """The end colours (0-255) of a colour map: its scale bar shows them."""
    points = list(lut.RGBPoints)
    return [rgb255(points[1:4]), rgb255(points[-3:])]


def default_plugin():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    return os.path.join(root, "build", "lib", "paraview-5.11", "plugins", "RunoutPlugin",
                        "RunoutPlugin.so")


def chosen_times(option, steps):
    """The asked times snapped to the frames, or 4 frames spread over the
    run (its start excluded: nothing has moved yet)."""
    if option:
        asked = [float(t) for t in option.split(",") if t.strip()]
        return [builtins.min(steps, key=lambda s: abs(s - t)) for t in asked]
    if len(steps) <= 4:
        return list(steps)
    picks = [steps[round(i * (len(steps) - 1) / 4)] for i in (1, 2, 3, 4)]
    return sorted(set(picks))


NICE_FACTORS = (1, 2, 3, 5, 10, 20, 30, 50, 100)
# Pixels above the slide (the caption and the colour bar) and below it (the
# scale bar) in a cropped particle picture.
MARGIN_TOP, MARGIN_BOTTOM = 110, 50


def exaggeration_for(bounds, size, fill=0.52, share=0.35):
    """The vertical exaggeration (a round factor) that makes a slide of
    these bounds, its length across the picture (fit_camera's fill), about
    `share` of the picture's height: a 130 m long, 2 m thick slide at its
    true shape is a thin strip of a 1200 x 600 picture."""
    length, thickness = bounds[1] - bounds[0], bounds[3] - bounds[2]
    if not (length > 0 and thickness > 0):
        return 1
    wanted = share * 2 * fill * length * size[1] / size[0] / thickness
    return builtins.max([f for f in NICE_FACTORS if f <= wanted] or [1])


def chart_figure(size, columns=1):
    """A matplotlib figure of the pictures' size in pixels, with `columns`
    charts side by side."""
    figure, axes = pyplot.subplots(1, columns, figsize=(size[0] / 100, size[1] / 100),
                                   dpi=100, squeeze=False)
    figure.set_layout_engine("tight")
    for ax in axes[0]:
        ax.grid(True, color="0.9")
    return figure, list(axes[0])


def chart_exaggeration(ax, figure):
    """Sets the chart's aspect to the largest round vertical exaggeration
    that keeps its data ranges in view, and returns it."""
    figure.canvas.draw()
    box = ax.get_window_extent()
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    wanted = (box.height / (y1 - y0)) / (box.width / (x1 - x0))
    factor = builtins.max([f for f in NICE_FACTORS if f <= wanted] or [1])
    ax.set_aspect(factor, adjustable="datalim")
    return factor


def round_up(value):
    """value rounded up to a multiple of half its power of ten (4.37 to
    4.5, 6.55 to 7): a colour range whose end labels read like the bar's."""
    if value <= 0:
        return 1.0
    step = 10 ** math.floor(math.log10(value)) / 2
    return math.ceil(value / step - 1e-9) * step


def particle_domain(reader):
    """The particles as a filled domain: a triangulation of them (Delaunay
    2D, no triangle wider than 4 particle spacings, so no skin over the
    gaps between blocks) that carries their arrays between them. Points
    leave gaps or overlap once heights are exaggerated."""
    spacing = reader.FieldData["particle_spacing"].GetRange()[0]
    mesh = simple.Delaunay2D(registrationName="particles triangulated", Input=reader)
    mesh.Alpha = 4.0 * spacing
    return mesh


def show_filled(reader, view, scale, point_size, array, title, **colours):
    """The particles as a filled domain (particle_domain) over the
    particles as points `point_size` pixels wide, both coloured by `array`
    (colour_by's options): the points round off the domain's edges, where
    the triangulation leaves notches. Returns the colour map."""
    points = runout_pv.show(reader, view, z=-0.2, scale=scale, Representation="Points",
                            PointSize=point_size)
    domain = runout_pv.show(particle_domain(reader), view, scale=scale)
    lut = runout_pv.colour_by(domain, view, array, title, **colours)
    points.ColorArrayName = [domain.ColorArrayName[0], domain.ColorArrayName[1]]
    points.LookupTable = lut
    points.Ambient, points.Diffuse = 1.0, 0.0
    return lut


def read_history(run_dir):
    """history.csv's rows as dicts of floats, or [] without one."""
    try:
        with open(os.path.join(run_dir, "history.csv")) as f:
            return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
    except (OSError, ValueError):
        return []


def peak_toe_time(run_dir):
    """The time of the run's peak toe velocity (history.csv), or None: the
    velocity contours are drawn then, while the slide is fastest."""
    rows = [r for r in read_history(run_dir) if "toe_velocity" in r]
    return builtins.max(rows, key=lambda r: r["toe_velocity"])["time"] if rows else None


def largest_speed(run_dir):
    """The largest particle speed of the run (history.csv's max_speed),
    one colour range for every velocity picture."""
    rows = [r for r in read_history(run_dir) if "max_speed" in r]
    return (builtins.max(r["max_speed"] for r in rows) or 1.0) if rows else None


class Figures:
    def __init__(self, options):
        self.options = options
        self.size = [int(v) for v in options.size.lower().split("x")]
        self.folder = os.path.join(options.out_dir, "figures")
        os.makedirs(self.folder, exist_ok=True)
        self.manifest = []
        runout_pv.load_plugin(options.plugin or default_plugin())
        self.reader = runout_pv.open_run(runout_pv.find_pvd(options.out_dir))
        self.steps = list(self.reader.TimestepValues) or [0.0]
        self.times = chosen_times(options.times, self.steps)

    def save(self, layout, name, colours, what, size=None):
        """A screenshot of the layout, `size` pixels (default --size)."""
        size = size or self.size
        path = os.path.join(self.folder, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        layout.SetSize(*size)
        simple.SaveScreenshot(path, layout, ImageResolution=size, CompressionLevel="9")
        self.manifest.append({"png": os.path.relpath(path, self.folder), "size": size,
                              "colours": colours, "what": what})
        print(path)
        return path

    def clear(self):
        """Deletes every view and layout (the next figure starts afresh)."""
        simple.RemoveViewsAndLayouts()

    # 1. Velocity magnitude on the particles.
    def run_bounds(self):
        """The particles' bounds over the chosen times and the first and
        last frames, so that pictures of one run compare."""
        bounds = [1e300, -1e300, 1e300, -1e300]
        for t in set(self.times + [self.steps[-1], self.steps[0]]):
            runout_pv.set_time(t)
            self.reader.UpdatePipeline(t)
            b = self.reader.GetDataInformation().GetBounds()
            bounds = [builtins.min(bounds[0], b[0]), builtins.max(bounds[1], b[1]),
                      builtins.min(bounds[2], b[2]), builtins.max(bounds[3], b[3])]
        return bounds

    def velocity_view(self, layout_name):
        layout = simple.CreateLayout(layout_name)
        view = runout_pv.render_view()
        simple.AssignViewToLayout(view=view, layout=layout, hint=0)
        self.bounds = self.run_bounds()
        self.factor = exaggeration_for(self.bounds, self.size)
        scale = [1.0, float(self.factor), 1.0]
        base = runout_pv.base_line(self.reader)
        runout_pv.show_lines(base, view, BASE_GREY, z=-1.0, width=3.0, scale=scale)
        speed = largest_speed(self.options.out_dir)
        lut = show_filled(self.reader, view, scale, self.point_size(), "velocity",
                          "velocity magnitude (m/s)", preset="Turbo", component="Magnitude",
                          data_range=None if speed is None else [0.0, round_up(speed)])
        text, label = self.time_label(view)
        label.FontSize = 16
        return layout, view, text, map_ends(lut)

    def point_size(self, fill=0.52):
        """About 2.5 particle spacings in pixels (2 to 16) in a picture of
        the run's bounds (frame's scale)."""
        spacing = self.reader.FieldData["particle_spacing"].GetRange()[0]
        per_metre = self.size[0] / (2 * fill * (self.bounds[1] - self.bounds[0]))
        return builtins.min(16.0, builtins.max(2.0, 2.5 * spacing * per_metre))

    def fit_to_run(self, view, layout):
        """The camera and the cropped picture on the particles of the
        whole run (run_bounds)."""
        return self.frame(view, layout, self.bounds)

    def frame(self, view, layout, bounds, fill=0.52):
        """Crops the picture to the slide (bounds, heights exaggerated by
        self.factor): the asked width, the height the slide needs with the
        caption and colour bar above it and a scale bar below, at most the
        asked height; sets a parallel camera on it and draws the scale bar.
        Returns the picture's size."""
        width = self.size[0]
        length, height = bounds[1] - bounds[0], self.factor * (bounds[3] - bounds[2])
        margins = MARGIN_TOP + MARGIN_BOTTOM
        per_metre = builtins.min(width / (2 * fill * length),
                                 (self.size[1] - margins) / builtins.max(height, 1e-9))
        size = [width, int(builtins.min(self.size[1], height * per_metre + margins))]
        layout.SetSize(*size)
        simple.Render(view)  # the first render resets the camera: before setting it
        bottom = self.factor * bounds[2] - MARGIN_BOTTOM / per_metre
        centre = [(bounds[0] + bounds[1]) / 2, bottom + size[1] / 2 / per_metre, 0.0]
        view.CameraParallelProjection = 1
        view.CameraFocalPoint = centre
        view.CameraPosition = [centre[0], centre[1], 100.0]
        view.CameraViewUp = [0.0, 1.0, 0.0]
        view.CameraParallelScale = size[1] / 2 / per_metre
        self.per_metre = per_metre
        # A scale bar in the lower left corner, about a fifth of the width.
        seen = width / per_metre
        bar = builtins.max(f * 10 ** k for k in range(-2, 5) for f in (1, 2, 5)
                           if f * 10 ** k <= seen / 5)
        x0, y0 = centre[0] - seen / 2 + 20 / per_metre, bottom + 24 / per_metre
        line = simple.Line(registrationName="scale bar", Point1=[x0, y0, 0.0],
                           Point2=[x0 + bar, y0, 0.0])
        runout_pv.show_lines(line, view, runout_pv.INK, z=4.0, width=4.0, scale=[1, 1, 1])
        self.text_at(view, f"{bar:g} m", x0 + bar + 8 / per_metre, y0 - 6 / per_metre,
                     14 / per_metre, runout_pv.INK)
        return size

    def text_at(self, view, text, x, y, height, colour):
        """3D text `height` high (world units) at (x, y), unlit."""
        mark = simple.a3DText(registrationName=f"text {text}", Text=text)
        display = simple.Show(mark, view)
        display.Scale = [height, height, 1.0]
        display.Position = [x, y, 4.0]
        display.AmbientColor = display.DiffuseColor = colour
        display.Ambient, display.Diffuse = 1.0, 0.0
        return display

    def time_label(self, view, t=None):
        """The caption source and its display in the view's upper left
        corner, reading label(t) when a time is given."""
        text = (simple.Text(registrationName="time label") if t is None else
                simple.Text(registrationName="time label", Text=self.label(t)))
        label = simple.Show(text, view)
        label.WindowLocation = "Upper Left Corner"
        label.Color = runout_pv.INK
        return text, label

    def label(self, t):
        """The picture's caption: its time and its vertical exaggeration."""
        return (f"t = {t:g} s, heights exaggerated {self.factor} x" if self.factor > 1
                else f"t = {t:g} s, true scale")

    def velocity(self):
        layout, view, text, ends = self.velocity_view("velocity")
        size = self.fit_to_run(view, layout)
        for t in self.times:
            runout_pv.set_time(t)
            text.Text = self.label(t)
            self.save(layout, f"velocity_t{t:07.2f}.png", ends,
                      f"velocity magnitude at t = {t:g} s", size)
        self.clear()

    def animation(self):
        layout, view, text, ends = self.velocity_view("animation")
        size = self.fit_to_run(view, layout)
        for i, t in enumerate(self.steps):
            runout_pv.set_time(t)
            text.Text = self.label(t)
            self.save(layout, os.path.join("animation", f"velocity_{i:05d}.png"), ends,
                      f"animation frame {i}, t = {t:g} s", size)
        self.clear()

    # 1b. Velocity contours at one time, framed on the slide then.
    def velocity_contours(self):
        asked = self.options.contour_time
        if asked is None:
            asked = peak_toe_time(self.options.out_dir)
        t = (self.times[-1] if asked is None
             else builtins.min(self.steps, key=lambda s: abs(s - asked)))
        self.contour_time = t
        runout_pv.set_time(t)
        self.reader.UpdatePipeline(t)
        bounds = self.reader.GetDataInformation().GetBounds()
        self.factor = exaggeration_for(bounds, self.size)
        scale = [1.0, float(self.factor), 1.0]
        layout = simple.CreateLayout("velocity contours")
        view = runout_pv.render_view()
        simple.AssignViewToLayout(view=view, layout=layout, hint=0)
        mesh = particle_domain(self.reader)
        speed = simple.Calculator(registrationName="speed", Input=mesh)
        speed.ResultArrayName = "speed"
        speed.Function = "mag(velocity)"
        top = largest_speed(self.options.out_dir) or 1.0
        step = builtins.max([v for v in (0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0) if top / v >= 6]
                            or [0.1])
        levels = [step * k for k in range(1, int(top / step) + 1)]
        lines = simple.Contour(registrationName="speed contours", Input=speed)
        lines.ContourBy = ["POINTS", "speed"]
        lines.Isosurfaces = levels
        base = runout_pv.base_line(self.reader)
        runout_pv.show_lines(base, view, BASE_GREY, z=-1.0, width=3.0, scale=scale)
        runout_pv.show(mesh, view, z=-0.5, scale=scale, ColorArrayName=["POINTS", ""],
                       AmbientColor=[0.85, 0.85, 0.85], DiffuseColor=[0.85, 0.85, 0.85],
                       Ambient=1.0, Diffuse=0.0)
        curves = runout_pv.show(lines, view, z=1.0, scale=scale, LineWidth=2.5)
        lut = runout_pv.colour_by(curves, view, "speed", "speed (m/s), contours every "
                                  f"{step:g} m/s", preset="Turbo",
                                  data_range=[0.0, step * math.ceil(top / step)])
        self.time_label(view, t)
        size = self.frame(view, layout, bounds)
        self.save(layout, f"velocity_contours_t{t:07.2f}.png", map_ends(lut),
                  f"speed contours every {step:g} m/s at t = {t:g} s", size)
        self.clear()

    # 2. Morphology evolution, drawn by matplotlib: ParaView's line charts
    # render every tick label twice, slightly offset, under Xvfb (ghost
    # marks), and cannot fix a chart's aspect ratio.
    def morphology(self):
        profile = simple.RunoutMorphology(registrationName="morphology", Input=self.reader)
        times = sorted(set([self.steps[0]] + self.times))
        curves = []
        for t in times:
            at = simple.ForceTime(registrationName=f"profile at {t:g} s",
                                  Input=simple.OutputPort(profile, 0))
            at.ForcedTime = t
            at.IgnorePipelineTime = 1
            data = servermanager.Fetch(at)
            points = sorted(data.GetPoint(i)[:2] for i in range(data.GetNumberOfPoints()))
            curves.append((t, [p[0] for p in points], [p[1] for p in points]))
        figure, axes = chart_figure(self.size)
        ax = axes[0]
        xs = [x for _, c, _ in curves for x in c] or [0.0, 1.0]
        ys = [y for _, _, c in curves for y in c] or [0.0, 1.0]
        ax.set_xlim(builtins.min(xs) - 5.0, builtins.max(xs) + 5.0)
        ax.set_ylim(builtins.min(0.0, builtins.min(ys)), 1.15 * builtins.max(ys))
        factor = chart_exaggeration(ax, figure)
        colours = []
        for i, (t, x, y) in enumerate(curves):
            # Distinct colours and dashes, the earlier times drawn wider
            # under the later ones, so that no profile hides another.
            colour = CURVES[i % len(CURVES)]
            ax.plot(x, y, color=colour, linestyle=DASHES[i % len(DASHES)],
                    linewidth=builtins.max(1.5, 3.5 - 0.5 * i), label=f"t = {t:g} s")
            colours.append(rgb255(colour))
        ax.set_xlabel("x (m)")
        ax.set_ylabel("surface height y (m)")
        ax.set_title("upper surface of the slide (Runout Morphology, Profile), "
                     + (f"heights exaggerated {factor} x" if factor > 1 else "true scale"))
        ax.legend(loc="upper right")
        self.save_chart(figure, "morphology.png", colours, "surface profiles at "
                        + ", ".join(f"{t:g}" for t, _, _ in curves) + " s")
        self.clear()

    def save_chart(self, figure, name, colours, what):
        path = os.path.join(self.folder, name)
        figure.savefig(path, dpi=100)
        pyplot.close(figure)
        self.manifest.append({"png": name, "size": self.size, "colours": colours,
                              "what": what})
        print(path)

    # 3. Plastic shear strain, shear bands, horsts and grabens, at each
    # chosen time (their evolution): one camera, one exaggeration and one
    # colour range for the series, so that its frames compare.
    def strain_bands(self):
        self.bounds = self.run_bounds()
        self.factor = exaggeration_for(self.bounds, self.size)
        strain, log = self.strain_range()
        for t in self.times:
            runout_pv.set_time(t)
            layout = simple.CreateLayout("strain bands")
            view = runout_pv.render_view()
            simple.AssignViewToLayout(view=view, layout=layout, hint=0)
            bands, _, _, lut = build_strain_bands(self.reader, view,
                                                  [1.0, float(self.factor), 1.0],
                                                  data_range=strain, log=log,
                                                  point_size=self.point_size())
            self.caption = self.time_label(view, t)[0]
            size = self.fit_to_run(view, layout)
            # The bands' red only where the frame has bands (not before the
            # slide fails).
            colours = map_ends(lut) + ([rgb255(BAND_RED)] if self.mark_dips(bands, view, t)
                                       else [])
            self.save(layout, f"strain_bands_t{t:07.2f}.png", colours,
                      f"plastic shear strain, shear bands (dips marked) and blocks at t = {t:g} s",
                      size)
            self.clear()

    def strain_range(self):
        """The series' one colour range of the plastic shear strain at the
        chosen times: 0 to its 99th percentile rounded up (the largest
        value is a few particles'), or, where the strain spans orders of
        magnitude (99th percentile above 5 medians: case 4, 0 to 500),
        three decades below a power of ten on a log scale. Returns (range,
        log)."""
        import numpy
        from vtkmodules.util.numpy_support import vtk_to_numpy
        values = []
        for t in self.times:
            self.reader.UpdatePipeline(t)
            array = servermanager.Fetch(self.reader).GetPointData().GetArray(
                "plastic_shear_strain")
            if array is not None:
                values.append(vtk_to_numpy(array))
        if not values:
            return [0.0, 1.0], False
        middle, top = numpy.percentile(numpy.concatenate(values), [50, 99])
        if top > 5 * middle and top > 0:
            decade = math.ceil(math.log10(top))
            return [10.0 ** (decade - 4), 10.0 ** decade], True
        return [0.0, round_up(float(top))], False

    def mark_dips(self, bands, view, t):
        """The dips (degrees, docs/filters.md: the true dip, not the
        exaggerated picture's) in red beside the bands' centroids, 14
        pixels high: the longest bands first, a band whose label would
        overlap one already placed left unlabelled and counted in the
        caption. Every band, marked or not, is listed in
        strain_bands_tNNNN.NN.csv beside the picture. Returns the number of
        bands."""
        bands.UpdatePipeline(t)
        table = servermanager.Fetch(bands, idx=1)
        names = [table.GetColumnName(c) for c in range(table.GetNumberOfColumns())]
        if "dip" not in names:
            return 0
        rows = [{n: table.GetColumnByName(n).GetValue(r) for n in names
                 if n in ("centroid_x", "centroid_y", "dip", "length")}
                for r in range(table.GetNumberOfRows())]
        rows.sort(key=lambda r: -r.get("length", 0.0))
        height = 14.0 / self.per_metre
        placed = []
        for row in rows:
            x = row["centroid_x"] + 0.5 * height
            y = self.factor * row["centroid_y"] + 0.5 * height
            # builtins': pvbatch's namespace has VTK's array any and abs.
            if builtins.any(builtins.abs(x - px) < 6.5 * height
                            and builtins.abs(y - py) < 1.5 * height for px, py in placed):
                continue
            placed.append((x, y))
            row["marked"] = 1
            self.text_at(view, f"{round(row['dip'])} deg", x, y, height, BAND_RED)
        with open(os.path.join(self.folder, f"strain_bands_t{t:07.2f}.csv"), "w",
                  newline="") as f:
            table_out = csv.DictWriter(f, ["centroid_x", "centroid_y", "dip", "length",
                                           "marked"], restval=0, extrasaction="ignore")
            table_out.writeheader()
            table_out.writerows(rows)
        if len(placed) < len(rows):
            self.caption.Text += (f"; dips of the {len(placed)} longest of {len(rows)} "
                                  "bands (all: .csv)")
        return len(rows)

    # 4. Runout and toe velocity against time (matplotlib, as figure 2),
    # the peak toe velocity of the first run marked: the contours' time.
    def history(self):
        runs = [self.options.out_dir] + list(self.options.compare)
        labels = (self.options.labels.split(",") if self.options.labels
                  else [os.path.basename(os.path.normpath(r)) for r in runs])
        if len(labels) != len(runs):
            raise SystemExit(f"--labels: {len(labels)} labels for {len(runs)} runs")
        figure, axes = chart_figure(self.size, 2)
        colours = []
        for i, (run, label) in enumerate(zip(runs, labels)):
            rows = read_history(run)
            colour = CURVES[(i + 1) % len(CURVES)]
            colours.append(rgb255(colour))
            time = [r["time"] for r in rows]
            for ax, column in zip(axes, ("runout", "toe_velocity")):
                ax.plot(time, [r[column] for r in rows], color=colour,
                        linestyle=DASHES[i % len(DASHES)], linewidth=2.5, label=label)
        peak = peak_toe_time(runs[0])
        if peak is not None:
            top = builtins.max(r["toe_velocity"] for r in read_history(runs[0]))
            axes[1].plot([peak], [top], "o", color=INK_CHART)
            axes[1].annotate(f"peak {top:.2g} m/s at {peak:g} s", (peak, top),
                             xytext=(8, -16), textcoords="offset points")
        for ax, title in zip(axes, ("runout (m)", "toe velocity (m/s)")):
            ax.set_xlabel("time (s)")
            ax.set_ylabel(title)
            ax.legend(loc="lower right" if title.startswith("runout") else "upper right")
        self.save_chart(figure, "history.png", colours,
                        "runout and toe velocity against time: " + ", ".join(labels))

    def write_manifest(self):
        with open(os.path.join(self.folder, "figures.json"), "w") as f:
            json.dump({"run": os.path.abspath(self.options.out_dir), "times": self.times,
                       "contour_time": self.contour_time,
                       "peak_toe_velocity_time": peak_toe_time(self.options.out_dir),
                       "figures": self.manifest}, f, indent=1)


def build_strain_bands(reader, view, scale=runout_pv.EXAGGERATION, data_range=None,
                       log=False, point_size=None):
    """Figure 3's pipeline in a view: the particles coloured by their
    plastic shear strain, the base, the shear band skeletons (red) and the
    block outlines (black) over them (also the pipeline of
    states/strain_bands.pvsm); with a point_size (the figures), the
    particles filled (show_filled) and the blocks filled by type."""
    bands = simple.RunoutShearBands(registrationName="shear bands", Input=reader)
    blocks = simple.RunoutHorstsAndGrabens(registrationName="horsts and grabens",
                                           Input=reader)
    base = runout_pv.base_line(reader)
    runout_pv.show_lines(base, view, BASE_GREY, z=-1.0, width=3.0, scale=scale)
    title = "plastic shear strain" + (", log scale" if log else "")
    if point_size:
        lut = show_filled(reader, view, scale, point_size, "plastic_shear_strain", title,
                          data_range=data_range)
    else:
        particles = runout_pv.show(reader, view, Representation="Points", PointSize=4.0,
                                   scale=scale)
        lut = runout_pv.colour_by(particles, view, "plastic_shear_strain", title,
                                  data_range=data_range)
    if log:
        lut.UseLogScale = 1
        # One label a decade: the automatic ones crowd on a log scale.
        bar = simple.GetScalarBar(lut, view)
        bar.UseCustomLabels, bar.AddRangeLabels, bar.LabelFormat = 1, 0, "%g"
        bar.CustomLabels = [10.0 ** k for k in range(round(math.log10(data_range[0])),
                                                     round(math.log10(data_range[1])) + 1)]
    if point_size:
        fill_blocks(blocks, view, scale)
    runout_pv.show_lines(blocks, view, BLOCK_INK, width=2.0, scale=scale)
    runout_pv.show_lines(bands, view, BAND_RED, z=2.0, width=3.0, scale=scale)
    return bands, blocks, base, lut


# The fill of each kind of block (Runout Horsts And Grabens' type_code).
BLOCK_TYPES = (("block", [0.6, 0.6, 0.6]), ("horst", [0.0, 0.45, 0.70]),
               ("graben", [0.90, 0.62, 0.0]))


def fill_blocks(blocks, view, scale):
    """The blocks filled by their type, translucent over the strain, with a
    legend in the lower right corner where the frame has blocks.
    Triangulated: the blocks are concave polygons, which VTK would fill as
    fans."""
    triangles = simple.Triangulate(registrationName="blocks filled", Input=blocks)
    display = runout_pv.show(triangles, view, z=0.5, scale=scale, Opacity=0.35)
    simple.ColorBy(display, ("CELLS", "type_code"))
    lut = simple.GetColorTransferFunction("type_code")
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = [v for code, (name, _) in enumerate(BLOCK_TYPES)
                       for v in (str(code), name)]
    lut.IndexedColors = [c for _, colour in BLOCK_TYPES for c in colour]
    display.LookupTable = lut
    display.Ambient, display.Diffuse = 1.0, 0.0
    blocks.UpdatePipeline(simple.GetAnimationScene().AnimationTime)
    display.SetScalarBarVisibility(view, blocks.GetDataInformation().GetNumberOfCells() > 0)
    bar = simple.GetScalarBar(lut, view)
    bar.Title = bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = runout_pv.INK
    bar.WindowLocation = "Lower Right Corner"
    bar.Orientation = "Horizontal"
    return display


def main():
    options = arguments()
    figures = Figures(options)
    figures.velocity()
    figures.morphology()
    figures.strain_bands()
    figures.velocity_contours()
    figures.history()
    if options.animation:
        figures.animation()
    figures.write_manifest()


if __name__ == "__main__":
    main()
