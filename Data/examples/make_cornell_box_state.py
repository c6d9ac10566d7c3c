"""Writes Example 4, cornell_box.pvsm: a ParaView state that opens the Cornell box pipeline
(Patch Scene Reader -> Interval Subdivision -> Spherical Cover -> Light Propagation -> Radiance
Image and Illumination Field, and a Hemisphere Extractor) in one layout of two views, side by
side:
- "Scene": a render view through the scene's camera "main" showing the Illumination Field in
  its true colours (DisplayRGB with Map Scalars off, lighting off: the colours are the light);
  the patches (wireframe), the lit points (by Radiosity) and one hemisphere are in the pipeline,
  hidden: tick their eyes to inspect the stages;
- "Image": a 2-D render view showing the Radiance Image (256 x 256 through "main") as a Slice
  of its RGB bytes (Map Scalars off), fitted to the view.

usage: pvbatch make_cornell_box_state.py PLUGIN DATA_DIR OUTPUT.pvsm

The scene's file name is stored as "Data/examples/../scenes/cornell_box.scene": relative to
the repository's root, so the state opens from there as it is, and through the state's own
folder, so ParaView's "Search files under specified directory", whose default is the state's
folder (Data/examples), finds it (it tries the folder, then appends the stored path's folders
from the last: "scenes", then ".."); pointed at the Data folder it finds it as well."""
import os
import sys

from paraview import servermanager
from paraview.simple import (AssignViewToLayout, ColorBy, CreateLayout, CreateView, Delete,
                             Hide, LoadPlugin, OutputPort, Render, SaveState, Show)

plugin, data, state = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
STORED_NAME = "Data/examples/../scenes/cornell_box.scene"

scene_file = os.path.abspath(os.path.join(data, "scenes", "cornell_box.scene"))
scene = globals()["PatchSceneReader"](registrationName="cornell_box.scene", FileName=scene_file)
subdivision = globals()["IntervalSubdivision"](registrationName="Interval Subdivision",
                                               Input=scene, MaxLevel=2)
cover = globals()["SphericalCover"](registrationName="Spherical Cover",
                                    Input=OutputPort(subdivision, 0))
propagation = globals()["LightPropagation"](registrationName="Light Propagation",
                                            Input=OutputPort(cover, 0))
# The final image (paper §5.3): port 0 the illumination, Patches the subdivision's exact patches
# (stored explicitly, so the state shows the wiring; left empty they would be the same).
image = globals()["RadianceImage"](registrationName="Radiance Image",
                                   Input=OutputPort(propagation, 0),
                                   Patches=OutputPort(subdivision, 0), CameraName="main",
                                   Width=256, Height=256)
field = globals()["IlluminationField"](registrationName="Illumination Field",
                                       Input=OutputPort(propagation, 0))
hemisphere = globals()["HemisphereExtractor"](registrationName="Hemisphere Extractor",
                                              Input=OutputPort(cover, 0), PointId=0)

layout = CreateLayout("Cornell box")
view = CreateView("RenderView", registrationName="Scene")
view.OrientationAxesVisibility = 0
AssignViewToLayout(view=view, layout=layout, hint=0)
image_view = CreateView("RenderView", registrationName="Image")
image_view.OrientationAxesVisibility = 0
image_view.InteractionMode = "2D"
# Split the layout's root cell in two: the scene on the left (cell 1), the image on the right
# (cell 2).
AssignViewToLayout(view=image_view, layout=layout, hint=2)
layout.SetSize(1000, 500)

# The inspection stages, hidden: the patches, the lit points by Radiosity, one hemisphere.
patches = Show(OutputPort(subdivision, 0), view)
patches.SetRepresentationType("Wireframe")
patches.ColorArrayName = ["POINTS", ""]
lit = Show(OutputPort(propagation, 0), view)
lit.SetRepresentationType("Points")
lit.PointSize = 8
lit.RenderPointsAsSpheres = 1
ColorBy(lit, ("POINTS", "Radiosity", "Magnitude"))
mesh = Show(OutputPort(hemisphere, 1), view)
ColorBy(mesh, ("CELLS", "SurfaceId"))
for port in (OutputPort(subdivision, 0), OutputPort(propagation, 0), OutputPort(hemisphere, 1)):
    Hide(port, view)

# The solution in its true colours: the bytes of DisplayRGB as they are, without shading.
surfaces = Show(field, view)
ColorBy(surfaces, ("POINTS", "DisplayRGB"))
surfaces.MapScalars = 0
surfaces.Ambient = 1.0
surfaces.Diffuse = 0.0
surfaces.SetScalarBarVisibility(view, False)

# The image as an image: its RGB bytes on a slice, fitted to the 2-D view.
pixels = Show(image, image_view)
pixels.SetRepresentationType("Slice")
ColorBy(pixels, ("POINTS", "RGB"))
pixels.MapScalars = 0
pixels.SetScalarBarVisibility(image_view, False)
image_view.ResetCamera(False)

# The scene's own camera (field data CameraParameters), after a first render that resets it.
Render(view)
camera = servermanager.Fetch(scene).GetFieldData().GetArray("CameraParameters").GetTuple(0)
view.CameraPosition = camera[0:3]
view.CameraFocalPoint = camera[3:6]
view.CameraViewUp = camera[6:9]
view.CameraViewAngle = camera[9]
Render(view)
Render(image_view)

SaveState(state)
with open(state) as f:
    text = f.read()
if text.count(f'value="{scene_file}"') != 1:
    sys.exit(f"{state}: the scene's file name {scene_file} is not in the state once")
with open(state, "w") as f:
    f.write(text.replace(f'value="{scene_file}"', f'value="{STORED_NAME}"'))
