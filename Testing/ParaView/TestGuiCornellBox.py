"""pvbatch, the proxies, views and layouts of ParaView's GUI on the Cornell box (issue 17).

State: Data/examples/cornell_box.pvsm, loaded from another folder with the data directory the
GUI's Load State dialog proposes (the state's own folder, Data/examples), finds the scene, has
every view in a layout (two: "Scene" and "Image", side by side) and shows the Illumination
Field in true colours from the scene's camera and the Radiance Image as an image; both views
are saved as screenshots (compared with Data/Baseline by ParaView.GuiCornellBox.Screenshots,
which holds the soft shadows) and their colours checked here: the left wall red, the right
wall green, the lamp white.

Defaults: the scene opened as File > Open does, the filters applied as the Filters menu does
(only the subdivision made coarse, for time): the Radiance Image on the Illumination alone
(Patches left empty: ParaView would not ask for them) lists the scene's cameras in its
CameraName domain, starts at the first ("main") and renders at its size (512 x 512) without any
property set, shown in a render view as a Slice coloured by RGB; the Illumination Field carries
DisplayRGB (bytes, the active scalars) whose ExposureStops of +1 doubles the linear value; the
patches coloured by SplitReason get a categorical map with the criteria's names.

usage: pvbatch TestGuiCornellBox.py PLUGIN DATA_DIR OUTPUT_DIR"""
import os
import sys
import tempfile

from paraview import servermanager
from paraview.modules.vtkRemotingServerManager import vtkSMSettings
from paraview.simple import (ColorBy, CreateView, Delete, FindSource, GetColorTransferFunction,
                             GetLayout, GetViews, LoadPlugin, LoadState, OpenDataFile,
                             OutputPort, Render, SaveScreenshot, Show)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

plugin, data, output = sys.argv[1:4]
data, output = os.path.abspath(data), os.path.abspath(output)
os.makedirs(output, exist_ok=True)
LoadPlugin(plugin, remote=False, ns=globals())
os.chdir(tempfile.mkdtemp())  # not the repository's root: the stored relative name alone fails
failures = []

# The plug-in's colour-map defaults, as ParaView's vtkSMTransferFunctionManager reads them for
# a new lookup table of an array named SplitReason (before any state brings its own).
fresh = servermanager.ProxyManager().SMProxyManager.NewProxy("lookup_tables", "PVLookupTable")
vtkSMSettings.GetInstance().GetProxySettings(".array_lookup_tables.SplitReason", fresh)
if fresh.GetProperty("IndexedLookup").GetElement(0) != 1 or \
        fresh.GetProperty("Annotations").GetNumberOfElements() != 10:
    failures.append("the settings give SplitReason no categorical map with 5 named values")


def srgb_to_linear(byte):
    c = byte / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    rgb = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)[:, :, :3]
    return rgb[::-1].astype(float)  # row 0 at the top, as the picture is seen


def mean(rgb, x0, x1, y0, y1):
    """The mean colour of the box [x0, x1) x [y0, y1) given in fractions of the picture."""
    h, w, _ = rgb.shape
    return rgb[int(y0 * h):int(y1 * h), int(x0 * w):int(x1 * w)].reshape(-1, 3).mean(axis=0)


