"""RunoutPlugin in headless ParaView (pvpython or pvbatch): it loads, and
every filter that its server-manager XML files define is in the "Runout"
category of the loaded plugin, under the Python name ParaView gives it.

Usage: pvpython|pvbatch plugin_loads.py <RunoutPlugin.so> <folder of its XML files>
Exit code 77 (ctest SKIP_RETURN_CODE) when paraview.simple is unavailable.
"""
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET


def runout_filters(xml_folder):
    """{proxy name: Python name} of every filter proxy in the XML files."""
    filters = {}
    for path in sorted(glob.glob(os.path.join(xml_folder, "*.xml"))):
        for group in ET.parse(path).getroot().iter("ProxyGroup"):
            if group.get("name") != "filters":
                continue
            for proxy in group.iter("SourceProxy"):
                # ParaView names the Python function after the label, keeping
                # only the characters valid in a Python name.
                label = proxy.get("label", proxy.get("name"))
                filters[proxy.get("name")] = re.sub(r"[^0-9A-Za-z_]", "", label)
    return filters


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
    try:
        from paraview import servermanager, simple
    except ImportError as error:
        print(f"paraview.simple is not available ({error}): skipped")
        sys.exit(77)
    plugin, xml_folder = sys.argv[1], sys.argv[2]
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
