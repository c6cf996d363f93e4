"""What the pvbatch scripts of states/ share (render_walkthrough.py,
figures.py, make_states.py, load_state.py): finding a run's files, showing
the particles and the filters' lines in a render view with the heights
exaggerated, colour maps with a scale bar, the base drawn from the frames'
field data, and fitting the camera to the slide or having it follow the
slide.

Import it from a script in this folder (the scripts put their own folder
first on sys.path, pvbatch does not always).
"""
from paraview import servermanager, simple

from state_on_run import find_pvd  # noqa: F401 (the scripts take it from here)

EXAGGERATION = [1.0, 3.0, 1.0]
WHITE = [1.0, 1.0, 1.0]
INK = [0.1, 0.1, 0.1]

# The Runout filters' Python names (the XML labels without spaces).
RUNOUT_FILTERS = ("RunoutPlasticStrain", "RunoutShearBands", "RunoutHorstsAndGrabens",
                  "RunoutMorphology", "RunoutMorphologyHistory")


def load_plugin(plugin):
    """Loads RunoutPlugin.so unless its filters are already there (a
    PV_PLUGIN_PATH start-up load)."""
    if not hasattr(simple, "RunoutShearBands"):
        simple.LoadPlugin(plugin, remote=False)


def open_run(pvd, reader_name="RunoutSeriesReader"):
    """The reader of a run, updated: the filters' array selectors take
    their defaults from the input's arrays, which ParaView knows once the
    reader has run (the GUI's Apply). The plugin's Runout Series Reader
    checks each frame against the run's manifest before VTK parses it, so a
    damaged frame is a warning and an empty step, not an abort."""
    reader = getattr(simple, reader_name)(registrationName="run", FileName=pvd)
    reader.UpdatePipeline()
    return reader


def render_view(background=WHITE):
    """A render view for a slide seen side-on: white, no orientation axes."""
    view = simple.CreateView("RenderView")
    view.OrientationAxesVisibility = 0
    view.Background = background
    view.UseColorPaletteForBackground = 0
    return view


def show(source, view, port=0, z=0.0, scale=EXAGGERATION, **properties):
    """Shows the output in the view, heights exaggerated, moved z towards
    the camera (lines drawn over the particles must be in front of them)."""
    display = simple.Show(simple.OutputPort(source, port), view)
    display.Scale = scale
    display.Position = [0.0, 0.0, z]
    for name, value in properties.items():
        setattr(display, name, value)
    return display


def show_lines(source, view, colour, port=0, z=1.0, width=2.5, **properties):
    """Shows the output as lines of one colour over the particles.
    Wireframe: the block outlines are polygons, which would hide the
    particles as surfaces."""
    return show(source, view, port=port, z=z, Representation="Wireframe", LineWidth=width,
                ColorArrayName=["POINTS", ""], AmbientColor=colour, DiffuseColor=colour,
                **properties)


def colour_by(display, view, array, title, preset="Viridis (matplotlib)", component=None,
              data_range=None, location="Upper Right Corner"):
    """Colours the display by a point array with a preset, a horizontal
    scale bar; the range is the data's unless data_range is given.
    Unlit (ambient only), so the colours on screen are the map's."""
    simple.ColorBy(display, ("POINTS", array) if component is None
                   else ("POINTS", array, component))
    lut = simple.GetColorTransferFunction(array)
    lut.ApplyPreset(preset, True)
    display.LookupTable = lut
    if data_range is None:
        display.RescaleTransferFunctionToDataRange(False, True)
    else:
        lut.AutomaticRescaleRangeMode = "Never"
        lut.RescaleTransferFunction(*data_range)
    display.Ambient = 1.0
    display.Diffuse = 0.0
    display.SetScalarBarVisibility(view, True)
    bar = simple.GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = INK
    bar.WindowLocation = location
    bar.Orientation = "Horizontal"
    # The ends as the other labels read (0 and 4.5, not 0.0e+00 and 4.5e+00).
    bar.RangeLabelFormat = "%.3g"
    return lut


# The base as a polyline, from the frames' field data base_points (one
# line of VTK in the Programmable Filter, so it stays in a state file).
BASE_SCRIPT = """
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray
frame = self.GetInputDataObject(0, 0)
base = frame.GetFieldData().GetArray("base_points") if frame else None
out = self.GetPolyDataOutput()
if base is not None and base.GetNumberOfTuples() > 1:
    points = vtkPoints()
    lines = vtkCellArray()
    lines.InsertNextCell(base.GetNumberOfTuples())
    for i in range(base.GetNumberOfTuples()):
        lines.InsertCellPoint(points.InsertNextPoint(base.GetTuple3(i)))
    out.SetPoints(points)
    out.SetLines(lines)
"""


def base_line(reader):
    """A Programmable Filter that draws the base of the frames (empty when
    the frames have no base_points)."""
    base = simple.ProgrammableFilter(registrationName="base", Input=reader)
    base.OutputDataSetType = "vtkPolyData"
    base.Script = BASE_SCRIPT
    return base


def fit_camera(view, bounds, exaggeration=EXAGGERATION, fill=0.55, margin=1.0, size=None):
    """A parallel side-on camera with the slide's length (bounds of the
    particles, unexaggerated) across the view's width, or its exaggerated
    height, whichever needs more room. Call after the view has its size, or
    give the size of the pictures to be taken of it."""
    xmin, xmax, ymin, ymax = bounds[:4]
    centre = [(xmin + xmax) / 2, exaggeration[1] * (ymin + ymax) / 2, 0.0]
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[0], centre[1], 100.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    width, height = size or view.ViewSize
    view.CameraParallelScale = max(fill * (xmax - xmin) * height / width,
                                   margin * exaggeration[1] * (ymax - ymin) * 0.5 + 1.0)


def follow_slide(view, reader, exaggeration=EXAGGERATION):
    """A camera that follows the slide as the time moves (ParaView's
    Follow Data camera track): its focal point on the centre of the
    particles' bounds, as the displays draw them (heights exaggerated, so
    it follows a hidden scaled copy, "camera target"). Without it a state
    keeps the framing it was saved with while the slide runs out of view."""
    target = simple.Transform(registrationName="camera target", Input=reader)
    target.Transform.Scale = exaggeration
    track = simple.GetCameraTrack(view=view)
    track.Mode = "Follow-data"
    track.DataSource = target
    # The track reports "too few keyframes" on every frame without two,
    # which Follow Data does not read; registered, or a state leaves them out.
    frames = [simple.CameraKeyFrame(KeyTime=t) for t in (0.0, 1.0)]
    for k, frame in enumerate(frames):
        servermanager.ProxyManager().RegisterProxy("animation", f"camera key frame {k}", frame)
    track.KeyFrames = frames
    return track


def set_time(time):
    """The time of every view and filter (the scene's time is what a state
    saves; view.ViewTime is not)."""
    scene = simple.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = time
