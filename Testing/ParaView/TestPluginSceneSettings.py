"""pvbatch: one pipeline. The scene's settings and cameras reach the filters of the plug-in as
they reach the command line's (paper section 4's MaxLevel, the cover's ThetaBins x PhiBins grid).
- a .scene whose settings differ from the defaults (the Cornell box with max_level 1,
  theta_bins 8, phi_bins 32, tolerance 0.05 and a 48 x 36 camera, written here), through
  paraview.simple with every property at its default, gives the patches, the cover grid and the
  illumination (radiosity, irradiance, energy balance) of `sphcover solve -o`, bit for bit, and
  the subdivision's SubdivisionSettings and the cover's CoverGrid report the scene's values;
- a property set in paraview.simple wins: MaxLevel 2 gives the patches of `sphcover subdivide
  --set max_level=2`; ThetaBins 4 on the cover gives a 4-row grid; the cover takes the grid the
  patches were subdivided for (ThetaBins 16 set on the subdivision only);
- the Radiance Image with no camera property set renders the scene's first camera at its size:
  the image of `sphcover render` (the PNG's bytes, the EXR's depth and radiance)."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy
from paraview import servermanager
from paraview.simple import Delete, LoadPlugin, OutputPort
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataReader

plugin, data, sphcover = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
from sphericalcover import vtkOpenEXRReader  # noqa: E402

failures = []
folder = tempfile.mkdtemp()

# The scene: the Cornell box (no files of its own to resolve) with settings the filters' former
# defaults (5, 32, 128, 0.02) would not give, and a small camera.
scene = json.load(open(os.path.join(data, "scenes", "cornell_box.scene")))
scene["settings"] = {"max_level": 1, "theta_bins": 8, "phi_bins": 32, "tolerance": 0.05}
scene["cameras"][0]["width"], scene["cameras"][0]["height"] = 48, 36
scene_file = os.path.join(folder, "coarse_cornell_box.scene")
with open(scene_file, "w") as stream:
    json.dump(scene, stream)
SETTINGS = [1, 8, 32, 0.05, 0.05, 0.05, 0.05, 0.0]  # SubdivisionSettings' order


def run(*arguments):
    result = subprocess.run([sphcover, *arguments, "--quiet"], capture_output=True, text=True,
                            timeout=600)
    if result.returncode != 0:
        failures.append(f"sphcover {' '.join(arguments)} failed: {result.stderr.strip()}")
    return result.returncode == 0


def blocks(path):
    reader = vtkXMLMultiBlockDataReader()
    reader.SetFileName(path)
    reader.Update()
    output = reader.GetOutput()
    return output.GetBlock(0), output.GetBlock(1)


def fetch(proxy, port=0):
    return servermanager.Fetch(proxy, idx=port)


def field(dataset, name):
    array = dataset.GetFieldData().GetArray(name)
    return None if array is None else vtk_to_numpy(array).ravel().tolist()


def same_arrays(label, got, want, attributes, names):
    """The arrays `names` of `attributes` (cell or point data) are identical, bit for bit."""
    for name in names:
        a = getattr(got, attributes)().GetArray(name)
        b = getattr(want, attributes)().GetArray(name)
        if a is None or b is None:
            failures.append(f"{label}: {name} missing ({a is not None}, {b is not None})")
        elif not numpy.array_equal(vtk_to_numpy(a), vtk_to_numpy(b)):
            difference = numpy.abs(vtk_to_numpy(a) - vtk_to_numpy(b)).max()
            failures.append(f"{label}: {name} differs (largest difference {difference})")


# The command line: the scene's settings, as SettingsOf reads them.
solution = os.path.join(folder, "solution.vtm")
if run("solve", scene_file, "-o", solution):
    cli_patches, cli_illumination = blocks(solution)
else:
    cli_patches = cli_illumination = None

# ParaView: every property at its default.
reader = globals()["PatchSceneReader"](FileName=scene_file)
subdivision = globals()["IntervalSubdivision"](Input=reader)
cover = globals()["SphericalCover"](Input=OutputPort(subdivision, 0))
propagation = globals()["LightPropagation"](Input=OutputPort(cover, 0))
for name in ["MaxLevel", "ThetaBins", "PhiBins", "SelfShadowingTolerance",
             "HemisphericalContainmentTolerance", "SphericalShapeTolerance",
             "CharacterisabilityTolerance"]:
    if subdivision.GetPropertyValue(name) != -1:
        failures.append(f"IntervalSubdivision.{name}: default {subdivision.GetPropertyValue(name)}, "
                        "expected -1 (the scene's)")
patches = fetch(subdivision)
illumination = fetch(propagation)
used = field(patches, "SubdivisionSettings")
print(f"ParaView: {patches.GetNumberOfCells()} patches, SubdivisionSettings {used}, "
      f"CoverGrid {field(illumination, 'CoverGrid')}")
if used != SETTINGS:
    failures.append(f"SubdivisionSettings {used}, expected the scene's {SETTINGS}")
levels = vtk_to_numpy(patches.GetCellData().GetArray("Level"))
if levels.max() != 1:
    failures.append(f"the deepest patch is at level {levels.max()}, expected the scene's 1")
grid = field(illumination, "CoverGrid")
if not grid or grid[:2] != [8, 32]:
    failures.append(f"CoverGrid {grid}, expected the scene's 8 x 32")
if cli_patches is not None:
    print(f"sphcover solve: {cli_patches.GetNumberOfCells()} patches, "
          f"CoverGrid {field(cli_illumination, 'CoverGrid')}")
    if patches.GetNumberOfCells() != cli_patches.GetNumberOfCells():
        failures.append(f"{patches.GetNumberOfCells()} patches in ParaView, "
                        f"{cli_patches.GetNumberOfCells()} by sphcover solve")
    else:
        same_arrays("patches", patches, cli_patches, "GetCellData",
                    ["SurfaceId", "Level", "UVRange", "Area"])
    if illumination.GetNumberOfPoints() != cli_illumination.GetNumberOfPoints():
        failures.append(f"{illumination.GetNumberOfPoints()} points in ParaView, "
                        f"{cli_illumination.GetNumberOfPoints()} by sphcover solve")
    else:
        same_arrays("illumination", illumination, cli_illumination, "GetPointData",
                    ["Radiosity", "Irradiance", "Brightness"])
    for name in ["CoverGrid", "EnergyBalance"]:
        if field(illumination, name) is None or field(illumination, name) != field(
                cli_illumination, name):
            failures.append(f"{name}: {field(illumination, name)} in ParaView, "
                            f"{field(cli_illumination, name)} by sphcover solve")

# A property the user sets wins over the scene's setting.
deeper_file = os.path.join(folder, "deeper.vtm")
deeper = globals()["IntervalSubdivision"](Input=reader, MaxLevel=2)
deeper_patches = fetch(deeper)
if field(deeper_patches, "SubdivisionSettings") != [2] + SETTINGS[1:]:
    failures.append(f"MaxLevel 2: SubdivisionSettings {field(deeper_patches, 'SubdivisionSettings')}")
if deeper_patches.GetNumberOfCells() <= patches.GetNumberOfCells():
    failures.append(f"MaxLevel 2: {deeper_patches.GetNumberOfCells()} patches, not more than the "
                    f"scene's level 1 ({patches.GetNumberOfCells()})")
if run("subdivide", scene_file, "-o", deeper_file, "--set", "max_level=2"):
    cli_deeper, _ = blocks(deeper_file)
    print(f"MaxLevel 2: {deeper_patches.GetNumberOfCells()} patches in ParaView, "
          f"{cli_deeper.GetNumberOfCells()} by sphcover subdivide --set max_level=2")
    if deeper_patches.GetNumberOfCells() != cli_deeper.GetNumberOfCells():
        failures.append("MaxLevel 2: not the patches of sphcover subdivide --set max_level=2")
Delete(deeper)

narrow = globals()["SphericalCover"](Input=OutputPort(subdivision, 0), ThetaBins=4)
narrow_grid = field(fetch(narrow), "CoverGrid")
if not narrow_grid or narrow_grid[:2] != [4, 32]:
    failures.append(f"ThetaBins 4 on the cover: CoverGrid {narrow_grid}, expected 4 x 32")
Delete(narrow)

finer = globals()["IntervalSubdivision"](Input=reader, ThetaBins=16)
follows = globals()["SphericalCover"](Input=OutputPort(finer, 0))
follows_grid = field(fetch(follows), "CoverGrid")
if not follows_grid or follows_grid[:2] != [16, 32]:
    failures.append(f"ThetaBins 16 on the subdivision: the cover's grid is {follows_grid}, "
                    "expected the subdivision's 16 x 32")
Delete(follows)
Delete(finer)

# The scene's camera: no camera property set, the image of sphcover render.
render = globals()["RadianceImage"](Input=OutputPort(propagation, 0),
                                    Patches=OutputPort(subdivision, 0))
image = fetch(render)
print(f"Radiance Image: {image.GetDimensions()[:2]} pixels")
if image.GetDimensions() != (48, 36, 1):
    failures.append(f"the image is {image.GetDimensions()}, not the scene camera's 48 x 36")
png = os.path.join(folder, "render.png")
exr = os.path.join(folder, "render.exr")
if run("render", scene_file, "-o", exr, "--png", png) and image.GetDimensions() == (48, 36, 1):
    png_reader = vtkPNGReader()
    png_reader.SetFileName(png)
    png_reader.Update()
    cli_rgb = vtk_to_numpy(png_reader.GetOutput().GetPointData().GetScalars())
    rgb = vtk_to_numpy(image.GetPointData().GetArray("RGB"))
    if cli_rgb.shape != rgb.shape or not numpy.array_equal(cli_rgb, rgb):
        failures.append("the RGB of the Radiance Image is not the PNG of sphcover render")
    exr_reader = vtkOpenEXRReader()
    exr_reader.SetFileName(exr)
    exr_reader.Update()
    cli_image = exr_reader.GetOutput()
    cli_depth = vtk_to_numpy(cli_image.GetPointData().GetArray("Depth")).ravel()
    depth = vtk_to_numpy(image.GetPointData().GetArray("Depth")).ravel()
    if not numpy.array_equal(cli_depth.astype(numpy.float32), depth):
        failures.append("the Depth of the Radiance Image is not the EXR's of sphcover render")
    # The EXR holds the radiance at the writer's pixel type (half by default, rounded to
    # nearest even as numpy does) or as the float it is.
    cli_radiance = vtk_to_numpy(cli_image.GetPointData().GetArray("Radiance")).astype(numpy.float32)
    radiance = vtk_to_numpy(image.GetPointData().GetArray("Radiance"))
    as_half = radiance.astype(numpy.float16).astype(numpy.float32)
    if cli_radiance.shape != radiance.shape or not (numpy.array_equal(cli_radiance, radiance) or
                                                    numpy.array_equal(cli_radiance, as_half)):
        failures.append("the Radiance of the Radiance Image is not the EXR's of sphcover render")
    else:
        print("sphcover render: the same image (PNG bytes, EXR depth and radiance)")

shutil.rmtree(folder, ignore_errors=True)
for failure in failures:
    print("FAIL:", failure)
sys.exit(1 if failures else 0)
