"""Writes the ParaView state files of states/ from a run, so that they are
reproducible (states/README.md says how to open them on any run):

  strain_bands.pvsm   figure 3 of states/figures.py: the particles coloured
                      by plastic shear strain, the base, the shear band
                      skeletons (Runout Shear Bands, red) and the block
                      outlines (Runout Horsts And Grabens, black), heights
                      exaggerated 3 times, at the run's last frame; the
                      colours span the strain of the frame shown and the
                      camera follows the slide.

Usage (a coarse run of the default scene is enough; the run's folder is
replaced in the state by /path/to/run, which scripts/paraview-state and
states/load_state.py replace with the run they are given):
  build/engine/runout run --cell 1.0 --ppc 2 --end 10 --out /tmp/staterun -q
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \\
    pvbatch states/make_states.py /tmp/staterun [--plugin RunoutPlugin.so] [--out states]
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from paraview import simple  # noqa: E402

import figures  # noqa: E402
import runout_pv  # noqa: E402

PLACEHOLDER = "/path/to/run"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("run_dir")
    parser.add_argument("--plugin", default=figures.default_plugin())
    parser.add_argument("--out", default=HERE)
    options = parser.parse_args()
    run_dir = os.path.abspath(options.run_dir)

    runout_pv.load_plugin(options.plugin)
    # ParaView's own PVD reader: load_state.py points the state's
    # PVDReader at the run it is given.
    reader = runout_pv.open_run(runout_pv.find_pvd(run_dir), "PVDReader")
    runout_pv.set_time(reader.TimestepValues[-1])
    layout = simple.CreateLayout("strain bands")
    view = runout_pv.render_view()
    simple.AssignViewToLayout(view=view, layout=layout, hint=0)
    lut = figures.build_strain_bands(reader, view)[3]
    # The colours span the strain of the frame shown, whatever run the
    # state is opened on (the range saved is that of the run made from).
    lut.AutomaticRescaleRangeMode = "Clamp and update every timestep"
    layout.SetSize(1200, 600)
    simple.Render(view)
    runout_pv.fit_camera(view, reader.GetDataInformation().GetBounds())
    runout_pv.follow_slide(view, reader)
    simple.Render(view)

    path = os.path.join(options.out, "strain_bands.pvsm")
    simple.SaveState(path)
    with open(path) as f:
        text = f.read()
    with open(path, "w") as f:
        f.write(text.replace(run_dir, PLACEHOLDER))
    print(path)


main()
