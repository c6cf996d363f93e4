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
import sys

from paraview import simple

EXAGGERATION = [1.0, 3.0, 1.0]
SIZE = [1100, 640]


def show(source, view, port=0, z=0.0, **properties):
    """Shows the output in the view, heights exaggerated, moved z towards
    the camera (lines drawn over the particles must be in front of them)."""
    display = simple.Show(simple.OutputPort(source, port), view)
    display.Scale = EXAGGERATION
    display.Position = [0.0, 0.0, z]
    for name, value in properties.items():
        setattr(display, name, value)
    return display


def main():
    pvd, plugin, png = sys.argv[1:4]
    simple.LoadPlugin(plugin, remote=False)
    reader = simple.PVDReader(FileName=pvd)
    # The filters' array selectors take their defaults from the input's
    # arrays, which ParaView knows once the reader has run (the GUI's Apply).
    reader.UpdatePipeline()
    times = reader.TimestepValues
    time = (float(sys.argv[4]) if len(sys.argv) > 4
            else min(times, key=lambda t: abs(t - times[-1] / 10)))

    # The filters with their default settings, as from Filters > Runout.
    bands = simple.RunoutShearBands(Input=reader)
    blocks = simple.RunoutHorstsAndGrabens(Input=reader)
    morphology = simple.RunoutMorphology(Input=reader)
    history = simple.RunoutMorphologyHistory(Input=reader)

    # The frame first, so that the colour range is the frame's.
    scene = simple.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = time

    layout = simple.CreateLayout("walkthrough")
    render = simple.CreateView("RenderView")
    render.OrientationAxesVisibility = 0
    render.Background = [1.0, 1.0, 1.0]
    render.UseColorPaletteForBackground = 0
    simple.AssignViewToLayout(view=render, layout=layout, hint=0)
    particles = show(reader, render, Representation="Points", PointSize=4.0)
    simple.ColorBy(particles, ("POINTS", "plastic_shear_strain"))
    particles.LookupTable = simple.GetColorTransferFunction("plastic_shear_strain")
    particles.LookupTable.ApplyPreset("Viridis (matplotlib)", True)
    particles.RescaleTransferFunctionToDataRange(False, True)
    particles.SetScalarBarVisibility(render, True)
    bar = simple.GetScalarBar(particles.LookupTable, render)
    bar.Title = "plastic shear strain"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.WindowLocation = "Upper Right Corner"
    bar.Orientation = "Horizontal"
    for source, colour in ((bands, [0.85, 0.0, 0.0]), (blocks, [0.15, 0.15, 0.15]),
                           (morphology, [1.0, 0.45, 0.0])):
        # Wireframe: the block outlines are polygons, which would hide the
        # particles as surfaces.
        show(source, render, z=1.0, Representation="Wireframe", LineWidth=2.5,
             ColorArrayName=["POINTS", ""], AmbientColor=colour, DiffuseColor=colour)

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
    xmin, xmax, ymin, ymax = reader.GetDataInformation().GetBounds()[:4]
    centre = [(xmin + xmax) / 2, EXAGGERATION[1] * (ymin + ymax) / 2, 0.0]
    render.CameraParallelProjection = 1
    render.CameraFocalPoint = centre
    render.CameraPosition = [centre[0], centre[1], 100.0]
    render.CameraViewUp = [0.0, 1.0, 0.0]
    width, height = render.ViewSize
    render.CameraParallelScale = 0.55 * (xmax - xmin) * height / width
    simple.SaveScreenshot(png, layout, ImageResolution=SIZE, CompressionLevel="9")


main()
