"""Run by pvpython (tests/app/paraview_test.py): opens an XDMF sidecar with
ParaView's default reader, as `File > Open` would, and prints what it sees as
JSON on the last line: the reader's class, the time steps, and per step the
point count, the last step's points and point arrays.

Usage: pvpython --force-offscreen-rendering paraview_reader.py FILE.xdmf [READER]
READER: "default" (OpenDataFile picks it) or a reader's proxy name (XDMFReader)."""
import json
import sys

from paraview import servermanager
from paraview.simple import OpenDataFile, XDMFReader
from vtk.util.numpy_support import vtk_to_numpy

path = sys.argv[1]
which = sys.argv[2] if len(sys.argv) > 2 else "default"
reader = OpenDataFile(path) if which == "default" else XDMFReader(FileNames=[path])
steps = list(reader.TimestepValues)
points_per_step = []
for t in steps:
    reader.UpdatePipeline(t)
    points_per_step.append(servermanager.Fetch(reader).GetNumberOfPoints())
reader.UpdatePipeline(steps[-1])
data = servermanager.Fetch(reader)
arrays = {}
point_data = data.GetPointData()
for i in range(point_data.GetNumberOfArrays()):
    array = point_data.GetArray(i)
    arrays[point_data.GetArrayName(i)] = vtk_to_numpy(array).tolist()
print(json.dumps({
    "reader": reader.GetXMLName(),
    "steps": steps,
    "points_per_step": points_per_step,
    "last_points": vtk_to_numpy(data.GetPoints().GetData()).tolist(),
    "arrays": arrays,
}))
