"""Inside ParaView's GUI client (run by RunParaViewScript.py): Example 4's state,
Data/examples/cornell_box.pvsm, loaded with the data directory the Load State dialog proposes
(the state's own folder), opens two views that are both in one layout, finds the scene, and the
layout's screenshot (ParaView.GuiClientState.Screenshot compares it with
Data/Baseline/GuiClientCornellBoxLayout.png) shows the Cornell box twice: in each half the left
wall red, the right wall green.

arguments (SPHCOVER_GUI_ARGS): RESULT_FILE PLUGIN DATA_DIR SCREENSHOT"""
import json
import os

from paraview import servermanager
from paraview.simple import (FindSource, GetLayout, GetViews, LoadPlugin, LoadState,
                             SaveScreenshot)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

result, plugin, data, screenshot = json.loads(os.environ["SPHCOVER_GUI_ARGS"])
failures = []
try:
    LoadPlugin(plugin, remote=False, ns=globals())
    LoadState(os.path.join(data, "examples", "cornell_box.pvsm"),
              data_directory=os.path.join(data, "examples"))
    reader = FindSource("cornell_box.scene")
    if reader is None or not os.path.isfile(reader.FileName):
        failures.append(f"the scene is not found: {reader.FileName if reader else None!r}")
    views = GetViews()
    layouts = [GetLayout(view) for view in views]
    if len(views) != 2 or any(layout is None for layout in layouts) or \
            len({layout.SMProxy.GetGlobalID() for layout in layouts}) != 1:
        failures.append(f"{len(views)} views, in layouts {layouts}: expected 2 in one layout")
    else:
        SaveScreenshot(screenshot, layouts[0], ImageResolution=[800, 400],
                       OverrideColorPalette="BlackBackground")
        reader_png = vtkPNGReader()
        reader_png.SetFileName(screenshot)
        reader_png.Update()
        image = reader_png.GetOutput()
        width, height, _ = image.GetDimensions()
        rgb = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)
        rgb = rgb[::-1, :, :3].astype(float)
        # The left view (x < 400) fills its height with the box; the right one shows the image
        # fitted (x 460..740). Mean colours of a strip of each wall, at mid-height.
        walls = {"scene view, left wall": (20, 60), "scene view, right wall": (340, 380),
                 "image view, left wall": (475, 500), "image view, right wall": (700, 725)}
        for label, (x0, x1) in walls.items():
            mean = rgb[180:220, x0:x1].reshape(-1, 3).mean(axis=0)
            red = mean[0] > 1.5 * mean[1] and mean[0] > 1.5 * mean[2]
            green = mean[1] > 1.2 * mean[0] and mean[1] > 1.2 * mean[2]
            if ("left" in label and not red) or ("right" in label and not green):
                failures.append(f"{label}: mean RGB {mean.round(1)}")
except Exception as error:  # the result file must say what went wrong
    failures.append(f"{type(error).__name__}: {error}")
with open(result, "w") as stream:
    stream.write("PASSED\n" if not failures else
                 "".join(f"FAILED: {failure}\n" for failure in failures))
