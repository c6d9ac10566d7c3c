"""`import sphericalcover` from /usr/bin/python3 (ParaView's vtkmodules): the readers run in a
plain VTK pipeline and produce the SPEC §4.1 arrays."""
import sys

from sphericalcover import vtkBPTReader, vtkPatchSceneReader
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid

data = sys.argv[1]
failures = []

reader = vtkPatchSceneReader()
reader.SetFileName(f"{data}/scenes/teapot_room.scene")
reader.Update()
grid = reader.GetOutput()
if not isinstance(grid, vtkUnstructuredGrid) or grid.GetNumberOfCells() == 0:
    failures.append("teapot_room: no cells")
cd = grid.GetCellData()
for name, components in [("SurfaceId", 1), ("MaterialId", 1), ("Emission", 3), ("Diffuse", 3),
                         ("Specular", 3), ("PhongExponent", 1), ("HigherOrderDegrees", 3)]:
    array = cd.GetArray(name)
    if array is None or array.GetNumberOfComponents() != components:
        failures.append(f"teapot_room: cell array {name}")
names = grid.GetFieldData().GetAbstractArray("SurfaceNames")
if names is None or "teapot" not in [names.GetValue(k) for k in range(names.GetNumberOfValues())]:
    failures.append("teapot_room: SurfaceNames lacks 'teapot'")

bpt = vtkBPTReader()
bpt.SetFileName(f"{data}/models/teapot.bpt")
bpt.Update()
if bpt.GetOutput().GetNumberOfCells() != 32:
    failures.append("teapot.bpt: expected 32 patches")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
