"""`import sphericalcover` from /usr/bin/python3 (ParaView's vtkmodules): the readers run in a
plain VTK pipeline and produce the Documentation/Pipeline.md#reader arrays; reader -> subdivision -> cover -> hemisphere
extractor runs and gives the Documentation/Pipeline.md#inspection-filters image and mesh."""
import sys

from sphericalcover import (vtkBPTReader, vtkHemisphereExtractor, vtkIntervalSubdivisionFilter,
                            vtkPatchSceneReader, vtkSphericalCoverFilter)
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData, vtkUnstructuredGrid

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

# The whole chain to one hemisphere: the furnace box is closed, so every cell has a source.
box = vtkPatchSceneReader()
box.SetFileName(f"{data}/scenes/furnace_box.scene")
subdivision = vtkIntervalSubdivisionFilter()
subdivision.SetInputConnection(box.GetOutputPort())
subdivision.SetMaxLevel(1)
cover = vtkSphericalCoverFilter()
cover.SetInputConnection(subdivision.GetOutputPort(0))
cover.SetThetaBins(8)
cover.SetPhiBins(24)
extractor = vtkHemisphereExtractor()
extractor.SetInputConnection(cover.GetOutputPort(0))
extractor.SetPointId(3)
extractor.Update()
image, mesh = extractor.GetImageOutput(), extractor.GetMeshOutput()
if not isinstance(image, vtkImageData) or image.GetDimensions() != (25, 9, 1):
    failures.append("hemisphere image: expected 24 x 8 cells")
else:
    source = image.GetCellData().GetArray("Source")
    if source is None or min(source.GetRange()) < 0:
        failures.append("hemisphere image: a cell of the closed furnace box has no source")
if not isinstance(mesh, vtkPolyData) or mesh.GetNumberOfCells() != 8 * 24:
    failures.append("hemisphere mesh: expected 192 cells")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
