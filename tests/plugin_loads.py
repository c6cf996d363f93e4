"""RunoutPlugin in headless ParaView: load it, apply Runout Distance to a
small frame, fetch the table.

Usage: pvpython plugin_loads.py <path to RunoutPlugin.so>
Exit code 77 (ctest SKIP_RETURN_CODE) when paraview.simple is unavailable.
"""
import os
import sys
import tempfile

try:
    from paraview import servermanager, simple
    from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
    from vtkmodules.vtkCommonDataModel import VTK_VERTEX, vtkUnstructuredGrid
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter
except ImportError as error:
    print(f"paraview.simple is not available ({error}): skipped")
    sys.exit(77)


def write_frame(path, time, x, x0):
    grid = vtkUnstructuredGrid()
    time_value = vtkDoubleArray()
    time_value.SetName("TimeValue")
    time_value.InsertNextValue(time)
    grid.GetFieldData().AddArray(time_value)
    points = vtkPoints()
    initial = vtkDoubleArray()
    initial.SetName("initial_position")
    initial.SetNumberOfComponents(3)
    for xi, x0i in zip(x, x0):
        points.InsertNextPoint(xi, 0.0, 0.0)
        initial.InsertNextTuple3(x0i, 0.0, 0.0)
    grid.SetPoints(points)
    for i in range(len(x)):
        grid.InsertNextCell(VTK_VERTEX, 1, [i])
    grid.GetPointData().AddArray(initial)
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetInputData(grid)
    writer.SetFileName(path)
    writer.SetDataModeToBinary()  # inline: never appended (expat trap)
    if not writer.Write():
        sys.exit(f"cannot write {path}")


def main():
    plugin = sys.argv[1]
    simple.LoadPlugin(plugin, remote=False, ns=globals())
    if "RunoutDistance" not in globals():
        sys.exit(f"{plugin} loaded, but no RunoutDistance filter")

    with tempfile.TemporaryDirectory() as folder:
        frame = os.path.join(folder, "frame_00000.vtu")
        write_frame(frame, 2.5, [1.0, 4.0, -2.0], [0.0, 3.0, -2.0])
        reader = simple.XMLUnstructuredGridReader(FileName=[frame])
        distance = RunoutDistance(Input=reader)  # noqa: F821 (from LoadPlugin)
        if distance.GetXMLName() != "RunoutRunoutDistance":
            sys.exit(f"unexpected proxy {distance.GetXMLName()}")
        distance.UpdatePipeline()
        table = servermanager.Fetch(distance)
        row = {table.GetColumnName(c): table.GetValue(0, c).ToDouble()
               for c in range(table.GetNumberOfColumns())}
    expected = {"time": 2.5, "toe_x": 4.0, "rear_x": -2.0, "length": 6.0, "runout": 1.0}
    if table.GetNumberOfRows() != 1 or any(row.get(k) != v for k, v in expected.items()):
        sys.exit(f"unexpected table {row}")
    print("RunoutPlugin OK:", row)


main()
