"""Every Runout filter in headless pvpython on the output of a coarse engine
run: a Tresca block sliding on a planar frictional slope, a few seconds of
runtime. Loads the plugin, opens the run's .pvd, applies each filter that
the plugin's XML files define with its default settings, updates every
output port on the last frame, and checks the morphology filters' values;
then opens the run again with the Runout Series Reader (frames checked
against the manifest) and checks that it gives the same history, that a
time asked is the frame shown even where the index stores it with a
rounding error, and that made without a file it waits for one quietly.
On every frame, a Runout Morphology column named after grabens must count
what Runout Horsts And Grabens calls grabens.
ctest fails the test on any "ERROR:" a filter prints.

Usage: pvpython plugin_filters_on_run.py <RunoutPlugin.so> <folder of its XML files>
The engine is $RUNOUT_CLI. Exit code 77 (ctest SKIP_RETURN_CODE) when
paraview.simple is unavailable.
"""
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

# The shared helpers lie beside this script, wherever it is run from.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from runout_paraview import paraview_and_arguments, runout_filters  # noqa: E402

SCENE = """
[scene]
name = "plugin_run"

[grid]
cell_size = 0.5
min = [-2.0, 0.0]
max = [60.0, 6.0]

[base]
kind = "planar"
interface = "frictional"
shear_strength = 500.0

[time]
end = 3.0
output_interval = 0.5

[gravity]
slope_angle = 5.0

[[material]]
name = "clay"
model = "tresca"
density = 600.0
youngs_modulus = 250000.0
poisson_ratio = 0.49
su0 = 2500.0

[[body]]
name = "slide"
material = "clay"
type = "trapezoid"
base_start = [0.0, 0.0]
base_length = 20.0
height = 2.0
rear_angle = 30.0
front_angle = 30.0
"""


def fail(message):
    sys.exit(f"FAILED: {message}")


def run_engine(folder):
    """Runs the scene coarse; returns the path of its .pvd."""
    scene = os.path.join(folder, "scene.toml")
    with open(scene, "w") as f:
        f.write(SCENE)
    out = os.path.join(folder, "out")
    subprocess.run([os.environ["RUNOUT_CLI"], "run", scene, "--cell", "0.5", "--ppc", "2",
                    "-o", out, "-q"], check=True)
    return os.path.join(out, "plugin_run.pvd")


def columns(table):
    """{column name: list of values} of a vtkTable."""
    return {table.GetColumnName(c): [table.GetValue(r, c) for r in range(table.GetNumberOfRows())]
            for c in range(table.GetNumberOfColumns())}


def check_array_defaults(simple, reader):
    expected = {"RunoutPlasticStrain": {"StrainArray": "plastic_shear_strain"},
                "RunoutShearBands": {"StrainArray": "plastic_shear_strain"},
                "RunoutHorstsAndGrabens": {"StrainArray": "plastic_shear_strain",
                                           "DisplacementArray": "displacement"},
                "RunoutMorphology": {"VelocityArray": "velocity", "MassArray": "mass",
                                     "InitialPositionArray": "initial_position"},
                "RunoutMorphologyHistory": {"VelocityArray": "velocity", "MassArray": "mass",
                                            "InitialPositionArray": "initial_position"}}
    for function, properties in expected.items():
        f = getattr(simple, function)(Input=reader)
        for name, array in properties.items():
            value = list(f.GetPropertyValue(name))
            if value != ["POINTS", array]:
                fail(f"{function}.{name} is {value} before the reader ran, not {array}")
        simple.Delete(f)
    print("array selections default to the engine's arrays before the reader runs")


def check_history(servermanager, history, times):
    history.UpdatePipeline()
    table = servermanager.Fetch(history)
    if table.GetNumberOfRows() != len(times):
        fail(f"history has {table.GetNumberOfRows()} rows for {len(times)} frames")
    c = columns(table)
    time = [v.ToDouble() for v in c["Time"]]
    toe = [v.ToDouble() for v in c["toe"]]
    runout = [v.ToDouble() for v in c["runout"]]
    if time != list(times):
        fail(f"history times {time}, the series' {list(times)}")
    if runout[0] != 0.0:
        fail(f"runout of the first frame {runout[0]}")
    if any(r < 0.0 for r in runout):
        fail(f"negative runout {runout}")
    if any(b < a for a, b in zip(toe, toe[1:])) or not toe[-1] > toe[0]:
        fail(f"the toe does not advance: {toe}")
    # Port 1, the chart's: the lengths alone, with their unit in the name.
    lengths = columns(servermanager.Fetch(history, idx=1))
    if sorted(lengths) != sorted(["Time", "toe (m)", "rear (m)", "runout (m)", "length (m)",
                                  "max_thickness (m)"]):
        fail(f"history port 1 columns {sorted(lengths)}")
    if [v.ToDouble() for v in lengths["toe (m)"]] != toe:
        fail("history port 1's toe differs from port 0's")
    print("history:", ", ".join(f"t={t:g} toe={x:.3f}" for t, x in zip(time, toe)))
    return runout


def check_morphology(servermanager, morphology, time, runout):
    morphology.UpdatePipeline(time)
    table = servermanager.Fetch(morphology, idx=1)
    profile = servermanager.Fetch(morphology, idx=0)
    if table.GetNumberOfRows() != 1:
        fail(f"morphology table has {table.GetNumberOfRows()} rows")
    c = columns(table)
    if c["Time"][0].ToDouble() != time or c["runout"][0].ToDouble() != runout:
        fail(f"morphology at t={time}: {c['Time'][0]}, runout {c['runout'][0]} (history {runout})")
    mechanism = c["mechanism"][0].ToString()
    if mechanism not in ("undetermined", "block sliding", "elongation", "spreading"):
        fail(f"mechanism {mechanism!r}")
    thickness = profile.GetPointData().GetArray("thickness")
    if profile.GetNumberOfPoints() == 0 or thickness is None:
        fail("empty profile")
    top = max(thickness.GetValue(k) for k in range(thickness.GetNumberOfTuples()))
    if not math.isclose(top, c["max_thickness"][0].ToDouble(), rel_tol=1e-12):
        fail(f"profile's largest thickness {top}, table's {c['max_thickness'][0]}")
    print(f"morphology at t={time:g}: runout {runout:.3f}, {mechanism}, "
          f"{profile.GetNumberOfPoints()} profile bins")