def check_cornell_colours(label, rgb):
    """The box's opening spans about the middle two thirds of the 400 x 400 pictures (the scene
    camera's 39.3 degrees; the image fitted to its view): the left wall at x 0.19..0.23 is red,
    the right wall at x 0.77..0.81 green, and the top half's brightest pixel (the lamp) white."""
    left, right = mean(rgb, 0.19, 0.23, 0.40, 0.60), mean(rgb, 0.77, 0.81, 0.40, 0.60)
    if not (left[0] > 1.5 * left[1] and left[0] > 1.5 * left[2]):
        failures.append(f"{label}: the left wall is not red: mean RGB {left.round(1)}")
    if not (right[1] > 1.2 * right[0] and right[1] > 1.2 * right[2]):
        failures.append(f"{label}: the right wall is not green: mean RGB {right.round(1)}")
    top = rgb[:rgb.shape[0] // 2].reshape(-1, 3)
    lamp = top[top.sum(axis=1).argmax()]
    if lamp.min() < 230:
        failures.append(f"{label}: the brightest pixel of the top half is not white: {lamp}")
    print(f"{label}: left wall {left.round(1)}, right wall {right.round(1)}, lamp {lamp}")


# --- the state --------------------------------------------------------------------------
state = os.path.join(data, "examples", "cornell_box.pvsm")
LoadState(state, data_directory=os.path.join(data, "examples"))
reader = FindSource("cornell_box.scene")
if reader is None or not os.path.isfile(reader.FileName) or not os.path.samefile(
        reader.FileName, os.path.join(data, "scenes", "cornell_box.scene")):
    failures.append(f"the state's reader does not read the scene: "
                    f"{reader.FileName if reader else None!r}")
proxy_manager = servermanager.ProxyManager().SMProxyManager
views = {proxy_manager.GetProxyName("views", view.SMProxy): view for view in GetViews()}
if sorted(views) != ["Image", "Scene"]:
    failures.append(f"the state's views are {sorted(views)}, expected Image and Scene")
for name, view in views.items():
    if GetLayout(view) is None:
        failures.append(f"the state's view {name!r} is in no layout")
layouts = {id(GetLayout(view).SMProxy) for view in views.values() if GetLayout(view)}
if len(layouts) != 1:
    failures.append(f"the state's views are in {len(layouts)} layouts, expected one")
if not failures:
    field = FindSource("Illumination Field")
    image = FindSource("Radiance Image")
    scene_display = servermanager.GetRepresentation(field, views["Scene"])
    image_display = servermanager.GetRepresentation(image, views["Image"])
    if not scene_display or not scene_display.Visibility or \
            list(scene_display.ColorArrayName) != ["POINTS", "DisplayRGB"] or \
            scene_display.MapScalars != 0:
        failures.append("the Scene view does not show the Illumination Field's DisplayRGB "
                        "with Map Scalars off")
    if not image_display or not image_display.Visibility or \
            image_display.Representation != "Slice" or image_display.MapScalars != 0:
        failures.append("the Image view does not show the Radiance Image as a Slice with Map "
                        "Scalars off")
    camera = servermanager.Fetch(reader).GetFieldData().GetArray("CameraParameters").GetTuple(0)
    position = list(views["Scene"].CameraPosition)
    if max(abs(a - b) for a, b in zip(position, camera[0:3])) > 1e-6:
        failures.append(f"the Scene view looks from {position}, not the scene camera's "
                        f"{camera[0:3]}")
    shots = {"Scene": "GuiCornellBoxScene.png", "Image": "GuiCornellBoxImage.png"}
    for name, file_name in shots.items():
        path = os.path.join(output, file_name)
        Render(views[name])
        SaveScreenshot(path, views[name], ImageResolution=[400, 400],
                       OverrideColorPalette="BlackBackground")
        check_cornell_colours(f"state, {name} view", pixels(path))

for view in GetViews():
    Delete(view)

# --- the defaults ------------------------------------------------------------------------
scene = OpenDataFile(os.path.join(data, "scenes", "cornell_box.scene"))
subdivision = globals()["IntervalSubdivision"](Input=scene, MaxLevel=2)
cover = globals()["SphericalCover"](Input=OutputPort(subdivision, 0))
propagation = globals()["LightPropagation"](Input=OutputPort(cover, 0))
render = globals()["RadianceImage"](Input=OutputPort(propagation, 0))
cameras = render.GetProperty("CameraName").SMProperty.FindDomain("vtkSMStringListDomain")
listed = [cameras.GetString(k) for k in range(cameras.GetNumberOfStrings())] if cameras else []
if listed != ["main"]:
    failures.append(f"Radiance Image: the CameraName domain lists {listed}, expected ['main']")
if render.CameraName != "main":
    failures.append(f"Radiance Image: CameraName starts at {render.CameraName!r}, not 'main'")
if render.GetProperty("Patches").SMProperty.GetNumberOfProxies() != 0:
    failures.append("Radiance Image: Patches is set though nothing set it")
render.UpdatePipeline()
info = render.GetDataInformation(0)
extent = info.GetExtent()
size = (extent[1] - extent[0] + 1, extent[3] - extent[2] + 1)
radiance = info.GetPointDataInformation().GetArrayInformation("Radiance")
if size != (512, 512) or radiance is None:
    failures.append(f"Radiance Image defaults: {size} pixels (expected the camera's 512 x 512)")
else:
    emission = [18.387, 10.9873, 2.75357]  # the lamp, brightest seen through "main"
    brightest = [radiance.GetComponentRange(band)[1] for band in range(3)]
    if any(b < e or b > 1.05 * e for b, e in zip(brightest, emission)):
        failures.append(f"Radiance Image defaults: brightest {brightest}, not the lamp's "
                        f"{emission}")
image_view = CreateView("RenderView")
image_view.InteractionMode = "2D"
image_view.OrientationAxesVisibility = 0
shown = Show(render, image_view)
if shown.Representation != "Slice" or list(shown.ColorArrayName) != ["POINTS", "RGB"]:
    failures.append(f"Radiance Image shown as {shown.Representation!r} coloured by "
                    f"{list(shown.ColorArrayName)}, expected a Slice by RGB")
shown.MapScalars = 0  # no hint sets it in ParaView 5.11 (README, "ParaView users")
shown.SetScalarBarVisibility(image_view, False)
image_view.ResetCamera(False)
path = os.path.join(output, "GuiCornellBoxDefaultImage.png")
SaveScreenshot(path, image_view, ImageResolution=[400, 400],
               OverrideColorPalette="BlackBackground")
check_cornell_colours("defaults, Radiance Image", pixels(path))

field = globals()["IlluminationField"](Input=OutputPort(propagation, 0))
lit = servermanager.Fetch(field)
rgb = lit.GetPointData().GetScalars()
if rgb is None or rgb.GetName() != "DisplayRGB" or rgb.GetDataTypeAsString() != "unsigned char" \
        or rgb.GetNumberOfComponents() != 3 or rgb.GetNumberOfTuples() != lit.GetNumberOfPoints():
    failures.append(f"Illumination Field: the active scalars are {rgb and rgb.GetName()}, "
                    "not DisplayRGB bytes per point")
else:
    before = vtk_to_numpy(rgb).astype(int)
    field.ExposureStops = 1.0
    after = vtk_to_numpy(servermanager.Fetch(field).GetPointData().GetScalars()).astype(int)
    # Unsaturated, not too dark values: +1 stop doubles the linear value (bytes round).
    ratios = [srgb_to_linear(a) / srgb_to_linear(b)
              for b, a in zip(before.ravel(), after.ravel()) if 40 <= b <= 150]
    if not ratios or min(ratios) < 1.9 or max(ratios) > 2.1:
        failures.append(f"Illumination Field: +1 stop multiplies the linear value by "
                        f"{min(ratios, default=0):.3f}..{max(ratios, default=0):.3f}, not 2")

# SplitReason: coloured by it, the patches get a categorical map with the criteria's names (the
# plug-in's array defaults, paraview_plugin/SphericalCoverColourDefaults.h, as the state
# stores them too); Level stays a continuous map.
patches_view = CreateView("RenderView")
patches_display = Show(OutputPort(subdivision, 0), patches_view)
ColorBy(patches_display, ("CELLS", "SplitReason"))
split = GetColorTransferFunction("SplitReason")
names = list(split.Annotations)
if split.InterpretValuesAsCategories != 1 or names[0::2] != ["0", "1", "2", "3", "4"] or \
        names[1::2] != ["none", "self-shadowing", "hemispherical containment",
                        "spherical shape", "characterisability"] or \
        len(split.IndexedColors) != 15:
    failures.append(f"SplitReason: categorical {split.InterpretValuesAsCategories}, "
                    f"annotations {names}")
if GetColorTransferFunction("Level").InterpretValuesAsCategories != 0:
    failures.append("Level: a categorical map, expected a continuous one")

# Views deleted before pvbatch exits: tearing down a view at interpreter exit crashes in X.
for view in GetViews():
    Delete(view)
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
