"""Renders the screenshot of docs/paraview.md: a run opened in ParaView
with the Runout filters applied with their default settings.

Top: the particles at one frame coloured by their plastic shear strain,
with the shear band skeletons (Runout Shear Bands), the block outlines
(Runout Horsts And Grabens) and the upper-surface profile (Runout
Morphology) over them, heights exaggerated 3 times. Bottom: Runout
Morphology History as the line chart ParaView opens it in. (Runout Plastic
Strain is left out: its gridded field would hide the particles.)

Usage (rendering needs an X server; Debian's ParaView has no offscreen
one, ../shared/BUILD.md):
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \\
    pvbatch states/render_walkthrough.py RUN.pvd RunoutPlugin.so OUT.png [TIME]
TIME defaults to the frame nearest a tenth of the run: early, while the
slide is still thick enough to show at the width of a page.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import simple  # noqa: E402

import runout_pv  # noqa: E402
from runout_pv import show  # noqa: E402

SIZE = [1100, 640]


def main():
    pvd, plugin, png = sys.argv[1:4]
    runout_pv.load_plugin(plugin)
    reader = runout_pv.open_run(pvd)
    times = reader.TimestepValues
    time = (float(sys.argv[4]) if len(sys.argv) > 4
            else min(times, key=lambda t: abs(t - times[-1] / 10)))

    # The filters with their default settings, as from Filters > Runout.
    bands = simple.RunoutShearBands(Input=reader)
    blocks = simple.RunoutHorstsAndGrabens(Input=reader)
    morphology = simple.RunoutMorphology(Input=reader)
    history = simple.RunoutMorphologyHistory(Input=reader)

    # The frame first, so that the colour range is the frame's.
    runout_pv.set_time(time)

    layout = simple.CreateLayout("walkthrough")
    render = runout_pv.render_view()
    simple.AssignViewToLayout(view=render, layout=layout, hint=0)
    particles = show(reader, render, Representation="Points", PointSize=4.0)
    runout_pv.colour_by(particles, render, "plastic_shear_strain", "plastic shear strain")
    for source, colour in ((bands, [0.85, 0.0, 0.0]), (blocks, [0.15, 0.15, 0.15]),
                           (morphology, [1.0, 0.45, 0.0])):
        runout_pv.show_lines(source, render, colour)

    chart = simple.CreateView("XYChartView")
    chart.LeftAxisTitle = "m"
    chart.BottomAxisTitle = "time (s)"
    layout.SplitVertical(0, 0.62)
    simple.AssignViewToLayout(view=chart, layout=layout, hint=2)
    curves = simple.Show(history, chart)
    curves.SeriesVisibility = ["toe", "runout", "length", "max_thickness"]
    curves.SeriesColor = ["toe", "0.1", "0.3", "0.9", "runout", "0.9", "0.1", "0.1",
                          "length", "0.2", "0.6", "0.2", "max_thickness", "0.5", "0.5", "0.5"]
    chart.LegendLocation = "TopLeft"

    layout.SetSize(*SIZE)  # after the views are in, or they keep their default size
    # Fit the slide's length to the view's width (its height is far less).
    simple.Render(render)
    runout_pv.fit_camera(render, reader.GetDataInformation().GetBounds())
    simple.SaveScreenshot(png, layout, ImageResolution=SIZE, CompressionLevel="9")


main()
