"""RunoutPlugin in headless ParaView (pvpython or pvbatch): it loads, and
every filter that its server-manager XML files define is in the "Runout"
category of the loaded plugin, under the Python name ParaView gives it.

Usage: pvpython|pvbatch plugin_loads.py <RunoutPlugin.so> <folder of its XML files>
Exit code 77 (ctest SKIP_RETURN_CODE) when paraview.simple is unavailable.
"""
import os
import sys

# The shared helpers lie beside this script, wherever it is run from.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from runout_paraview import paraview_and_arguments, runout_filters  # noqa: E402


def loaded_runout_category(servermanager):
    """Names of the loaded filter proxies shown in the Runout menu."""
    definitions = servermanager.ProxyManager().GetProxyDefinitionManager()
    it = definitions.NewSingleGroupIterator("filters")
    names = set()
    it.GoToFirstItem()
    while not it.IsDoneWithTraversal():
        hints = it.GetProxyHints()
        menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
        if menu is not None and menu.GetAttribute("category") == "Runout":
            names.add(it.GetProxyName())
        it.GoToNextItem()
    return names


def main():
    servermanager, simple, plugin, xml_folder = paraview_and_arguments()
    expected = runout_filters(xml_folder)
    if not expected:
        sys.exit(f"no filter proxies in {xml_folder}/*.xml")

    simple.LoadPlugin(plugin, remote=False)  # adds the filters' functions to simple
    category = loaded_runout_category(servermanager)
    if category != set(expected):
        sys.exit(f"Runout category {sorted(category)}, the XML files define {sorted(expected)}")
    missing = [name for name in expected.values() if not hasattr(simple, name)]
    if missing:
        sys.exit(f"{plugin} loaded, but without the Python functions {missing}")
    print("RunoutPlugin OK:", ", ".join(sorted(expected.values())))


if __name__ == "__main__":
    main()
