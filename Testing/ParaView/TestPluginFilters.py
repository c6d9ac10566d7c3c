"""pvbatch: the filter proxies of the plug-in (Interval Subdivision, Spherical Cover).
- every property's XML default equals the C++ constructor's value (the wrapped class's getter);
- every property can be set to a non-default value and back;
- on the Cornell box the output ports carry the Documentation/Pipeline.md#interval-subdivision and #spherical-cover data: patches and
  characteristic points, whose areas add up to the surfaces' areas; cover points with their
  covered projected solid angles and the strip table;
- a bad property value makes the update fail without a crash (empty output)."""
import sys

from paraview import servermanager
from paraview.simple import LoadPlugin, OpenDataFile, OutputPort

plugin, data = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
from sphericalcover import (vtkIlluminationField, vtkIntervalSubdivisionFilter,  # noqa: E402
                            vtkPLightPropagationFilter, vtkPSphericalCoverFilter,
                            vtkRadianceImageFilter)

failures = []
scene = OpenDataFile(f"{data}/scenes/cornell_box.scene")
subdivision = globals()["IntervalSubdivision"](Input=scene)
cxx = vtkIntervalSubdivisionFilter()

BOOLEANS_AND_ENUMS = ("RangeMethod", "SelfShadowing", "HemisphericalContainment", "SphericalShape",
                      "Characterisability", "FillMethod", "BackFacesOcclude", "Refinement",
                      "ShootingOrder", "BalanceExchanges", "GatherRows", "GatherSolution")


def check_properties(proxy, native, names):
    """XML defaults equal the C++ defaults; each property can be changed and reset."""
    for name in names:
        prop = proxy.SMProxy.GetProperty(name)
        default = prop.GetElement(0)
        value = getattr(native, "Get" + name)()
        if float(default) != float(value):
            failures.append(f"{name}: XML default {default} != C++ default {value}")
        other = (1 - default) if name in BOOLEANS_AND_ENUMS else default * 2
        prop.SetElement(0, other)
        proxy.SMProxy.UpdateVTKObjects()
        if prop.GetElement(0) != other:
            failures.append(f"{name}: cannot be set to {other}")
        prop.SetElement(0, default)
        proxy.SMProxy.UpdateVTKObjects()


check_properties(subdivision, cxx, ["RangeMethod", "MaxLevel", "ThetaBins", "PhiBins", "SelfShadowing",
                 "SelfShadowingTolerance", "HemisphericalContainment",
                 "HemisphericalContainmentTolerance", "SphericalShape", "SphericalShapeTolerance",
                 "Characterisability", "CharacterisabilityTolerance"])

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

# The spherical cover of the (coarsely) subdivided box.
cover = globals()["SphericalCover"](Input=OutputPort(subdivision, 0))
check_properties(cover, vtkPSphericalCoverFilter(), ["ThetaBins", "PhiBins", "SamplesPerCell", "FillMethod",
                 "BackFacesOcclude", "GenerateStripTable", "GatherRows", "MemoryLimit", "Refinement",
                 "RefinementLevels"])
subdivision.MaxLevel = 1
# Without refinement one point per patch; with the default refinement the floor patches along
# the blocks' footprints (and the ceiling's around the light) are split, the area unchanged.
cover.Refinement = "Off"
cover.UpdatePipeline()
patch_count = subdivision.GetDataInformation(0).GetNumberOfCells()
unrefined = servermanager.Fetch(cover)
if unrefined.GetNumberOfPoints() != patch_count:
    failures.append("one cover point per patch expected without refinement")
cover.Refinement = "Enclosure Boundaries"
cover.UpdatePipeline()
cover_points = servermanager.Fetch(cover)
if cover_points.GetNumberOfPoints() <= patch_count:
    failures.append("the refinement split no patch along the blocks' footprints")


def area_sum(points):
    area = points.GetPointData().GetArray("Area")
    return sum(area.GetValue(k) for k in range(area.GetNumberOfTuples()))


if abs(area_sum(cover_points) / area_sum(unrefined) - 1) > 1e-9:
    failures.append("the refined patches' areas do not add up to the patches'")
for name in ["Normals", "Tangents", "Area", "PatchId", "SurfaceId", "CoveredProjectedSolidAngle",
             "VisibleSources", "MaterialId", "Diffuse", "Emission"]:
    if cover_points.GetPointData().GetArray(name) is None:
        failures.append(f"cover points lack {name}")
