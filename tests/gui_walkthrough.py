"""The Runout plugin in the real ParaView GUI, as docs/paraview.md walks a
user through it: the `paraview` binary under Xvfb, the plugin loaded at
start-up through PV_PLUGIN_PATH, a run opened with --data, then Qt events
(ParaView's own test player, --test-script) that press Apply, pick each
Runout filter from Filters > Alphabetical with the run selected in the
Pipeline Browser and press Apply, and step through time with the VCR
toolbar. Between the events, gui_steps.py records from the GUI's Python
shell what the GUI made (views, representations, visibilities) and saves
screenshots of the render view.

It fails on any error or warning ParaView prints, and unless
- the GUI made one render view and one line chart, no spreadsheet;
- the particles stay shown, block outlines are Wireframe, the Strain Grid
  an Outline, the chart shows the history's lengths, its axes titled with
  their units;
- at t = 0, where the filters are applied, the screenshots show the
  particles with the profile over them, there are no bands or blocks, and
  nothing shown is coloured by a map of range zero;
- at t = 0 each output of each Runout filter (empty bands and blocks,
  one-row tables among them), shown in a spreadsheet, lists its rows;
- at the last frame the screenshots show the particles and, over them, the
  shear bands, the block outlines and the profile: each drawn alone marks
  pixels, those pixels lie within the particles' picture, and in the
  picture as the GUI shows it most of them still have the overlay's colour
  (it is drawn, not covered), while most of the particles' pixels still
  differ from the background (not covered by the outlines' polygons);
- Sources > Runout Series Reader, made after the walk-through, waits for
  its file (no time steps, no message);
- Runout Morphology reports no count named after grabens that differs from
  the blocks Runout Horsts And Grabens types graben.
Then it opens states/strain_bands.pvsm on the run with
scripts/paraview-state (--test-script: paraview refuses --script beside
--state), and fails on any error or warning, and unless at the run's last
frame the Runout filters are there, the reader reads the run, the camera
looks at the centre of the slide as drawn and the strain's colour map spans
the frame's strain.

Run by pvpython (for VTK's PNG reader and numpy):
  pvpython tests/gui_walkthrough.py SOURCE_DIR RUNOUT_CLI PLUGIN_DIR PARAVIEW [KEEP_DIR]
KEEP_DIR keeps the screenshots, the pictures of the whole GUI that
docs/paraview.md shows (gui_layout.png, gui_walkthrough.png: copy them to
docs/images/ after a passing run) and the record, record.json, which
`gui_walkthrough.py --check RECORD` checks again.
Exits 77 (skipped) without xvfb-run or the paraview binary.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

# -fbdir: Xvfb keeps its screen in a file there, for the pictures of the
# whole GUI.
XVFB = ["xvfb-run", "-a", "-s", "-screen 0 1600x1000x24 -noreset -fbdir {fbdir}"]
# The overlays first: Runout Plastic Strain's particles take the run's place
# (ParaView's default), the overlays must leave it shown. The history last:
# its chart becomes the active view, where the others would not be shown.
OVERLAY_FILTERS = ("RunoutShearBands", "RunoutHorstsAndGrabens", "RunoutMorphology")
FILTERS = OVERLAY_FILTERS + ("RunoutPlasticStrain", "RunoutMorphologyHistory")
# Every Runout filter has two outputs (ports 0 and 1).
PORTS = 2
# The history's chart: the plugin's line chart with titled axes (left, bottom).
CHART = "RunoutHistoryChartView"
AXIS_TITLES = ["distance (m)", "time (s)"]
# ParaView's Qt object names (its test recorder writes the same).
SHELL = "pqClientMainWindow/pythonShellDock/pythonShell/consoleWidget"
APPLY = "pqClientMainWindow/propertiesDock/propertiesPanel/Accept"
MENU = "pqClientMainWindow/menubar/menuFilters/Alphabetical"
SOURCES = "pqClientMainWindow/menubar/menuSources/Alphabetical"
BROWSER = "pqClientMainWindow/pipelineBrowserDock/pipelineBrowser"
VCR = "pqClientMainWindow/VCRToolbar/"
# What ParaView prints for an error or a warning (the terminal copy of its
# Output Messages window).
PROBLEM = re.compile(r"ERR\|| WARN\||ERROR|Warning:|Error:")


def fail(failures):
    for failure in failures:
        print("FAILED:", failure)
    sys.exit(1 if failures else 0)


def event(obj, command, arguments=""):
    quote = (arguments.replace("&", "&amp;").replace('"', "&quot;")
             .replace("<", "&lt;").replace(">", "&gt;"))
    return f'  <pqevent object="{obj}" command="{command}" arguments="{quote}" />'


def shell_step(steps, config, what, tag=""):
    """The event that runs gui_steps.py's step in the GUI's Python shell."""
    return event(SHELL, "executeCommand",
                 f"exec(open({steps!r}).read()); runout_gui_step({what!r}, {tag!r}, {config!r})")


def events_of(lines):
    """A test script of ParaView's event player."""
    return "<?xml version=\"1.0\" ?>\n<pqevents>\n" + "\n".join(lines) + "\n</pqevents>\n"


