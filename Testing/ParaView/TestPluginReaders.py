"""pvbatch: the plug-in loads, its readers open the shipped scenes by extension and by name,
the output has the cells and named arrays of Documentation/Pipeline.md#reader and shows in a render view (the curved
Bezier cells are drawn: the image is not blank). A malformed scene gives an empty output
instead of a crash."""
import os
import sys
import tempfile

from paraview.servermanager import Fetch
from paraview.simple import (ColorBy, CreateView, Delete, LoadPlugin, OpenDataFile, Render,
                             SaveScreenshot, Show)
from vtkmodules.vtkIOImage import vtkPNGReader

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


view = CreateView("RenderView")
view.ViewSize = [320, 240]
view.OrientationAxesVisibility = 0


def check_shows(source, what):
    """Shows the source alone through the scene's first camera, coloured by SurfaceId, and
    checks that the image shows many surfaces (the scenes are rooms seen from inside)."""
    for shown in view.Representations:
        shown.Visibility = 0
    display = Show(source, view)
    display.NonlinearSubdivisionLevel = 3
    ColorBy(display, ("CELLS", "SurfaceId"))
    camera = Fetch(source).GetFieldData().GetArray("CameraParameters").GetTuple(0)
    view.CameraPosition = camera[0:3]
    view.CameraFocalPoint = camera[3:6]
    view.CameraViewUp = camera[6:9]
    view.CameraViewAngle = camera[9]
    Render(view)
    png = os.path.join(tempfile.mkdtemp(), "shot.png")
    SaveScreenshot(png, view, ImageResolution=[320, 240])
    reader = vtkPNGReader()
    reader.SetFileName(png)
    reader.Update()
    scalars = reader.GetOutput().GetPointData().GetScalars()
    colours = {scalars.GetTuple(k)[:3] for k in range(0, scalars.GetNumberOfTuples(), 7)}
    if len(colours) < 8:
        failures.append(f"{what}: the render shows {len(colours)} colours, nothing drawn")


# By extension (the reader factory) and by proxy name.
cornell = OpenDataFile(f"{data}/scenes/cornell_box.scene")
check(cornell, "cornell_box.scene (factory)", 16)
check_shows(cornell, "cornell_box.scene")
teapot_room = globals()["PatchSceneReader"](FileName=f"{data}/scenes/teapot_room.scene")
check(teapot_room, "teapot_room.scene", 39)
check_shows(teapot_room, "teapot_room.scene")
check(OpenDataFile(f"{data}/models/teapot.bpt"), "teapot.bpt (factory)", 32)
check(globals()["BPTReader"](FileName=f"{data}/models/geonum2017/sphere.bpt"), "sphere.bpt", 8)

bad = globals()["PatchSceneReader"](FileName=f"{test_data}/bad/unknown_material.scene")
bad.UpdatePipeline()
if bad.GetDataInformation().GetNumberOfCells() != 0:
    failures.append("a malformed scene produced cells")

for failure in failures:
    print("FAILED:", failure)
# pvbatch crashes in sys.exit while a render view is alive: delete it first.
Delete(view)
del view
sys.exit(1 if failures else 0)
