"""Example 1, "Visual debugging of subdivision" (pvbatch).

Loads the teapot room, subdivides it (paper §4) and shows, from the scene's camera:
- the patches with their edges, coloured by SplitReason (which criterion of paper §4.2 caused
  the last split: 0 none, 1 self-shadowing, 2 hemispherical containment, 3 spherical shape,
  4 characterisability);
- the characteristic points as arrows along their Normals;
- the hemisphere of one characteristic point on a wall (the Hemisphere Extractor's 3-D mesh,
  placed at the point), coloured by the scene entry (SurfaceNameId) seen through each
  cell;
and saves a screenshot.

usage: pvbatch visual_debugging_of_subdivision.py PLUGIN DATA_DIR OUTPUT.png
  PLUGIN    build/lib/paraview-plugins/SphericalCover/SphericalCover.so
  DATA_DIR  the repository's Data folder

Settings are small (MaxLevel 2, an 8 x 32 hemisphere grid) so that it runs in seconds; raise
them to see the subdivision of the real solver settings."""
import os
import sys

from paraview import servermanager
from paraview.simple import (ColorBy, Delete, GetColorTransferFunction, GetScalarBar, Glyph,
                             LoadPlugin,
                             OpenDataFile, OutputPort, Render, SaveScreenshot, Show,
                             CreateRenderView)

plugin, data, screenshot = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())

scene = OpenDataFile(f"{data}/scenes/teapot_room.scene")
subdivision = globals()["IntervalSubdivision"](Input=scene, MaxLevel=2, ThetaBins=8, PhiBins=32)
cover = globals()["SphericalCover"](Input=OutputPort(subdivision, 0), ThetaBins=8, PhiBins=32)

# One characteristic point on the left wall (x = -6), above the teapot's handle: the one nearest
# to (-6, 4, 0), among the cover's points (the refinement splits patches, so the subdivision's
# point ids are not the cover's).
points = servermanager.Fetch(cover, idx=0)


def distance_to_spot(k):
    p = points.GetPoint(k)
    return (p[0] + 6) ** 2 + (p[1] - 4) ** 2 + p[2] ** 2


chosen = min(range(points.GetNumberOfPoints()), key=distance_to_spot)
hemisphere = globals()["HemisphereExtractor"](Input=OutputPort(cover, 0), PointId=chosen,
                                               Radius=1.2)

view = CreateRenderView()
view.ViewSize = [400, 300]
view.OrientationAxesVisibility = 0
view.Background = [1, 1, 1]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass

patches = Show(OutputPort(subdivision, 0), view)
patches.SetRepresentationType("Surface With Edges")
patches.EdgeColor = [0.1, 0.1, 0.1]
ColorBy(patches, ("CELLS", "SplitReason"))
# SplitReason is a category: one colour and one legend entry per criterion.
split_colours = GetColorTransferFunction("SplitReason")
split_colours.InterpretValuesAsCategories = 1
split_colours.Annotations = ["0", "none", "1", "self-shadowing", "2", "hemispherical containment",
                             "3", "spherical shape", "4", "characterisability"]
split_colours.IndexedColors = [0.85, 0.85, 0.85, 0.30, 0.75, 0.75, 0.95, 0.85, 0.30,
                               0.85, 0.35, 0.30, 0.45, 0.40, 0.80]
patches.SetScalarBarVisibility(view, True)
legend = GetScalarBar(split_colours, view)
legend.Title = "SplitReason"
legend.ComponentTitle = ""
legend.TitleFontSize = 10
legend.LabelFontSize = 9
legend.TitleColor = legend.LabelColor = [0, 0, 0]
legend.WindowLocation = "Upper Right Corner"

arrows = Glyph(Input=OutputPort(subdivision, 1), GlyphType="Arrow")
arrows.OrientationArray = ["POINTS", "Normals"]
arrows.ScaleArray = ["POINTS", "No scale array"]
arrows.ScaleFactor = 0.4
arrows.GlyphMode = "All Points"
arrows_display = Show(arrows, view)
arrows_display.ColorArrayName = ["POINTS", ""]
arrows_display.AmbientColor = arrows_display.DiffuseColor = [0.2, 0.2, 0.2]

mesh = Show(OutputPort(hemisphere, 1), view)
# SurfaceNameId: the scene entry seen through each cell (the teapot's 32 patches are one entry).
ColorBy(mesh, ("CELLS", "SurfaceNameId"))
mesh.LookupTable = GetColorTransferFunction("SurfaceNameId")
mesh.LookupTable.ApplyPreset("Jet", True)
mesh.SetScalarBarVisibility(view, False)

# The scene's own camera (field data CameraParameters, Documentation/Pipeline.md#reader), set after
# the first render (which resets the camera to show everything).
Render(view)
camera = servermanager.Fetch(scene).GetFieldData().GetArray("CameraParameters").GetTuple(0)
view.CameraPosition = camera[0:3]
view.CameraFocalPoint = camera[3:6]
view.CameraViewUp = camera[6:9]
view.CameraViewAngle = camera[9]
Render(view)
os.makedirs(os.path.dirname(os.path.abspath(screenshot)), exist_ok=True)
saved = SaveScreenshot(screenshot, view, ImageResolution=[400, 300])
print(f"characteristic point {chosen}; screenshot: {screenshot}")

Delete(view)
del view
if not saved or not os.path.isfile(screenshot):
    print(f"cannot write the screenshot {screenshot}", file=sys.stderr)
    sys.exit(1)
