"""RunoutPlugin in headless ParaView (pvpython or pvbatch): it loads, and
every filter and reader that its server-manager XML files define is in the
"Runout" category of the Filters or Sources menu, under the Python name
ParaView gives it, which is its XML name (the name state files and
ParaView's messages use) and the one docs/filters.md shows, with a menu
icon that is a 32 x 32 PNG of RunoutIcons.qrc. With
RUNOUT_PLUGIN_ICONS=ON (the build found Qt's rcc) the plugin must hold
each icon (its bytes and its name, which rcc stores as UTF-16): the GUI
looks the icon up there, and one missing shows as no icon, silently.

Usage: pvpython|pvbatch plugin_loads.py <RunoutPlugin.so> <folder of its XML files>
Exit code 77 (ctest SKIP_RETURN_CODE) when paraview.simple is unavailable.
"""
import os
import struct
import sys
import xml.etree.ElementTree as ET

# The shared helpers lie beside this script, wherever it is run from.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from runout_paraview import paraview_and_arguments, runout_filters  # noqa: E402


def loaded_runout_category(servermanager, group):
    """{name: menu icon} of the loaded proxies of the group ("filters" or
    "sources") shown in its menu's Runout category."""
    definitions = servermanager.ProxyManager().GetProxyDefinitionManager()
    it = definitions.NewSingleGroupIterator(group)
    names = {}
    it.GoToFirstItem()
    while not it.IsDoneWithTraversal():
        hints = it.GetProxyHints()
        menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
        if menu is not None and menu.GetAttribute("category") == "Runout":
            names[it.GetProxyName()] = menu.GetAttribute("icon")
        it.GoToNextItem()
    return names


def icon_problems(icons, plugin, xml_folder):
    """What is wrong with the filters' menu icons ({proxy: ":/prefix/alias"})."""
    qrc = ET.parse(os.path.join(xml_folder, "RunoutIcons.qrc")).getroot()
    files = {f"{r.get('prefix')}/{f.get('alias')}": f.text for r in qrc.iter("qresource")
             for f in r.iter("file")}
    with open(plugin, "rb") as f:
        binary = f.read()
    built_in = os.environ.get("RUNOUT_PLUGIN_ICONS") == "ON"
    problems = []
    for proxy, icon in sorted(icons.items()):
        path = files.get((icon or "")[len(":"):])
        if path is None:
            problems.append(f"{proxy}: icon {icon!r} is not in RunoutIcons.qrc")
            continue
        with open(os.path.join(xml_folder, path), "rb") as f:
            png = f.read()
        if png[:8] != b"\x89PNG\r\n\x1a\n" or struct.unpack(">II", png[16:24]) != (32, 32):
            problems.append(f"{proxy}: {path} is not a 32 x 32 PNG")
        name = os.path.basename(icon).encode("utf-16-be")
        if built_in and (png not in binary or name not in binary):
            problems.append(f"{proxy}: {icon} is not compiled into {plugin}")
    return problems


def name_problems(expected, xml_folder):
    """One name per filter: a state file and ParaView's messages name a
    proxy by its XML name, Python by its label, so the two must be the
    same, and docs/filters.md must show it ({XML name: Python name})."""
    docs = os.path.join(xml_folder, os.pardir, os.pardir, "docs", "filters.md")
    with open(docs) as f:
        text = f.read()
    problems = []
    for proxy, python in sorted(expected.items()):
        if proxy != python:
            problems.append(f"{proxy}: its Python name is {python}; state files and "
                            f"ParaView's messages say {proxy}")
        if f"`{python}`" not in text:
            problems.append(f"{python}: docs/filters.md does not show this Python name")
    return problems


def main():
    servermanager, simple, plugin, xml_folder = paraview_and_arguments()
    expected = {group: runout_filters(xml_folder, group) for group in ("filters", "sources")}
    if not all(expected.values()):
        sys.exit(f"no filter or no reader proxies in {xml_folder}/*.xml")

    simple.LoadPlugin(plugin, remote=False)  # adds the filters' functions to simple
    for group, proxies in expected.items():
        category = loaded_runout_category(servermanager, group)
        if set(category) != set(proxies):
            sys.exit(f"Runout category of {group} {sorted(category)}, "
                     f"the XML files define {sorted(proxies)}")
        problems = icon_problems(category, plugin, xml_folder)
        if problems:
            sys.exit("\n".join(problems))
    expected = {**expected["filters"], **expected["sources"]}
    missing = [name for name in expected.values() if not hasattr(simple, name)]
    if missing:
        sys.exit(f"{plugin} loaded, but without the Python functions {missing}")
    problems = name_problems(expected, xml_folder)
    if problems:
        sys.exit("\n".join(problems))
    print("RunoutPlugin OK:", ", ".join(sorted(expected.values())))


if __name__ == "__main__":
    main()