def events(steps, config):
    """The test script: Apply on the opened run, every filter on the run,
    then the first frame, the last, and back one."""
    def step(what, tag):
        return shell_step(steps, config, what, tag)
    lines = [event(APPLY, "activate"), step("record", "opened")]
    for name in FILTERS:
        # The run selected in the Pipeline Browser (its first source).
        lines += [event(BROWSER, "mousePress", "1,1,0,50,5,/0:0/0:0"),
                  event(BROWSER, "mouseRelease", "1,0,0,50,5,/0:0/0:0"),
                  event(MENU, "activate", name), event(APPLY, "activate")]
        if name == OVERLAY_FILTERS[-1]:
            lines.append(step("record", "overlays"))
    lines.append(step("record", "applied"))
    # Every output in a spreadsheet where the filters were applied (t = 0:
    # empty bands and blocks, one-row tables), each shown between events so
    # that the Qt table paints it.
    lines += [step("sheet", f"{name}:{port}") for name in FILTERS for port in range(PORTS)]
    lines += [step("sheet-close", ""), event(VCR + "actionVCRLastFrame", "activate"),
              step("record", "last"), event(VCR + "actionVCRPreviousFrame", "activate"),
              step("record", "previous")]
    # docs/paraview.md's pictures: the GUI after the walk-through, then with
    # the colours its step 4 has the user give (each a step of its own, so
    # that the screen is painted before it is saved).
    lines += [step("frame", ""), step("picture", "gui_layout"), step("style", ""),
              step("picture", "gui_walkthrough")]
    # The plugin's reader from the Sources menu, as a user starts with it:
    # made before a file is picked, it must wait for one without an error.
    lines += [event(SOURCES, "activate", "RunoutSeriesReader"), step("new-reader", ""),
              step("finish", "")]
    return events_of(lines)


def pixels(path):
    """(height, width, 3) int array of a PNG, top row first."""
    from figures_check import png_pixels
    width, height, data = png_pixels(path)
    return data.reshape(height, width, 3)[::-1]


