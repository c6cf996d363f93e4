"""The Python steps of the GUI test (gui_walkthrough.py), run inside the
real ParaView GUI through its Python shell, between the Qt events that open
the run and apply the Runout filters from the Filters menu. Each step is one
shell command:

  exec(open(THIS_FILE).read()); runout_gui_step("record", "t0", CONFIG)

"record" records what the GUI made of the pipeline (sources, which outputs
are shown in which view and how, the views) and saves screenshots of the
render view: everything as the GUI shows it, then the particles alone, each
overlay alone and nothing, with the same camera, so that the test can tell
where each is drawn and whether it is covered. "finish" writes the record
to CONFIG's result file and ends ParaView (its --exit does not end it after
a test script with events in Debian's 5.11).
"""
import json
import os
import sys

from paraview import simple

# The record, kept across the shell commands of one session.
if "RUNOUT_GUI_RECORD" not in globals():
    RUNOUT_GUI_RECORD = {"steps": []}

# The overlays the test looks for: (filter's XML name, port, part).
OVERLAYS = (("RunoutShearBands", 0, "bands"), ("RunoutHorstGraben", 0, "blocks"),
            ("RunoutMorphology", 0, "profile"))
# The Strain Grid's outline: drawn where the slide is highest at t = 0,
# along the profile's top, so the test leaves those pixels out.
GRID = (("RunoutPlasticStrain", 1, "grid"),)
# What shows the particles: the reader, or Runout Plastic Strain's
# Particles, which take its place.
PARTICLES = (("PVDReader", 0), ("RunoutPlasticStrain", 0))
EXAGGERATION = [1.0, 3.0, 1.0]
# The render view's screenshots: wider than the view the GUI leaves it
# beside the chart, so that short bands still cover pixels.
SHOT = [1200, 400]


def _render_view():
    return [v for v in simple.GetViews() if v.GetXMLName() == "RenderView"][0]


def _source(xml_name):
    found = [s for s in simple.GetSources().values() if s.GetXMLName() == xml_name]
    return found[0] if found else None


def _key(rep):
    """(XML name of the source, port) a representation shows, or None."""
    prop = rep.SMProxy.GetProperty("Input")
    if prop is None or prop.GetNumberOfProxies() == 0:
        return None
    producer = prop.GetProxy(0)
    sources = [s for s in simple.GetSources().values() if s.SMProxy == producer]
    return (sources[0].GetXMLName() if sources else "?", prop.GetOutputPortForConnection(0))


def _displays(view):
    """{(source XML name, port): representation} in the view; the GUI's,
    none made here (GetDisplayProperties would make one)."""
    found = {}
    for rep in view.Representations:
        key = _key(rep)
        if key is not None:
            found[key] = rep
    return found


def _representations():
    """Every representation the GUI made: source, port, view, visible,
    representation type, colour array and range, chart series shown."""
    rows = []
    for view in simple.GetViews():
        for key, rep in _displays(view).items():
            row = {"source": key[0], "port": key[1], "view": view.GetXMLName(),
                   "visible": int(rep.Visibility)}
            if rep.GetProperty("Representation") is not None:
                row["representation"] = rep.SMProxy.GetProperty("Representation").GetElement(0)
            color = rep.GetProperty("ColorArrayName")
            if color is not None and rep.ColorArrayName[1]:
                # The array it is coloured by and its colour map's range.
                row["color"] = rep.ColorArrayName[1]
                points = rep.LookupTable.RGBPoints if rep.LookupTable else []
                row["range"] = [points[0], points[-4]] if len(points) >= 4 else []
            if rep.GetProperty("SeriesVisibility") is not None:
                # The names of the series shown.
                row["series"] = [str(v) for v in rep.SeriesVisibility]
            rows.append(row)
    return rows



def _shots(view, tag, folder):
    """Screenshots of the view as shown, then of each part alone."""
    displays = _displays(view)
    shown = {key: int(d.Visibility) for key, d in displays.items()}
    for key, display in displays.items():
        display.Scale = EXAGGERATION
        # Lines in front of the particles, as a user moves them (docs/paraview.md).
        display.Position = [0.0, 0.0, 0.0 if key in PARTICLES else 1.0]
    size = SHOT
    files = {}
    # Scalar bars and the orientation axes are drawn over everything in
    # every picture: left out, so that what differs is the data's.
    bars = [r for r in view.Representations if r.GetXMLName() == "ScalarBarWidgetRepresentation"]
    bars_shown = [int(r.Visibility) for r in bars]
    axes = view.OrientationAxesVisibility
    for bar in bars:
        bar.Visibility = 0
    view.OrientationAxesVisibility = 0

    def shoot(part):
        path = os.path.join(folder, f"{tag}_{part}.png")
        simple.Render(view)
        simple.SaveScreenshot(path, view, ImageResolution=size, TransparentBackground=0)
        files[part] = path

    shoot("gui")
    particles = [k for k in displays if k in PARTICLES and shown[k]]
    parts = {"particles": particles, "none": []}
    for name, port, part in OVERLAYS + GRID:
        parts[part] = [(name, port)]
    for part, keys in parts.items():
        for key, display in displays.items():
            display.Visibility = 1 if key in keys else 0
        shoot(part)
    for key, display in displays.items():
        display.Visibility = shown[key]
    for bar, visible in zip(bars, bars_shown):
        bar.Visibility = visible
    view.OrientationAxesVisibility = axes
    simple.Render(view)
    return files, size


def runout_gui_step(what, tag, config_path):
    with open(config_path) as f:
        config = json.load(f)
    record = RUNOUT_GUI_RECORD
    if what == "finish":
        try:
            record["layout"] = os.path.join(config["folder"], "layout.png")
            simple.SaveScreenshot(record["layout"], simple.GetLayout(), TransparentBackground=0)
            with open(config["result"], "w") as f:
                json.dump(record, f, indent=1, default=str)
        finally:
            os._exit(0)  # the test reads the record, or its absence
    view = _render_view()
    reader = _source("PVDReader")
    scene = simple.GetAnimationScene()
    step = {"tag": tag, "time": float(scene.AnimationTime), "views": [v.GetXMLName() for v in
                                                               simple.GetViews()],
            "sources": sorted(s.GetXMLName() for s in simple.GetSources().values()),
            "representations": _representations()}
    if reader is not None:
        # The states' camera (states/runout_pv.py), framed for the shots.
        if config["states"] not in sys.path:
            sys.path.insert(0, config["states"])
        import runout_pv
        runout_pv.fit_camera(view, reader.GetDataInformation().GetBounds(),
                             exaggeration=EXAGGERATION, margin=1.2, size=SHOT)
        step["shots"], step["size"] = _shots(view, tag, config["folder"])
        step["counts"] = {}
        for name, port, part in OVERLAYS:
            source = _source(name)
            if source is not None:
                info = source.GetDataInformation(port)
                step["counts"][part] = [info.GetNumberOfPoints(), info.GetNumberOfCells()]
    record["steps"].append(step)
