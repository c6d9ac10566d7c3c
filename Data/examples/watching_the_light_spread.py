"""Example 2, "Watching the light spread" (pvbatch).

Progressive propagation (paper §5.1) shoots the light of the brightest characteristic point
first. Stopping it after K shots (Light Propagation's MaximumShots) shows how the light
spreads through the Cornell box: first the lamp lights the ceiling-facing surfaces directly,
then the walls bleed their colours into each other. For K = 1, 10, 100 and 0 (until
equilibrium) the script saves a screenshot of the patches coloured by the radiosity of their
characteristic point (RGB through a fixed exposure), and finally a line chart of the convergence history (the unshot energy
after each shot).

usage: pvbatch watching_the_light_spread.py PLUGIN DATA_DIR OUTPUT_DIR
writes OUTPUT_DIR/light_spread_<K>.png (K = 1, 10, 100, 0) and OUTPUT_DIR/convergence.png

Settings are small (MaxLevel 2, a 16 x 64 hemisphere grid) so that it runs in seconds."""
import os
import sys

from paraview import servermanager
from paraview.simple import (ColorBy, CreateView, Delete, LoadPlugin,
                             OutputPort, ProgrammableFilter, Render, SaveScreenshot, Show)

plugin, data, folder = sys.argv[1:4]
os.makedirs(folder, exist_ok=True)
LoadPlugin(plugin, remote=False, ns=globals())

SHOTS = [1, 10, 100, 0]

scene = globals()["PatchSceneReader"](FileName=f"{data}/scenes/cornell_box.scene")
subdivision = globals()["IntervalSubdivision"](Input=scene, MaxLevel=2)
cover = globals()["SphericalCover"](Input=OutputPort(subdivision, 0), ThetaBins=16, PhiBins=64)
propagation = globals()["LightPropagation"](Input=OutputPort(cover, 0))

# Each patch takes the area-weighted mean radiosity of its characteristic points (the points'
# InputPatchId indexes the subdivision's patches; the cover's refinement may give a patch several
# points), so the patches show the solution as flat-shaded radiosity.
lit_patches = ProgrammableFilter(Input=[OutputPort(subdivision, 0), OutputPort(propagation, 0)])
lit_patches.OutputDataSetType = "vtkUnstructuredGrid"
lit_patches.Script = """
import numpy
patches, points = inputs[0], inputs[1]
output.ShallowCopy(patches.VTKObject)
count = patches.GetNumberOfCells()
ids = numpy.asarray(points.PointData["InputPatchId"])
area = numpy.asarray(points.PointData["Area"])
power = numpy.zeros((count, 3))
numpy.add.at(power, ids, numpy.asarray(points.PointData["Radiosity"]) * area[:, None])
total = numpy.bincount(ids, weights=area, minlength=count)
radiosity = power / numpy.maximum(total, 1e-300)[:, None]
cells = radiosity[patches.CellData["PatchId"]]
output.CellData.append(cells, "Radiosity")
# For display: exposure (radiance 0.4 W m^-2 sr^-1 -> white), clipping, sRGB-like gamma 2.2.
rgb = 255 * numpy.clip(cells * EXPOSURE, 0, 1) ** (1 / 2.2)
output.CellData.append(rgb.round().astype(numpy.uint8), "RGB")
""".replace("EXPOSURE", "2.5")

view = CreateView("RenderView")
view.ViewSize = [400, 300]
view.OrientationAxesVisibility = 0
display = Show(lit_patches, view)
display.SetRepresentationType("Surface With Edges")
display.EdgeColor = [0.3, 0.3, 0.3]
# Radiance as the eye sees it: the RGB bands through a fixed exposure, the same for every
# step, so that the steps compare and the walls' colours bleed visibly.
ColorBy(display, ("CELLS", "RGB"))
display.MapScalars = 0

Render(view)
camera = servermanager.Fetch(scene).GetFieldData().GetArray("CameraParameters").GetTuple(0)
view.CameraPosition = camera[0:3]
view.CameraFocalPoint = camera[3:6]
view.CameraViewUp = camera[6:9]
view.CameraViewAngle = camera[9]

for shots in SHOTS:
    propagation.MaximumShots = shots
    Render(view)
    path = os.path.join(folder, f"light_spread_{shots}.png")
    SaveScreenshot(path, view, ImageResolution=[400, 300])
    print(f"MaximumShots {shots}: {propagation.GetDataInformation(1).GetNumberOfRows()} shots, "
          f"{path}")

# The convergence history of the full run: unshot energy (W) after each shot.
chart = CreateView("XYChartView")
chart.ViewSize = [400, 300]
chart.LeftAxisLogScale = 1
chart.LeftAxisTitle = "Unshot energy (W)"
chart.BottomAxisTitle = "Shot"
chart.ShowLegend = 0
history = Show(OutputPort(propagation, 1), chart, "XYChartRepresentation")
history.UseIndexForXAxis = 0
history.XArrayName = "Shot"
history.SeriesVisibility = ["UnshotEnergy"]
Render(chart)
SaveScreenshot(os.path.join(folder, "convergence.png"), chart, ImageResolution=[400, 300])

Delete(chart)
Delete(view)
del chart, view