def check_step(step, failures):
    """The pixel checks of one recorded step's screenshots."""
    import numpy
    shots = {part: pixels(path) for part, path in step["shots"].items()}
    background = shots["none"]

    def drawn(part):
        return numpy.abs(shots[part] - background).max(axis=2) > 40

    particles = drawn("particles")
    gui = shots["gui"]
    count = int(particles.sum())
    print(f"{step['tag']} (t = {step['time']:g}): particles {count} px", end="")
    if count < 2000:
        failures.append(f"{step['tag']}: the particles cover {count} pixels alone")
        return
    rows, cols = numpy.nonzero(particles)
    box = (rows.min() - 15, rows.max() + 15, cols.min() - 15, cols.max() + 15)
    # Lines cross the particles; polygons drawn as surfaces would cover them
    # (in a light grey that differs from the white particles by only 20 to
    # 40 per channel: the same session renders what is not covered alike).
    still = numpy.abs(gui - shots["particles"]).max(axis=2)[particles] <= 12
    print(f" {still.mean():.0%} shown", end="")
    if still.mean() < 0.5:
        failures.append(f"{step['tag']}: only {still.mean():.0%} of the particles' pixels are "
                        "shown in the GUI's picture (covered?)")
    # Where the grid's outline crosses an overlay, either may be on top.
    grid = drawn("grid")
    for part in ("bands", "blocks", "profile"):
        mask = drawn(part) & ~grid
        n = int(mask.sum())
        cells = step["counts"].get(part, [0, 0])[1]
        print(f", {part} {n} px ({cells} cells)", end="")
        if cells == 0:
            continue  # nothing to draw at this frame (e.g. no bands at t = 0)
        if n < 20:
            failures.append(f"{step['tag']}: {part} ({cells} cells) draw {n} pixels alone")
            continue
        r, c = numpy.nonzero(mask)
        inside = ((r >= box[0]) & (r <= box[1]) & (c >= box[2]) & (c <= box[3])).mean()
        if inside < 0.9:
            failures.append(f"{step['tag']}: {part}: {inside:.0%} of its pixels over the particles")
        # Where the overlay alone and the particles alone look different,
        # the GUI's picture must look like the overlay: drawn over them, not
        # hidden behind them (antialiased lines blend, hence "closer").
        alone, under, shown = shots[part][mask], shots["particles"][mask], gui[mask]
        distinct = numpy.abs(alone - under).max(axis=1) > 40
        if distinct.sum() < 10:
            failures.append(f"{step['tag']}: {part}: {int(distinct.sum())} of its pixels differ "
                            "from the particles under them: not told apart")
            continue
        closer = (numpy.abs(shown - alone).sum(axis=1) < numpy.abs(shown - under).sum(axis=1))
        kept = closer[distinct].mean()
        print(f" {kept:.0%} on top", end="")
        if kept < 0.6:
            failures.append(f"{step['tag']}: {part}: {kept:.0%} of its pixels shown over the "
                            "particles in the GUI's picture (hidden behind them?)")
    print()


def check_opening(applied, failures):
    """Where ParaView opens the series (t = 0), as docs/paraview.md says:
    the particles and the profile over them, no bands or blocks yet (no
    plastic strain), and no display coloured by a map whose range is that
    of a field still 0 everywhere (it would keep it when the time moves)."""
    if applied["time"] != 0:
        failures.append(f"the filters were applied at t = {applied['time']}, not 0")
    for part in ("bands", "blocks"):
        if applied["counts"].get(part, [0, 0])[1]:
            failures.append(f"{part} at t = 0: docs/paraview.md says there are none")
    for rep in applied["representations"]:
        low, high = (rep.get("range") or [0, 1])[:2]
        if rep["visible"] and rep.get("color") and not high - low > 1e-9 * max(1, abs(high)):
            failures.append(f"{rep['source']} port {rep['port']} coloured by {rep['color']} "
                            f"with the range {low:g} to {high:g} at t = 0")
    check_step(applied, failures)


def check_sheets(sheets, failures):
    """Each Runout filter's outputs at t = 0 in a spreadsheet (steps
    "sheet"): every one shown (a crash leaves no record), and for the
    attributes the output has (a table's rows; a data set's points and
    cells) the spreadsheet lists as many rows as the output has, with
    columns where there are rows; the history's tables carry no frame's
    field data."""
    shown = sorted((s["source"], s["port"]) for s in sheets)
    expected = sorted((name, port) for name in FILTERS for port in range(PORTS))
    if shown != expected:
        failures.append(f"outputs shown in a spreadsheet: {shown}, not {expected}")
    for sheet in sheets:
        what = f"{sheet['source']} port {sheet['port']} in a spreadsheet"
        if sheet["time"] != 0:
            failures.append(f"{what} at t = {sheet['time']}, not 0")
        own = ("rows",) if sheet["class"] == "vtkTable" else ("points", "cells")
        for attribute in own:
            listed = sheet["attributes"][attribute]
            count = sheet["counts"][attribute]
            if listed["rows"] != count:
                failures.append(f"{what}: {listed['rows']} rows of {attribute}, "
                                f"the output has {count}")
            elif count and not listed["columns"]:
                failures.append(f"{what}: {count} {attribute} and no column")
        # The history's tables span every frame: no one frame's field data
        # (its TimeValue, ...) may come with them.
        field = sheet["attributes"]["field"]
        if sheet["source"] == "RunoutMorphologyHistory" and field["columns"]:
            failures.append(f"{what}: field data {field['columns']}")


