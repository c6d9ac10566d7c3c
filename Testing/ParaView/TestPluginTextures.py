"""pvbatch: a textured scene in ParaView's render view (paper §5.4). The reader's surfaces carry
TextureCoordinates as their active TCoords and the field arrays MaterialTextures (the PNG's
path) and Transmittance; the floor of Data/scenes/textured_floor.scene, drawn unlit with the
texture its MaterialTextures names, shows it the right way round: seen from above with +x to the
right and -z up (the floor's u and v), red grows from left to right and green from bottom to top
(textures/ramp.png: red with u, green with v), as in the solution."""
import os
import sys
import tempfile

from paraview.servermanager import Fetch
from paraview.simple import (CreateTexture, CreateView, Delete, LoadPlugin, Render,
                             SaveScreenshot, Show)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

plugin, data = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
failures = []

reader = globals()["PatchSceneReader"](FileName=f"{data}/scenes/textured_floor.scene")
reader.UpdatePipeline()
grid = Fetch(reader)
tcoords = grid.GetPointData().GetTCoords()
if tcoords is None or tcoords.GetName() != "TextureCoordinates":
    failures.append("the reader's output has no active TCoords named TextureCoordinates")
if grid.GetCellData().GetArray("Transmittance") is None:
    failures.append("the reader's output has no cell array Transmittance")
textures = grid.GetFieldData().GetAbstractArray("MaterialTextures")
material = int(grid.GetCellData().GetArray("MaterialId").GetTuple1(0))  # the floor's
texture_file = textures.GetValue(material) if textures else ""
if not texture_file.endswith("ramp.png"):
    failures.append(f"the floor's MaterialTextures entry is '{texture_file}'")

view = CreateView("RenderView")
view.ViewSize = [200, 200]
view.OrientationAxesVisibility = 0
view.Background = [0, 0, 0]
if not failures:
    display = Show(reader, view)
    display.ColorArrayName = ["POINTS", ""]
    display.DiffuseColor = [1, 1, 1]
    display.AmbientColor = [1, 1, 1]
    display.Ambient = 1.0
    display.Diffuse = 0.0
    display.Texture = CreateTexture(texture_file)
    # From above the floor's centre, below the lamp's height: x to the right, -z up.
    view.CameraPosition = [0.5, 0.9, 0.5]
    view.CameraFocalPoint = [0.5, 0.0, 0.5]
    view.CameraViewUp = [0, 0, -1]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 0.5
    Render(view)
    png = os.path.join(tempfile.mkdtemp(), "floor.png")
    SaveScreenshot(png, view, ImageResolution=[200, 200])
    image = vtkPNGReader()
    image.SetFileName(png)
    image.Update()
    rgb = vtk_to_numpy(image.GetOutput().GetPointData().GetScalars())[:, :3].reshape(200, 200, 3)
    rgb = rgb.astype(float)  # [row from the bottom, column]
    inner = rgb[40:160, 40:160]
    left, right = inner[:, :30].mean(axis=(0, 1)), inner[:, -30:].mean(axis=(0, 1))
    bottom, top = inner[:30].mean(axis=(0, 1)), inner[-30:].mean(axis=(0, 1))
    print(f"left {left}, right {right}, bottom {bottom}, top {top}")
    if not (right[0] - left[0] > 60 and abs(right[1] - left[1]) < 15):
        failures.append(f"red does not grow from left to right alone (left {left}, right {right})")
    if not (top[1] - bottom[1] > 60 and abs(top[0] - bottom[0]) < 15):
        failures.append(f"green does not grow from bottom to top alone (bottom {bottom}, top {top})")

for failure in failures:
    print("FAILED:", failure)
# pvbatch crashes in sys.exit while a render view is alive: delete it first.
Delete(view)
del view
sys.exit(1 if failures else 0)