def check_grabens(servermanager, morphology, blocks, times):
    """One meaning of "graben": a column of Runout Morphology's table
    named after grabens counts the blocks Runout Horsts And Grabens types
    graben (type_code 2) in the same frame."""
    named = 0
    for time in times:
        morphology.UpdatePipeline(time)
        blocks.UpdatePipeline(time)
        table = columns(servermanager.Fetch(morphology, idx=1))
        codes = columns(servermanager.Fetch(blocks, idx=1)).get("type_code", [])
        grabens = sum(1 for code in codes if code.ToInt() == 2)
        for name, values in table.items():
            if "graben" in name and not name.startswith("initial"):
                named += 1
                if values[0].ToInt() != grabens:
                    fail(f"at t={time:g} Runout Morphology's {name} is {values[0]}, Runout "
                         f"Horsts And Grabens types {grabens} blocks graben")
    print(f"grabens: {named} Morphology counts named so, each equal to the typed blocks")


def check_reader_waits(simple):
    """The reader as Sources > Runout Series Reader makes it, before a file
    is picked: no time steps, and no error (ctest fails on one)."""
    reader = simple.RunoutSeriesReader()
    reader.UpdatePipelineInformation()
    if len(reader.TimestepValues):
        fail(f"a Runout Series Reader without a file offers times {reader.TimestepValues}")
    simple.Delete(reader)
    print("Runout Series Reader without a file: no times, no error")


def check_times_asked(simple, pvd, times):
    """The time asked is the frame shown: an index whose times carry the
    rounding error of a sum of steps (27.700000000000003 for 27.7), written
    beside the run's with its manifest, gives frame k at the time printed
    with 12 digits."""
    folder = os.path.dirname(pvd)
    nudged = os.path.join(folder, "nudged.pvd")
    with open(pvd) as f:
        text = f.read()
    text = re.sub(r'timestep="([^"]+)"',
                  lambda m: f'timestep="{float(m.group(1)) * (1 + 4e-16)!r}"', text)
    with open(nudged, "w") as f:
        f.write(text)
    shutil.copy(pvd + ".manifest", nudged + ".manifest")
    reader = simple.RunoutSeriesReader(FileName=nudged)
    reader.UpdatePipelineInformation()
    stored = list(reader.TimestepValues)
    if stored[1:] == list(times[1:]):
        fail(f"the nudged index {nudged} lists the run's times exactly: nothing to check")
    for k, time in enumerate(stored):
        asked = float(f"{time:.12g}")
        reader.UpdatePipeline(asked)
        shown = reader.GetDataInformation().DataInformation.GetTime()
        if shown != time:
            fail(f"asked t={asked!r}, the reader shows the frame at {shown!r}, not {time!r}")
    simple.Delete(reader)
    print(f"times asked: each of {len(stored)} frames shown at its rounded time")


def main():
    servermanager, simple, plugin, xml_folder = paraview_and_arguments()
    with tempfile.TemporaryDirectory() as folder:
        pvd = run_engine(folder)
        simple.LoadPlugin(plugin, remote=False)
        reader = simple.PVDReader(FileName=pvd)
        # The array selectors keep the engine's array names as their
        # defaults even on a reader that has not run yet (they came out as
        # '0' when the domain, still empty, reset them).
        check_array_defaults(simple, reader)
        reader.UpdatePipeline()
        times = reader.TimestepValues
        if len(times) < 3:
            fail(f"the run wrote {len(times)} frames")

        filters = {}
        for proxy_name, function in sorted(runout_filters(xml_folder).items()):
            if not hasattr(simple, function):
                fail(f"no filter {function} after loading {plugin}")
            f = getattr(simple, function)(Input=reader)
            f.UpdatePipeline(times[-1])
            for port in range(f.SMProxy.GetNumberOfOutputPorts()):
                if servermanager.Fetch(f, idx=port) is None:
                    fail(f"{function} gave no output on port {port}")
            filters[proxy_name] = f
            print(f"{function}: {f.SMProxy.GetNumberOfOutputPorts()} output port(s) updated")

        runout = check_history(servermanager, filters["RunoutMorphologyHistory"], times)
        for k in (0, len(times) - 1):
            check_morphology(servermanager, filters["RunoutMorphology"], times[k], runout[k])

        # The Runout Series Reader, which checks each frame against the
        # run's manifest, gives the same series and the same history.
        series = simple.RunoutSeriesReader(FileName=pvd)
        series.UpdatePipeline()
        if list(series.TimestepValues) != list(times):
            fail(f"Runout Series Reader times {list(series.TimestepValues)}, PVD reader {list(times)}")
        history = simple.RunoutMorphologyHistory(Input=series)
        if check_history(servermanager, history, times) != runout:
            fail("the history through the Runout Series Reader differs from the PVD reader's")
        print("Runout Series Reader: the same", len(times), "frames and history")
        check_times_asked(simple, pvd, times)
        check_reader_waits(simple)
        check_grabens(servermanager, filters["RunoutMorphology"],
                      filters["RunoutHorstsAndGrabens"], times)
    print("all Runout filters ran on", len(times), "frames")


if __name__ == "__main__":
    main()
