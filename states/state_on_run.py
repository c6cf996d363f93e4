"""A state file of states/ pointed at a run: every reader of the state
(ParaView's PVD reader, the Runout Series Reader) reads the run's .pvd.

The shipped states name their run /path/to/run (make_states.py); ParaView
given one as it is looks for that folder and prints an error for every
filter and representation that cannot update (160 lines for
strain_bands.pvsm). scripts/paraview-state and load_state.py load the copy
this writes instead. Plain Python (no ParaView), so the wrapper can run it
with any python3:

  python3 states/state_on_run.py STATE.pvsm RUN_DIR OUT.pvsm
"""
import glob
import os
import sys
import xml.etree.ElementTree as ET

# The proxies of a state that read a run's index, by XML type.
READERS = ("PVDReader", "RunoutSeriesReader")


def find_pvd(run_dir):
    """The frame series <name>.pvd of a run's output folder."""
    found = sorted(glob.glob(os.path.join(run_dir, "*.pvd")))
    if not found:
        raise SystemExit(f"no .pvd in {run_dir}: not a run's output folder")
    return found[0]


def state_on_run(state, run_dir):
    """The state file's XML with each reader's FileName the run's .pvd
    (absolute); exits when the state has no reader to point."""
    pvd = os.path.abspath(find_pvd(run_dir))
    tree = ET.parse(state)
    pointed = 0
    for proxy in tree.getroot().iter("Proxy"):
        if proxy.get("group") != "sources" or proxy.get("type") not in READERS:
            continue
        for prop in proxy.iter("Property"):
            if prop.get("name") == "FileName":
                for element in prop.iter("Element"):
                    element.set("value", pvd)
                    pointed += 1
    if not pointed:
        raise SystemExit(f"{state}: no reader of a .pvd to point at {pvd}")
    return ET.tostring(tree.getroot(), encoding="unicode")


def write_state_on_run(state, run_dir, out):
    """Writes state_on_run(state, run_dir) to out; returns out."""
    with open(out, "w") as f:
        f.write('<?xml version="1.0"?>\n' + state_on_run(state, run_dir))
    return out


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__.strip().splitlines()[-1].strip())
    write_state_on_run(*sys.argv[1:4])
