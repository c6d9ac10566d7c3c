"""pvbatch: Example 4, the ParaView state Data/examples/cornell_box.pvsm, opens the Cornell box
pipeline: loaded (with the plug-in) from another folder with the Data folder as the data
directory, as the GUI's "Search files under specified directory" does, it has the reader,
Interval Subdivision, Spherical Cover, Light Propagation and Hemisphere Extractor connected in
that order, the reader finds the scene, the pipeline updates to lit characteristic points (one
per patch, with Radiosity) and a hemisphere mesh, and a render view shows them.

usage: pvbatch TestExampleState.py PLUGIN DATA_DIR"""
import os
import sys
import tempfile

from paraview.simple import Delete, FindSource, GetRenderViews, GetDisplayProperties, LoadPlugin
from paraview.simple import LoadState

plugin, data = sys.argv[1:3]
data = os.path.abspath(data)
LoadPlugin(plugin, remote=False, ns=globals())
os.chdir(tempfile.mkdtemp())  # not the repository root: the relative file name alone fails

failures = []
state = os.path.join(data, "examples", "cornell_box.pvsm")
LoadState(state, data_directory=data)

STAGES = ["cornell_box.scene", "Interval Subdivision", "Spherical Cover", "Light Propagation",
          "Hemisphere Extractor"]
proxies = {name: FindSource(name) for name in STAGES}
for name, proxy in proxies.items():
    if proxy is None:
        failures.append(f"the state has no {name!r}")
if not failures:
    reader = proxies["cornell_box.scene"]
    if reader.GetXMLName() != "PatchSceneReader" or not os.path.samefile(
            reader.FileName, os.path.join(data, "scenes", "cornell_box.scene")):
        failures.append(f"the reader reads {reader.FileName!r}")
    expected_inputs = {"Interval Subdivision": "cornell_box.scene",
                       "Spherical Cover": "Interval Subdivision",
                       "Light Propagation": "Spherical Cover",
                       "Hemisphere Extractor": "Spherical Cover"}
    for name, upstream in expected_inputs.items():
        if proxies[name].Input.SMProxy != proxies[upstream].SMProxy:
            failures.append(f"{name} is not fed by {upstream}")
    propagation = proxies["Light Propagation"]
    propagation.UpdatePipeline()
    lit = propagation.GetDataInformation(0)
    patches = proxies["Interval Subdivision"].GetDataInformation(0).GetNumberOfCells()
    if lit.GetNumberOfPoints() == 0 or lit.GetNumberOfPoints() != patches:
        failures.append(f"{lit.GetNumberOfPoints()} lit points for {patches} patches")
    if lit.GetPointDataInformation().GetArrayInformation("Radiosity") is None:
        failures.append("the lit points have no Radiosity")
    hemisphere = proxies["Hemisphere Extractor"]
    hemisphere.UpdatePipeline()
    if hemisphere.GetDataInformation(1).GetNumberOfCells() == 0:
        failures.append("the hemisphere mesh is empty")
    views = GetRenderViews()
    if len(views) != 1:
        failures.append(f"{len(views)} render views, expected 1")
    elif not GetDisplayProperties(propagation, views[0]).Visibility:
        failures.append("the render view does not show the lit points")

for view in GetRenderViews():
    Delete(view)
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
