"""What the headless ParaView tests of RunoutPlugin share (plugin_loads.py,
plugin_filters_on_run.py): their arguments, the skip without
paraview.simple, and the filters that the plugin's XML files define.
"""
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET


def runout_filters(xml_folder, group_name="filters"):
    """{proxy name: Python name} of every proxy of the group ("filters", or
    "sources" for the reader) in the XML files."""
    filters = {}
    for path in sorted(glob.glob(os.path.join(xml_folder, "*.xml"))):
        for group in ET.parse(path).getroot().iter("ProxyGroup"):
            if group.get("name") != group_name:
                continue
            for proxy in group.iter("SourceProxy"):
                # ParaView names the Python function after the label, keeping
                # only the characters valid in a Python name.
                label = proxy.get("label", proxy.get("name"))
                filters[proxy.get("name")] = re.sub(r"[^0-9A-Za-z_]", "", label)
    return filters


def paraview_and_arguments():
    """(servermanager, simple, plugin, xml_folder): paraview's modules and
    the script's arguments <RunoutPlugin.so> <folder of its XML files>.
    Exits 77 (ctest SKIP_RETURN_CODE) when paraview.simple is unavailable."""
    try:
        from paraview import servermanager, simple
    except ImportError as error:
        print(f"paraview.simple is not available ({error}): skipped")
        sys.exit(77)
    return servermanager, simple, sys.argv[1], sys.argv[2]
