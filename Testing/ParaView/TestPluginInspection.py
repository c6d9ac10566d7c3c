"""pvbatch: the inspection proxy of the plug-in (Hemisphere Extractor, Documentation/Pipeline.md#inspection-filters).
- every property's XML default equals the C++ constructor's value;
- on the closed furnace box the "Hemisphere Image" port is a vtkImageData of PhiBins x ThetaBins
  cells in which every cell has a source, and the "Hemisphere Mesh" port has one cell per cell;
- a PointId out of range makes the update fail without a crash (empty output)."""
import sys

from paraview import servermanager
from paraview.simple import LoadPlugin, OpenDataFile, OutputPort

plugin, data = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
from sphericalcover import vtkHemisphereExtractor  # noqa: E402

failures = []
scene = OpenDataFile(f"{data}/scenes/furnace_box.scene")
subdivision = globals()["IntervalSubdivision"](Input=scene)
subdivision.MaxLevel = 1
cover = globals()["SphericalCover"](Input=OutputPort(subdivision, 0))
cover.ThetaBins = 8
cover.PhiBins = 24
extractor = globals()["HemisphereExtractor"](Input=OutputPort(cover, 0))

native = vtkHemisphereExtractor()
for name in ["PointId", "Radius"]:
    default = extractor.SMProxy.GetProperty(name).GetElement(0)
    value = getattr(native, "Get" + name)()
    if float(default) != float(value):
        failures.append(f"{name}: XML default {default} != C++ default {value}")

extractor.PointId = 2
extractor.UpdatePipeline()
image_info = extractor.GetDataInformation(0)
if image_info.GetDataClassName() != "vtkImageData" or image_info.GetNumberOfCells() != 8 * 24:
    failures.append(f"Hemisphere Image: {image_info.GetDataClassName()} of "
                    f"{image_info.GetNumberOfCells()} cells, expected vtkImageData of 192")
source = image_info.GetCellDataInformation().GetArrayInformation("Source")
if source is None or source.GetComponentRange(0)[0] < 0:
    failures.append("Hemisphere Image: a cell of the closed furnace box has no source")
mesh_info = extractor.GetDataInformation(1)
if mesh_info.GetDataClassName() != "vtkPolyData" or mesh_info.GetNumberOfCells() != 8 * 24:
    failures.append(f"Hemisphere Mesh: {mesh_info.GetNumberOfCells()} cells, expected 192")

extractor.PointId = 10000
extractor.UpdatePipeline()
if extractor.GetDataInformation(1).GetNumberOfCells() != 0:
    failures.append("a PointId out of range still produced a mesh")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
