"""pvbatch: Example 4, the ParaView state Data/examples/cornell_box.pvsm, opens the Cornell box
pipeline: loaded (with the plug-in) from another folder with the Data folder as the data
directory, as the GUI's "Search files under specified directory" does, it has the reader,
Interval Subdivision, Spherical Cover, Light Propagation, Radiance Image (fed by Light
Propagation and by the subdivision's patches), Illumination Field and Hemisphere Extractor
connected in that order, the reader finds the scene, the pipeline updates to lit characteristic
points (one per patch, with Radiosity; the cover's refinement may split a patch into several), a
hemisphere mesh and a 256 x 256 image through the scene's camera whose brightest pixel is the
lamp (its emission, W m^-2 sr^-1, at least), and its two render views (the scene and the image)
show the Illumination Field and the image. ParaView.GuiCornellBox loads it with the state's own
folder as the data directory and compares its views with baselines.

usage: pvbatch TestExampleState.py PLUGIN DATA_DIR"""
import os
import sys
import tempfile

from paraview import servermanager
from paraview.simple import Delete, FindSource, GetRenderViews, LoadPlugin
from paraview.simple import LoadState

plugin, data = sys.argv[1:3]
data = os.path.abspath(data)
LoadPlugin(plugin, remote=False, ns=globals())
os.chdir(tempfile.mkdtemp())  # not the repository root: the relative file name alone fails

failures = []
state = os.path.join(data, "examples", "cornell_box.pvsm")
LoadState(state, data_directory=data)

STAGES = ["cornell_box.scene", "Interval Subdivision", "Spherical Cover", "Light Propagation",
          "Radiance Image", "Illumination Field", "Hemisphere Extractor"]
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
                       "Radiance Image": "Light Propagation",
                       "Illumination Field": "Light Propagation",
                       "Hemisphere Extractor": "Spherical Cover"}
    for name, upstream in expected_inputs.items():
        if proxies[name].Input.SMProxy != proxies[upstream].SMProxy:
            failures.append(f"{name} is not fed by {upstream}")
    image = proxies["Radiance Image"]
    patches_input = image.SMProxy.GetProperty("Patches")
    if patches_input.GetProxy(0) != proxies["Interval Subdivision"].SMProxy or \
            patches_input.GetOutputPortForConnection(0) != 0:
        failures.append("Radiance Image's Patches are not the subdivision's patches (port 0)")
    propagation = proxies["Light Propagation"]
    propagation.UpdatePipeline()
    lit = propagation.GetDataInformation(0)
    cover_points = proxies["Spherical Cover"].GetDataInformation(0).GetNumberOfPoints()
    patches = proxies["Interval Subdivision"].GetDataInformation(0).GetNumberOfCells()
    # One lit point per cover point; the cover's refinement may split patches (never merge).
    if lit.GetNumberOfPoints() == 0 or lit.GetNumberOfPoints() != cover_points or \
            cover_points < patches:
        failures.append(f"{lit.GetNumberOfPoints()} lit points, {cover_points} cover points "
                        f"for {patches} patches")
    if lit.GetPointDataInformation().GetArrayInformation("Radiosity") is None:
        failures.append("the lit points have no Radiosity")
    hemisphere = proxies["Hemisphere Extractor"]
    hemisphere.UpdatePipeline()
    if hemisphere.GetDataInformation(1).GetNumberOfCells() == 0:
        failures.append("the hemisphere mesh is empty")
    # The image: the size stored, and the lamp (emission 18.387, 10.9873, 2.75357 in the
    # scene; exitant radiance = emission + reflection, paper §5) its brightest pixel.
    image.UpdatePipeline()
    info = image.GetDataInformation(0)
    extent = info.GetExtent()
    radiance = info.GetPointDataInformation().GetArrayInformation("Radiance")
    if (extent[1] - extent[0] + 1, extent[3] - extent[2] + 1) != (256, 256) or radiance is None:
        failures.append(f"the Radiance Image has extent {extent}, Radiance {radiance}")
    else:
        emission = [18.387, 10.9873, 2.75357]
        brightest = [radiance.GetComponentRange(band)[1] for band in range(3)]
        if any(b < e or b > 1.05 * e for b, e in zip(brightest, emission)):
            failures.append(f"the image's brightest radiance {brightest} is not the lamp's "
                            f"emission {emission} (at most 5% more)")
        else:
            print(f"Radiance Image: 256 x 256, brightest radiance {brightest}")
    views = GetRenderViews()
    # servermanager.GetRepresentation, unlike GetDisplayProperties, creates none.
    shown = sorted(name for view in views for name in ("Illumination Field", "Radiance Image")
                   if servermanager.GetRepresentation(proxies[name], view) and
                   servermanager.GetRepresentation(proxies[name], view).Visibility)
    if len(views) != 2 or shown != ["Illumination Field", "Radiance Image"]:
        failures.append(f"{len(views)} render views showing {shown}, expected 2 showing the "
                        "Illumination Field and the Radiance Image")

for view in GetRenderViews():
    Delete(view)
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
