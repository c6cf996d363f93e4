"""The Python steps of the GUI test (gui_walkthrough.py), run inside the
real ParaView GUI through its Python shell, between the Qt events that open
the run and apply the Runout filters from the Filters menu. Each step is one
shell command:

  exec(open(THIS_FILE).read()); runout_gui_step("record", "t0", CONFIG)

"record" records what the GUI made of the pipeline (sources, which outputs
are shown in which view and how, the views) and saves screenshots of the
render view: everything as the GUI shows it, then the particles alone, each
overlay alone and nothing, with the same camera, so that the test can tell
where each is drawn and whether it is covered. "sheet" (tag FILTER:PORT)
shows one output of a Runout filter in a spreadsheet, as a user opens one,
and records what the spreadsheet shows; "sheet-close" removes it. "frame"
fits the camera to the render view, "style" does what docs/paraview.md has
the user do after Apply (colours, exaggeration), "picture" saves the whole
screen (docs/paraview.md's pictures). "new-reader" records what
Sources > Runout Series Reader made and removes it. "state", run by
--script in a GUI that scripts/paraview-state opened, records the state at
the run's last frame into CONFIG's result file and ends ParaView. "finish"
writes the record
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
OVERLAYS = (("RunoutShearBands", 0, "bands"), ("RunoutHorstsAndGrabens", 0, "blocks"),
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


def _axis_titles():
    """{chart view's XML name: [left, bottom]}: the titles of the axes its
    chart draws (the vtkAxis objects, not the view's properties alone)."""
    from vtkmodules.vtkChartsCore import vtkAxis
    titles = {}
    for view in simple.GetViews():
        if view.GetProperty("LeftAxisTitle") is not None:
            chart = view.GetClientSideObject().GetChart()
            titles[view.GetXMLName()] = [chart.GetAxis(vtkAxis.LEFT).GetTitle(),
                                         chart.GetAxis(vtkAxis.BOTTOM).GetTitle()]
    return titles


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


# The spreadsheet the "sheet" steps show the filters' outputs in, and its
# layout tab, kept across the shell commands until "sheet-close".
if "RUNOUT_GUI_SHEET" not in globals():
    RUNOUT_GUI_SHEET = {}
# The attributes the spreadsheet's Attribute menu offers (vtkDataObject's
# field associations), by the names the test reports.
SHEET_ATTRIBUTES = {"points": 0, "cells": 1, "field": 2, "rows": 6}


def _sheet(name, port):
    """Shows output `port` of the filter `name` alone in a spreadsheet (in
    a layout tab of its own, made by the first call; the Qt table paints it
    once the shell returns to the event loop), and records what the
    spreadsheet serves that table for each attribute: rows and visible
    columns, and every value of the first row (read as the table reads
    them). The output's own counts come with it, to compare."""
    if not RUNOUT_GUI_SHEET:
        layout = simple.CreateLayout("Runout spreadsheets")
        sheet = simple.CreateView("SpreadSheetView")
        simple.AssignViewToLayout(view=sheet, layout=layout, hint=0)
        RUNOUT_GUI_SHEET.update(layout=layout, view=sheet)
    sheet = RUNOUT_GUI_SHEET["view"]
    for rep in sheet.Representations:
        rep.Visibility = 0
    source = _source(name)
    simple.Show(simple.OutputPort(source, port), sheet)
    info = source.GetDataInformation(port)
    row = {"source": name, "port": port, "class": info.GetDataClassName(),
           "counts": {"points": info.GetNumberOfPoints(), "cells": info.GetNumberOfCells(),
                      "rows": info.GetNumberOfRows()},
           "attributes": {}}
    table = sheet.GetClientSideObject()
    for attribute, association in SHEET_ATTRIBUTES.items():
        sheet.FieldAssociation = association
        simple.Render(sheet)
        columns = [i for i in range(table.GetNumberOfColumns()) if table.GetColumnVisibility(i)]
        rows = table.GetNumberOfRows()
        first = [table.GetValue(0, i).ToString() for i in columns] if rows else []
        row["attributes"][attribute] = {"rows": rows, "first": first,
                                        "columns": [table.GetColumnName(i) for i in columns]}
    sheet.FieldAssociation = SHEET_ATTRIBUTES["rows" if info.GetDataClassName() == "vtkTable"
                                              else "points"]
    simple.Render(sheet)
    return row


def _close_sheet(view):
    """Removes the spreadsheet and its tab: the walk-through goes on with
    the render view and the chart alone."""
    simple.Delete(RUNOUT_GUI_SHEET["view"])
    simple.RemoveLayout(RUNOUT_GUI_SHEET["layout"])
    RUNOUT_GUI_SHEET.clear()
    simple.SetActiveView(view)


# The colours docs/paraview.md has the user give the overlays (its step 4):
# (filter's XML name, port): RGB, apart from the particles' blue to red.
LINE_COLOURS = {("RunoutShearBands", 0): [1.0, 1.0, 0.0],
                ("RunoutHorstsAndGrabens", 0): [0.0, 0.0, 0.0],
                ("RunoutMorphology", 0): [0.0, 0.8, 0.0]}


def _style(view):
    """What docs/paraview.md's step 4 has the user do after Apply: the
    particles coloured by plastic_shear_strain, rescaled over all time
    steps, with a scale bar; the shear bands, block outlines and profile in
    solid colours of their own; heights exaggerated and the lines moved
    towards the camera (as _shots does)."""
    for key, display in _displays(view).items():
        display.Scale = EXAGGERATION
        display.Position = [0.0, 0.0, 0.0 if key in PARTICLES else 1.0]
        if key in PARTICLES and display.Visibility:
            simple.ColorBy(display, ("POINTS", "plastic_shear_strain"))
            display.RescaleTransferFunctionToDataRangeOverTime()
            display.SetScalarBarVisibility(view, True)
        elif key in LINE_COLOURS:
            if display.LookupTable:  # the profile's thickness: its bar goes with it
                display.SetScalarBarVisibility(view, False)
            display.ColorArrayName = ["POINTS", ""]  # Solid Color
            display.AmbientColor = display.DiffuseColor = LINE_COLOURS[key]
    simple.Render(view)


def _save_screen(fbdir, path):
    """The whole X screen as a PNG: Xvfb's framebuffer, which -fbdir
    keeps as an XWD file (header big-endian; 32-bit pixels in the byte
    order it states, 8 bits a channel for the 24-bit screen)."""
    import struct

    import numpy
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOImage import vtkPNGWriter
    with open(os.path.join(fbdir, "Xvfb_screen0"), "rb") as f:
        data = f.read()
    header = struct.unpack(">25I", data[:100])
    size, width, height, byte_order, stride, colours = (header[0], header[4], header[5],
                                                         header[7], header[12], header[19])
    start = size + 12 * colours
    pixels = numpy.frombuffer(data, numpy.uint8, stride * height, start).reshape(height, stride)
    pixels = pixels[:, :4 * width].reshape(height, width, 4)
    # Red is the third byte of a pixel in LSBFirst order, the second in MSBFirst.
    rgb = pixels[..., [2, 1, 0]] if byte_order == 0 else pixels[..., [1, 2, 3]]
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    # VTK's images start at the bottom row.
    image.GetPointData().SetScalars(numpy_to_vtk(numpy.ascontiguousarray(
        rgb[::-1].reshape(-1, 3)), deep=1))
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


def _fit_camera(view, reader, config, size):
    """The states' camera (states/runout_pv.py) on the run's particles,
    framed for pictures of `size` (None: the view's own)."""
    if config["states"] not in sys.path:
        sys.path.insert(0, config["states"])
    import runout_pv
    runout_pv.fit_camera(view, reader.GetDataInformation().GetBounds(),
                         exaggeration=EXAGGERATION, margin=1.2, size=size)


def _grabens():
    """The blocks Runout Horsts And Grabens types graben (type_code 2) in
    the frame shown, and the columns of Runout Morphology's table named
    after grabens: {"typed": n, "morphology": {column: value}}."""
    from paraview import servermanager
    blocks, morphology = _source("RunoutHorstsAndGrabens"), _source("RunoutMorphology")
    if blocks is None or morphology is None:
        return {}
    table = servermanager.Fetch(blocks, idx=1)
    codes = table.GetColumnByName("type_code")
    typed = sum(1 for r in range(table.GetNumberOfRows())
                if codes is not None and codes.GetValue(r) == 2)
    row = servermanager.Fetch(morphology, idx=1)
    named = {row.GetColumnName(c): row.GetValue(0, c).ToDouble()
             for c in range(row.GetNumberOfColumns())
             if "graben" in row.GetColumnName(c) and not row.GetColumnName(c).startswith("initial")}
    return {"typed": typed, "morphology": named}


def _new_reader():
    """What Sources > Runout Series Reader made (before any Apply): its
    file name and time steps; then removed, leaving the walk-through's
    pipeline as it was."""
    reader = _source("RunoutSeriesReader")
    if reader is None:
        return {"made": False}
    made = {"made": True, "file": reader.FileName, "steps": len(reader.TimestepValues)}
    simple.Delete(reader)
    return made


def _state_on_run(view):
    """A state as scripts/paraview-state opened it, at the run's last frame
    (the VCR's Last Frame): the sources, the file its reader reads, the
    particles' bounds, the camera, and the strain's colour map against the
    frame's strain."""
    reader = simple.FindSource("run")
    scene = simple.GetAnimationScene()
    scene.AnimationTime = reader.TimestepValues[-1]
    # Not simple.Render: its first call in a session resets the camera.
    view.StillRender()
    info = reader.GetDataInformation()
    points = simple.GetColorTransferFunction("plastic_shear_strain").RGBPoints
    return {"sources": sorted(s.GetXMLName() for s in simple.GetSources().values()),
            "file": reader.FileName, "time": float(scene.AnimationTime),
            "last": reader.TimestepValues[-1], "bounds": list(info.GetBounds()),
            "focal": list(view.CameraFocalPoint), "scale": view.CameraParallelScale,
            "size": list(view.ViewSize), "exaggeration": list(EXAGGERATION),
            "map": [points[0], points[-4]],
            "strain": list(info.GetPointDataInformation().GetArrayInformation(
                "plastic_shear_strain").GetComponentRange(0))}


def runout_gui_step(what, tag, config_path):
    with open(config_path) as f:
        config = json.load(f)
    record = RUNOUT_GUI_RECORD
    if what == "finish":
        try:
            with open(config["result"], "w") as f:
                json.dump(record, f, indent=1, default=str)
        finally:
            os._exit(0)  # the test reads the record, or its absence
    view = _render_view()
    scene = simple.GetAnimationScene()
    if what == "state":
        try:
            with open(config["result"], "w") as f:
                json.dump(_state_on_run(view), f, indent=1, default=str)
        finally:
            os._exit(0)
    if what == "new-reader":
        record["new_reader"] = _new_reader()
        return
    if what == "sheet":
        name, port = tag.split(":")
        shown = _sheet(name, int(port))
        shown["time"] = float(scene.AnimationTime)
        record.setdefault("sheets", []).append(shown)
        return
    if what == "sheet-close":
        _close_sheet(view)
        return
    reader = _source("PVDReader")
    if what == "frame":
        # The render view two thirds of the layout (as a user drags the
        # splitter: the slide is long and thin), the slide across it.
        simple.GetLayout().SetSplitFraction(0, 2 / 3)
        _fit_camera(view, reader, config, None)
        simple.Render(view)
        return
    if what == "style":
        _style(view)
        return
    if what == "picture":
        # The screen as the event loop last painted it.
        path = os.path.join(config["folder"], f"{tag}.png")
        _save_screen(config["fbdir"], path)
        record.setdefault("pictures", []).append(path)
        return
    step = {"tag": tag, "time": float(scene.AnimationTime), "views": [v.GetXMLName() for v in
                                                               simple.GetViews()],
            "sources": sorted(s.GetXMLName() for s in simple.GetSources().values()),
            "representations": _representations(), "axis_titles": _axis_titles()}
    if reader is not None:
        _fit_camera(view, reader, config, SHOT)
        step["shots"], step["size"] = _shots(view, tag, config["folder"])
        step["counts"] = {}
        for name, port, part in OVERLAYS:
            source = _source(name)
            if source is not None:
                info = source.GetDataInformation(port)
                step["counts"][part] = [info.GetNumberOfPoints(), info.GetNumberOfCells()]
        step["grabens"] = _grabens()
    record["steps"].append(step)
