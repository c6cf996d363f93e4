"""Loads a state file of states/ on a run's output folder, checks that
the Runout filters are in it (LoadState drops a filter of a plugin that is
not loaded, with only a warning), and optionally renders it.

Usage:
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \\
    pvbatch states/load_state.py STATE.pvsm RUN_DIR [--plugin RunoutPlugin.so] \\
    [--png OUT.png] [--size WxH] [--time T]
Exits 1 when a filter the state file names is missing once loaded.
"""
import argparse
import os
import re
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from paraview import simple  # noqa: E402

import figures  # noqa: E402
import runout_pv  # noqa: E402
from state_on_run import write_state_on_run  # noqa: E402


def state_filters(state):
    """The Runout proxies (group filters) a state file holds, by XML name."""
    with open(state) as f:
        return sorted(set(re.findall(r'<Proxy group="filters" type="(Runout\w+)"', f.read())))


def load(state, run_dir, plugin):
    """LoadState of the state with its reader pointed at the run's .pvd,
    whatever its name (the copy scripts/paraview-state opens in the GUI)."""
    try:
        runout_pv.load_plugin(plugin)
    except RuntimeError:
        pass  # reported below
    if not hasattr(simple, "RunoutShearBands"):
        # ParaView's state loader would print two errors per Runout proxy
        # and drop them: one line instead.
        sys.exit(f"ERROR: the Runout plugin is not loaded ({plugin}): not loading {state}")
    with tempfile.TemporaryDirectory() as folder:
        simple.LoadState(write_state_on_run(state, run_dir,
                                            os.path.join(folder, os.path.basename(state))))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("state")
    parser.add_argument("run_dir")
    parser.add_argument("--plugin", default=figures.default_plugin())
    parser.add_argument("--png")
    parser.add_argument("--size", default="1200x600")
    parser.add_argument("--time", type=float)
    options = parser.parse_args()

    expected = state_filters(options.state)
    load(options.state, options.run_dir, options.plugin)
    loaded = sorted(set(p.GetXMLName() for p in simple.GetSources().values()
                        if p.GetXMLName().startswith("Runout")))
    print("state filters:", expected, "loaded:", loaded)
    reader = simple.FindSource("run")
    print("run:", reader.FileName)
    if not expected or loaded != expected:
        print(f"ERROR: {options.state}: filters {expected} in the file, {loaded} once loaded")
        sys.exit(1)
    if options.png:
        scene = simple.GetAnimationScene()
        scene.UpdateAnimationUsingDataTimeSteps()
        scene.AnimationTime = (options.time if options.time is not None
                               else reader.TimestepValues[-1])
        size = [int(v) for v in options.size.lower().split("x")]
        layout = simple.GetLayouts().values().__iter__().__next__()
        layout.SetSize(*size)
        view = simple.GetViews()[0] if isinstance(simple.GetViews(), list) else None
        simple.Render(view)
        runout_pv.fit_camera(view, reader.GetDataInformation().GetBounds())
        simple.SaveScreenshot(options.png, layout, ImageResolution=size, CompressionLevel="9")
        print(options.png)


main()