def check_pictures(paths, failures):
    """docs/paraview.md's pictures of the whole screen: both saved, the
    GUI's window over the screen (not one colour), and the second with the
    particles coloured (not the first again)."""
    import numpy
    names = [os.path.basename(p) for p in paths]
    if names != ["gui_layout.png", "gui_walkthrough.png"]:
        failures.append(f"pictures of the GUI: {names}")
        return
    screens = [pixels(p) for p in paths]
    for name, screen in zip(names, screens):
        if screen.shape[:2] != (1000, 1600) or screen.std() < 10:
            failures.append(f"{name}: {screen.shape[1]} x {screen.shape[0]}, "
                            f"spread {screen.std():.1f}: not the GUI's screen")
    changed = (numpy.abs(screens[0] - screens[1]).max(axis=2) > 40).mean()
    if changed < 0.005:
        failures.append(f"{names[1]} differs from {names[0]} in {changed:.2%} of its pixels: "
                        "not recoloured")


def check_new_reader(made, failures):
    """Sources > Runout Series Reader made the reader, with no file and no
    time steps yet (and, the log checks, without an error)."""
    if not made.get("made"):
        failures.append("Sources > Runout > Runout Series Reader made no reader")
    elif made["file"] or made["steps"]:
        failures.append(f"the new Runout Series Reader reads {made['file']!r} "
                        f"({made['steps']} steps) before a file is picked")


def check_state(state, run_pvd, failures):
    """states/strain_bands.pvsm as scripts/paraview-state opened it on the
    run, at its last frame: the Runout filters there, the reader on the
    run, the camera on the slide as drawn (heights exaggerated), and the
    strain's colours spanning the frame's strain."""
    for name in ("RunoutShearBands", "RunoutHorstsAndGrabens"):
        if name not in state["sources"]:
            failures.append(f"state: {name} not loaded ({state['sources']})")
    if os.path.realpath(state["file"]) != os.path.realpath(run_pvd):
        failures.append(f"state: its reader reads {state['file']}, not the run's {run_pvd}")
    if state["time"] != state["last"]:
        failures.append(f"state: at t = {state['time']} after Last Frame, not {state['last']}")
    b, scale = state["bounds"], state["exaggeration"]
    centre = [(b[0] + b[1]) / 2 * scale[0], (b[2] + b[3]) / 2 * scale[1]]
    off = [abs(f - c) for f, c in zip(state["focal"], centre)]
    if max(off) > 1e-6 * (b[1] - b[0]):
        failures.append(f"state: the camera looks at {state['focal'][:2]}, the slide's centre "
                        f"is {centre} at the last frame: it does not follow the slide")
    low, high = state["strain"]
    if not (abs(state["map"][0] - low) <= 1e-6 * max(1.0, high)
            and abs(state["map"][1] - high) <= 1e-6 * max(1.0, high)):
        failures.append(f"state: the strain's colours span {state['map']}, the frame's strain "
                        f"{state['strain']}")
    print(f"state at t = {state['time']:g}: camera on x = {state['focal'][0]:.2f} "
          f"(slide {b[0]:.2f} to {b[1]:.2f}), colours {state['map']} for strain "
          f"{state['strain']}")


