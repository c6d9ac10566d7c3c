"""pvbatch: the Interval Subdivision proxy of the plug-in.
- every property's XML default equals the C++ constructor's value (the wrapped class's getter);
- every property can be set to a non-default value and back;
- on the Cornell box the two output ports carry the patches and the characteristic points with
  the SPEC §4.2 arrays, and the patches' areas add up to the surfaces' areas;
- a bad property value makes the update fail without a crash (empty output)."""
import sys

from paraview import servermanager
from paraview.simple import LoadPlugin, OpenDataFile, UpdatePipeline

plugin, data = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
from sphericalcover import vtkIntervalSubdivisionFilter  # noqa: E402

failures = []
scene = OpenDataFile(f"{data}/scenes/cornell_box.scene")
subdivision = globals()["IntervalSubdivision"](Input=scene)
cxx = vtkIntervalSubdivisionFilter()

properties = ["RangeMethod", "MaxLevel", "ThetaBins", "PhiBins", "SelfShadowing",
              "SelfShadowingTolerance", "HemisphericalContainment",
              "HemisphericalContainmentTolerance", "SphericalShape", "SphericalShapeTolerance",
              "Characterisability", "CharacterisabilityTolerance"]
for name in properties:
    prop = subdivision.SMProxy.GetProperty(name)
    default = prop.GetElement(0)
    native = getattr(cxx, "Get" + name)()
    if float(default) != float(native):
        failures.append(f"{name}: XML default {default} != C++ default {native}")
    other = (1 - default) if name in ("RangeMethod", "SelfShadowing", "HemisphericalContainment",
                                      "SphericalShape", "Characterisability") else default * 2
    prop.SetElement(0, other)
    subdivision.SMProxy.UpdateVTKObjects()
    if prop.GetElement(0) != other:
        failures.append(f"{name}: cannot be set to {other}")
    prop.SetElement(0, default)
    subdivision.SMProxy.UpdateVTKObjects()

subdivision.MaxLevel = 2
subdivision.UpdatePipeline()
patches = servermanager.Fetch(subdivision)
points_info = subdivision.GetDataInformation(1)
patch_info = subdivision.GetDataInformation(0)
cells = patch_info.GetNumberOfCells()
if cells <= 16:
    failures.append(f"the Cornell box was not subdivided ({cells} patches)")
if points_info.GetNumberOfPoints() != cells:
    failures.append(f"{points_info.GetNumberOfPoints()} characteristic points for {cells} patches")
cell_arrays = set(subdivision.CellData.keys())
for name in ["SurfaceId", "PatchId", "Level", "UVRange", "Area", "SplitReason", "MaterialId",
             "Diffuse", "Emission"]:
    if name not in cell_arrays:
        failures.append(f"patches lack {name}")
point_data = points_info.GetPointDataInformation()
point_arrays = {point_data.GetArrayInformation(k).GetName() for k in range(point_data.GetNumberOfArrays())}
for name in ["Normals", "PatchId", "SurfaceId", "UV", "Area"]:
    if name not in point_arrays:
        failures.append(f"characteristic points lack {name}")

# Areas: the patches add up to the surfaces' areas, as VTK's own cell-size filter measures them.
area = patches.GetCellData().GetArray("Area")
total = sum(area.GetValue(k) for k in range(patches.GetNumberOfCells()))
reader_output = servermanager.Fetch(scene)
from vtkmodules.vtkFiltersVerdict import vtkCellSizeFilter  # noqa: E402
sizes = vtkCellSizeFilter()
sizes.SetInputData(reader_output)
sizes.ComputeAreaOn()
sizes.Update()
reader_area = sizes.GetOutput().GetCellData().GetArray("Area")
expected = sum(reader_area.GetValue(k) for k in range(reader_output.GetNumberOfCells()))
if abs(total / expected - 1) > 1e-6:
    failures.append(f"patch areas add up to {total}, the surfaces' to {expected}")

bad = globals()["IntervalSubdivision"](Input=scene)
bad.SelfShadowingTolerance = -1
bad.UpdatePipeline()
if bad.GetDataInformation(0).GetNumberOfCells() != 0:
    failures.append("a negative tolerance still produced patches")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
