"""Writes Example 4, cornell_box.pvsm: a ParaView state that opens the Cornell box pipeline
(Patch Scene Reader -> Interval Subdivision -> Spherical Cover -> Light Propagation -> Radiance
Image, and a Hemisphere Extractor) in a render view from the scene's camera: the patches as a
wireframe, the characteristic points as spheres coloured by Radiosity, one hemisphere at its
point. The Radiance Image (the scene's camera "main", 256 x 256) is in the pipeline but not
shown: show it in a render view (2-D) coloured by RGB with Map Scalars off, or save it as .exr.

usage: pvbatch make_cornell_box_state.py PLUGIN DATA_DIR OUTPUT.pvsm

The scene's file name is stored relative to the repository ("Data/scenes/cornell_box.scene"),
so the state opens from the repository's root as it is, and from anywhere with ParaView's
"Search files under specified directory" pointed at the Data folder."""
import os
import sys

from paraview import servermanager
from paraview.simple import (ColorBy, CreateView, Delete, GetColorTransferFunction, LoadPlugin,
                             OutputPort, Render, SaveState, Show)

plugin, data, state = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())

scene_file = os.path.abspath(os.path.join(data, "scenes", "cornell_box.scene"))
scene = globals()["PatchSceneReader"](registrationName="cornell_box.scene", FileName=scene_file)
subdivision = globals()["IntervalSubdivision"](registrationName="Interval Subdivision",
                                               Input=scene, MaxLevel=2)
cover = globals()["SphericalCover"](registrationName="Spherical Cover",
                                    Input=OutputPort(subdivision, 0))
propagation = globals()["LightPropagation"](registrationName="Light Propagation",
                                            Input=OutputPort(cover, 0))
# The final image (paper §5.3): port 0 the illumination, Patches the subdivision's exact patches.
image = globals()["RadianceImage"](registrationName="Radiance Image",
                                   Input=OutputPort(propagation, 0),
                                   Patches=OutputPort(subdivision, 0), CameraName="main",
                                   Width=256, Height=256)
hemisphere = globals()["HemisphereExtractor"](registrationName="Hemisphere Extractor",
                                              Input=OutputPort(cover, 0), PointId=0)

view = CreateView("RenderView")
view.ViewSize = [600, 500]
view.OrientationAxesVisibility = 0
patches = Show(OutputPort(subdivision, 0), view)
patches.SetRepresentationType("Wireframe")
patches.ColorArrayName = ["POINTS", ""]
patches.AmbientColor = patches.DiffuseColor = [0.6, 0.6, 0.6]
lit = Show(OutputPort(propagation, 0), view)
lit.SetRepresentationType("Points")
lit.PointSize = 8
lit.RenderPointsAsSpheres = 1
ColorBy(lit, ("POINTS", "Radiosity", "Magnitude"))
lit.SetScalarBarVisibility(view, True)
# Walls and blocks reflect about 0.1 to 0.5 W m^-2 sr^-1; the lamp's 17 would wash them out.
radiosity = GetColorTransferFunction("Radiosity")
radiosity.ApplyPreset("Inferno (matplotlib)", True)
radiosity.AutomaticRescaleRangeMode = "Never"
radiosity.RescaleTransferFunction(0.0, 0.5)
mesh = Show(OutputPort(hemisphere, 1), view)
ColorBy(mesh, ("CELLS", "SurfaceId"))

# The scene's own camera (field data CameraParameters), after a first render that resets it.
Render(view)
camera = servermanager.Fetch(scene).GetFieldData().GetArray("CameraParameters").GetTuple(0)
view.CameraPosition = camera[0:3]
view.CameraFocalPoint = camera[3:6]
view.CameraViewUp = camera[6:9]
view.CameraViewAngle = camera[9]
Render(view)

SaveState(state)
with open(state) as f:
    text = f.read()
if text.count(f'value="{scene_file}"') != 1:
    sys.exit(f"{state}: the scene's file name {scene_file} is not in the state once")
with open(state, "w") as f:
    f.write(text.replace(f'value="{scene_file}"', 'value="Data/scenes/cornell_box.scene"'))
Delete(view)
del view