def check_record(record, failures):
    steps = {step["tag"]: step for step in record["steps"]}
    if sorted(steps) != ["applied", "last", "opened", "overlays", "previous"]:
        failures.append(f"recorded steps {sorted(steps)}")
        return
    applied = steps["applied"]
    for name in FILTERS:
        if name not in applied["sources"]:
            failures.append(f"{name} not in the pipeline after its Apply: {applied['sources']}")
    views = sorted(applied["views"])
    if views != ["RenderView", CHART]:
        failures.append(f"views after the walk-through: {views} (one render view, one chart)")
    titles = applied["axis_titles"].get(CHART)
    if titles != AXIS_TITLES:
        failures.append(f"the history chart's axes (left, bottom) are titled {titles}, "
                        f"not {AXIS_TITLES}")
    reps = {(r["source"], r["port"], r["view"]): r for r in applied["representations"]}

    def rep(source, port, view="RenderView"):
        return reps.get((source, port, view), {})

    overlays = {(r["source"], r["port"], r["view"]): r for r in steps["overlays"]["representations"]}
    if not overlays.get(("PVDReader", 0, "RenderView"), {}).get("visible"):
        failures.append("the run's particles are hidden once the overlay filters are applied")
    if not rep("RunoutPlasticStrain", 0).get("visible"):
        failures.append("Runout Plastic Strain's particles are not shown after its Apply")
    for source, port, kind in (("RunoutHorstsAndGrabens", 0, "Wireframe"),
                               ("RunoutPlasticStrain", 1, "Outline")):
        if rep(source, port).get("representation") != kind:
            failures.append(f"{source} port {port} shown as {rep(source, port)}, not {kind}")
    for source in ("RunoutShearBands", "RunoutHorstsAndGrabens", "RunoutMorphology"):
        if not rep(source, 0).get("visible"):
            failures.append(f"{source} is not shown in the render view")
    chart = rep("RunoutMorphologyHistory", 1, CHART)
    shown = sorted(chart.get("series", []))
    if shown != sorted(["toe (m)", "rear (m)", "runout (m)", "length (m)",
                        "max_thickness (m)"]):
        failures.append(f"the history chart shows {shown}")
    check_opening(applied, failures)
    check_sheets(record.get("sheets", []), failures)
    check_pictures(record.get("pictures", []), failures)
    check_new_reader(record.get("new_reader", {}), failures)
    times = [steps[t]["time"] for t in ("opened", "last", "previous")]
    if not times[0] < times[2] < times[1]:
        failures.append(f"times at open, last, previous frame: {times}")
    for tag in ("last", "previous"):
        check_step(steps[tag], failures)
    for tag in ("applied", "last", "previous"):
        grabens = steps[tag].get("grabens", {})
        for column, value in grabens.get("morphology", {}).items():
            if value != grabens["typed"]:
                failures.append(f"{tag}: Runout Morphology's {column} is {value:g} where Runout "
                                f"Horsts And Grabens types {grabens['typed']} blocks graben")
    for part in ("bands", "blocks"):
        if not steps["last"]["counts"].get(part, [0, 0])[1]:
            failures.append(f"no {part} at the last frame: the run shows nothing to check")


def run_gui(command, env, what, result, failures):
    """Runs ParaView's GUI; its record (the JSON file `result` that its
    Python steps write), or None. Each error or warning line it prints, and
    a missing record, is a failure of `what`."""
    start = time.time()
    proc = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          env=env)
    print(f"{what} ran {time.time() - start:.0f} s, exit {proc.returncode}")
    problems = [line for line in proc.stdout.splitlines() if PROBLEM.search(line)]
    for line in problems:
        print("paraview:", line)
    if problems:
        failures.append(f"{len(problems)} error or warning lines from {what}")
    if not os.path.isfile(result):
        print(proc.stdout)
        failures.append(f"{what}: its Python steps did not finish (no record)")
        return None
    with open(result) as f:
        return json.load(f)


