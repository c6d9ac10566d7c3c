"""pvbatch: the plug-in loads, its readers open the shipped scenes by extension and by name,
and the output has the cells and named arrays of SPEC §4.1. A malformed scene gives an empty
output instead of a crash."""
import sys

from paraview.simple import LoadPlugin, OpenDataFile

plugin, data, test_data = sys.argv[1:4]
# The plug-in's proxies (PatchSceneReader, BPTReader) are added to this namespace.
LoadPlugin(plugin, remote=False, ns=globals())
failures = []

expected_arrays = {"SurfaceId", "SurfaceNameId", "MaterialId", "MaterialType", "Emission",
                   "Diffuse", "Specular", "PhongExponent", "TwoSided"}


def check(source, what, cells):
    source.UpdatePipeline()
    info = source.GetDataInformation()
    if info.GetNumberOfCells() != cells:
        failures.append(f"{what}: {info.GetNumberOfCells()} cells, expected {cells}")
    missing = expected_arrays - set(source.CellData.keys())
    if missing:
        failures.append(f"{what}: missing cell arrays {sorted(missing)}")


# By extension (the reader factory) and by proxy name.
check(OpenDataFile(f"{data}/scenes/cornell_box.scene"), "cornell_box.scene (factory)", 16)
check(globals()["PatchSceneReader"](FileName=f"{data}/scenes/teapot_room.scene"), "teapot_room.scene", 39)
check(OpenDataFile(f"{data}/models/teapot.bpt"), "teapot.bpt (factory)", 32)
check(globals()["BPTReader"](FileName=f"{data}/models/geonum2017/sphere.bpt"), "sphere.bpt", 8)

bad = globals()["PatchSceneReader"](FileName=f"{test_data}/bad/unknown_material.scene")
bad.UpdatePipeline()
if bad.GetDataInformation().GetNumberOfCells() != 0:
    failures.append("a malformed scene produced cells")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