covered = cover_points.GetPointData().GetArray("CoveredProjectedSolidAngle")
values = [covered.GetValue(k) for k in range(covered.GetNumberOfTuples())]
areas = cover_points.GetPointData().GetArray("Area")
# The Cornell box is open at the front: no point sees more than pi; points on the floor under
# the blocks (a small share of the area, but many small pieces) see nothing, all others
# something.
seeing = sum(areas.GetValue(k) for k in range(len(values)) if values[k] > 0)
if max(values) > 3.14159265358979 + 1e-9 or seeing < 0.9 * area_sum(cover_points):
    failures.append(f"covered projected solid angles out of range: {min(values)}..{max(values)}")
if cover.GetDataInformation(1).GetNumberOfRows() == 0:
    failures.append("the strip table is empty")

# Light propagation over the cover: the Cornell box is all diffuse.
propagation = globals()["LightPropagation"](Input=OutputPort(cover, 0))
check_properties(propagation, vtkPLightPropagationFilter(), ["ConvergenceTolerance", "MaximumShots",
                 "ShootingOrder", "ShotBatch", "BalanceExchanges", "GatherSolution"])
propagation.UpdatePipeline()
lit = servermanager.Fetch(propagation)
for name in ["Irradiance", "Radiosity", "Brightness"]:
    if lit.GetPointData().GetArray(name) is None:
        failures.append(f"illumination lacks {name}")
if lit.GetFieldData().GetArray("IncidentRadiance") is None:
    failures.append("illumination lacks the incident radiance of the hemisphere regions")
if propagation.GetDataInformation(1).GetNumberOfRows() == 0:
    failures.append("the convergence history is empty")

# Rendering: the illumination and the patches through the scene's camera.
render = globals()["RadianceImage"](Input=OutputPort(propagation, 0),
                                    Patches=OutputPort(subdivision, 0))
native_render = vtkRadianceImageFilter()
check_properties(render, native_render, ["ViewAngle", "Width", "Height", "SamplesPerPixel",
                 "ExposureFactor", "MemoryLimit"])
for name in ["Position", "FocalPoint", "ViewUp"]:
    prop = render.SMProxy.GetProperty(name)
    xml_default = [prop.GetElement(k) for k in range(prop.GetNumberOfElements())]
    if xml_default != list(getattr(native_render, "Get" + name)()):
        failures.append(f"{name}: XML default {xml_default} != C++ default")
# CameraName: ParaView starts at the scene's first camera (its StringListDomain of the scene's
# cameras); the C++ default, empty, looks through the same camera.
if render.SMProxy.GetProperty("CameraName").GetElement(0) != "main" or \
        native_render.GetCameraName() != "":
    failures.append(f"CameraName: ParaView's default "
                    f"{render.SMProxy.GetProperty('CameraName').GetElement(0)!r} is not the "
                    f"scene's first camera 'main', or the C++ default "
                    f"{native_render.GetCameraName()!r} is not empty")
render.CameraName = "main"
render.Width = 32
render.Height = 24
render.SamplesPerPixel = 1
render.UpdatePipeline()
image = servermanager.Fetch(render)
if image.GetDimensions() != (32, 24, 1):
    failures.append(f"the image is {image.GetDimensions()}, not 32 x 24")
for name in ["Radiance", "Depth", "SurfaceId", "RGB"]:
    if image.GetPointData().GetArray(name) is None:
        failures.append(f"the image lacks {name}")
seen = image.GetPointData().GetArray("SurfaceId")
if seen is not None and max(seen.GetValue(k) for k in range(seen.GetNumberOfTuples())) < 0:
    failures.append("the Cornell box's camera sees nothing")

# The illumination field: every patch tessellated with the interpolated radiance.
lit_field = globals()["IlluminationField"](Input=OutputPort(propagation, 0),
                                           Patches=OutputPort(subdivision, 0))
check_properties(lit_field, vtkIlluminationField(), ["Resolution"])
lit_field.Resolution = 2
lit_field.UpdatePipeline()
field_info = lit_field.GetDataInformation(0)
if field_info.GetNumberOfCells() != 4 * subdivision.GetDataInformation(0).GetNumberOfCells():
    failures.append(f"the field has {field_info.GetNumberOfCells()} quads, not 4 per patch")
if "Radiance" not in lit_field.PointData.keys():
    failures.append("the field lacks Radiance")

bad = globals()["IntervalSubdivision"](Input=scene)
bad.SelfShadowingTolerance = -0.5  # -1 is the default: the scene's tolerance
bad.UpdatePipeline()
if bad.GetDataInformation(0).GetNumberOfCells() != 0:
    failures.append("a negative tolerance still produced patches")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