def open_state(source, run_dir, plugin_dir, paraview, work, env, failures):
    """scripts/paraview-state on the run in the real GUI, with a --script
    that records the state at the last frame (gui_steps.py's "state")."""
    config = os.path.join(work, "state_config.json")
    result = os.path.join(work, "state.json")
    with open(config, "w") as f:
        json.dump({"result": result, "states": os.path.join(source, "states")}, f)
    # A test script of one event, the step in the Python shell (paraview
    # refuses --script beside --state).
    script = os.path.join(work, "state_events.xml")
    with open(script, "w") as f:
        f.write(events_of([shell_step(os.path.join(source, "tests", "gui_steps.py"), config,
                                      "state")]))
    # The wrapper puts the plugin in PV_PLUGIN_PATH itself.
    env = {k: v for k, v in env.items() if k != "PV_PLUGIN_PATH"}
    env.update(RUNOUT_PARAVIEW=paraview, RUNOUT_PLUGIN_DIR=plugin_dir)
    state = run_gui(XVFB[:-1] + ["-screen 0 1600x1000x24 -noreset", "timeout", "-k", "5", "120",
                                 os.path.join(source, "scripts", "paraview-state"), run_dir,
                                 os.path.join(source, "states", "strain_bands.pvsm"),
                                 "--test-script=" + script, "--dr"],
                    env, "scripts/paraview-state", result, failures)
    if state is not None:
        check_state(state, os.path.join(run_dir, "default.pvd"), failures)


def main():
    if sys.argv[1] == "--check":  # the checks alone, on a kept record
        failures = []
        with open(sys.argv[2]) as f:
            check_record(json.load(f), failures)
        fail(failures)
    source, cli, plugin_dir, paraview = [os.path.abspath(a) for a in sys.argv[1:5]]
    keep = sys.argv[5] if len(sys.argv) > 5 else None
    if not shutil.which("xvfb-run") or not paraview or not os.path.isfile(paraview):
        print("no xvfb-run or paraview: skipped")
        sys.exit(77)
    work = tempfile.mkdtemp(prefix="runout_gui_")
    try:
        run_dir = os.path.join(work, "run")
        subprocess.run([cli, "run", "--cell", "0.7", "--ppc", "2", "--end", "14", "--out",
                        run_dir, "-q"], check=True)
        folder = keep or os.path.join(work, "shots")
        os.makedirs(folder, exist_ok=True)
        config = os.path.join(work, "config.json")
        fbdir = os.path.join(work, "screen")
        os.makedirs(fbdir)
        # Kept with the screenshots, for --check.
        result = os.path.join(folder, "record.json")
        with open(config, "w") as f:
            json.dump({"folder": folder, "result": result, "fbdir": fbdir,
                       "states": os.path.join(source, "states")}, f)
        script = os.path.join(work, "events.xml")
        with open(script, "w") as f:
            f.write(events(os.path.join(source, "tests", "gui_steps.py"), config))
        # A HOME of its own: no settings or recent files of the user's.
        env = dict(os.environ, HOME=os.path.join(work, "home"), PV_PLUGIN_PATH=plugin_dir)
        os.makedirs(env["HOME"])
        # timeout inside xvfb-run: a hung GUI is killed, not left running.
        xvfb = XVFB[:-1] + [XVFB[-1].format(fbdir=fbdir)]
        failures = []
        record = run_gui(xvfb + ["timeout", "-k", "5", "200", paraview,
                                 "--data=" + os.path.join(run_dir, "default.pvd"),
                                 "--test-script=" + script, "--exit",
                                 # No settings: no Welcome dialog, which
                                 # would stop the event player.
                                 "--dr",
                                 # The screen's size (no window manager
                                 # to maximise it), for the pictures.
                                 "-geometry", "1600x1000+0+0"],
                         env, "paraview", result, failures)
        if record is None:
            fail(failures)
        check_record(record, failures)
        open_state(source, run_dir, plugin_dir, paraview, work, env, failures)
        fail(failures)
    finally:
        shutil.rmtree(work, ignore_errors=True)


main()
