"""Example 3, "Scripted VTK pipeline" (plain Python: vtkmodules and sphericalcover, no ParaView).

The whole method as an ordinary VTK pipeline, one algorithm per stage of the paper:

  vtkPatchSceneReader            the scene's exact Bezier surfaces
  -> vtkIntervalSubdivisionFilter  patches and characteristic points (paper §4)
  -> vtkSphericalCoverFilter       every point's hemisphere of visible patches (§3.3, §4.2.5)
  -> vtkLightPropagationFilter     progressive shooting to equilibrium (§5.1)
  -> vtkRadianceImageFilter        the view through a camera of the scene (§5.3); port 0 the
                                   illumination, port 1 the subdivision's patches
  -> vtkOpenEXRWriter              the HDR image: Radiance (float RGB, W m^-2 sr^-1), Depth (as
                                   OpenEXR's depth channel Z) and SurfaceId (float channels)

Each stage is updated in turn, so the script can time it; a ProgressEvent observer shows its
progress on stderr and an ErrorEvent observer turns a failed stage into one line and exit
status 1. Then it prints the report figures: per surface the area-weighted mean radiosity of
its characteristic points, the energy balance, the shots of the convergence history, and the
timings.

usage: /usr/bin/python3 scripted_vtk_pipeline.py DATA_DIR OUTPUT.exr [--scene NAME]
           [--camera NAME] [--max-level N] [--theta-bins N] [--phi-bins N] [--size WxH] [--spp N]
with PYTHONPATH pointing at the build's package (build/lib/python3.11/site-packages).

The defaults (the Cornell box, MaxLevel 4, a 32 x 128 hemisphere grid, 256 x 256 pixels, 4
samples per pixel) run in about five seconds; the scene's own settings (--max-level 5) take
about half a minute."""
import argparse
import os
import re
import sys
import time

from sphericalcover import (vtkIntervalSubdivisionFilter, vtkLightPropagationFilter,
                            vtkOpenEXRWriter, vtkPatchSceneReader, vtkRadianceImageFilter,
                            vtkSphericalCoverFilter)
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_FLOAT, VTK_STRING
from vtkmodules.vtkFiltersCore import vtkArrayCalculator


def size(text):
    width, _, height = text.partition("x")
    if not (width.isdigit() and height.isdigit() and int(width) > 0 and int(height) > 0):
        raise argparse.ArgumentTypeError(f"{text!r} is not WIDTHxHEIGHT")
    return int(width), int(height)


parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("data", help="the repository's Data folder")
parser.add_argument("output", help="the OpenEXR file to write (its folder is created)")
parser.add_argument("--scene", default="cornell_box", help="a scene of DATA/scenes (default "
                    "cornell_box)")
parser.add_argument("--camera", help="a camera of the scene (default: its first)")
parser.add_argument("--max-level", type=int, default=4, help="subdivision depth (default 4)")
parser.add_argument("--theta-bins", type=int, default=32, help="hemisphere rows (default 32)")
parser.add_argument("--phi-bins", type=int, default=128, help="hemisphere columns (default 128)")
parser.add_argument("--size", type=size, default=(256, 256), help="image size (default 256x256)")
parser.add_argument("--spp", type=int, default=4, help="samples per pixel (default 4)")
arguments = parser.parse_args()
program = os.path.basename(sys.argv[0])


class Stage:
    """One algorithm of the pipeline: its progress on stderr (redrawn in place on a terminal,
    every quarter as a line elsewhere, e.g. in a CI log), its errors collected, its time."""

    def __init__(self, name, algorithm):
        self.name, self.algorithm, self.errors, self.seconds = name, algorithm, [], 0.0
        self.shown = -1
        algorithm.AddObserver("ProgressEvent", self.progress)
        # The executive's "returned failure for request" follows the algorithm's own message;
        # observing both keeps that second, longer message off stderr.
        algorithm.AddObserver("ErrorEvent", self.error)
        algorithm.GetExecutive().AddObserver("ErrorEvent", self.error)

    def progress(self, algorithm, event):
        percent = int(100 * algorithm.GetProgress())
        step = percent if sys.stderr.isatty() else percent // 25 * 25
        if step != self.shown:
            self.shown = step
            bar = "#" * (step // 5)
            ending = "\r" if sys.stderr.isatty() and step < 100 else "\n"
            sys.stderr.write(f"{self.name:<10} [{bar:<20}] {step:3d}%{ending}")
            sys.stderr.flush()

    @calldata_type(VTK_STRING)
    def error(self, caller, event, message):
        # VTK's text is "ERROR: In file, line n\nclass (address): message": keep the message.
        self.errors.append(re.sub(r"^\w+ \(0x[0-9a-f]+\): ", "", message.strip().splitlines()[-1]))

    def run(self):
        start = time.perf_counter()
        self.algorithm.Update()
        self.seconds = time.perf_counter() - start
        if self.errors:
            sys.exit(f"{program}: {self.name}: {self.errors[0]}")


reader = vtkPatchSceneReader()
reader.SetFileName(os.path.join(arguments.data, "scenes", arguments.scene + ".scene"))

# The subdivision stops splitting a patch that would project to about one cell of the hemisphere
# grid (Documentation/Pipeline.md#interval-subdivision), so it is given the cover's grid too.
subdivision = vtkIntervalSubdivisionFilter()
subdivision.SetInputConnection(reader.GetOutputPort())
subdivision.SetMaxLevel(arguments.max_level)
subdivision.SetThetaBins(arguments.theta_bins)
subdivision.SetPhiBins(arguments.phi_bins)

cover = vtkSphericalCoverFilter()
cover.SetInputConnection(subdivision.GetOutputPort(0))  # port 0: the patches
cover.SetThetaBins(arguments.theta_bins)
cover.SetPhiBins(arguments.phi_bins)

propagation = vtkLightPropagationFilter()
propagation.SetInputConnection(cover.GetOutputPort(0))  # port 0: the cover points

render = vtkRadianceImageFilter()
render.SetInputConnection(0, propagation.GetOutputPort(0))  # the illumination
render.SetPatchesConnection(subdivision.GetOutputPort(0))   # port 1: the exact patches
render.SetWidth(arguments.size[0])
render.SetHeight(arguments.size[1])
render.SetSamplesPerPixel(arguments.spp)

# EXR channels are floating point: SurfaceId (int, -1 where nothing is seen) goes to the file
# as a float channel of the same name, exact for these small integers.
surface_channel = vtkArrayCalculator()
surface_channel.SetInputConnection(render.GetOutputPort())
surface_channel.SetAttributeTypeToPointData()
surface_channel.AddScalarArrayName("SurfaceId")
surface_channel.SetFunction("SurfaceId")
surface_channel.SetResultArrayName("SurfaceId")
surface_channel.SetResultArrayType(VTK_FLOAT)

writer = vtkOpenEXRWriter()
writer.SetInputConnection(surface_channel.GetOutputPort())
writer.SetFileName(arguments.output)
writer.SetColorArrayName("Radiance")
writer.AddChannelArray("Depth")  # as OpenEXR's channel Z, +inf where nothing is seen
writer.AddChannelArray("SurfaceId")

try:
    os.makedirs(os.path.dirname(os.path.abspath(arguments.output)), exist_ok=True)
except OSError as error:
    sys.exit(f"{program}: {arguments.output}: cannot create its folder ({error.strerror})")

stages = [Stage("read", reader), Stage("subdivide", subdivision), Stage("cover", cover),
          Stage("propagate", propagation)]
for stage in stages:
    stage.run()

# The camera is chosen by name among the scene's (the illumination's field data carries them).
names = propagation.GetOutput().GetFieldData().GetAbstractArray("CameraNames")
cameras = [names.GetValue(k) for k in range(names.GetNumberOfValues())] if names else []
camera = arguments.camera or (cameras[0] if cameras else None)
if camera not in cameras:
    sys.exit(f"{program}: the scene has no camera {camera!r} (cameras: {', '.join(cameras)})")
render.SetCameraName(camera)
stages.append(Stage("render", render))
stages[-1].run()

stages.append(Stage("write", writer))
start = time.perf_counter()
if not writer.Write() or writer.GetErrorCode() or stages[-1].errors:
    sys.exit(f"{program}: write: " + (stages[-1].errors or [f"cannot write {arguments.output}"])[0])
stages[-1].seconds = time.perf_counter() - start

# --- The report ------------------------------------------------------------------------------
lit = propagation.GetOutput()
points = lit.GetPointData()
radiosity = vtk_to_numpy(points.GetArray("Radiosity"))  # exitant radiance, W m^-2 sr^-1
area = vtk_to_numpy(points.GetArray("Area"))
surface = vtk_to_numpy(points.GetArray("SurfaceId"))
name_id = vtk_to_numpy(points.GetArray("SurfaceNameId"))
surface_names = lit.GetFieldData().GetAbstractArray("SurfaceNames")
patches = subdivision.GetOutput().GetNumberOfCells()
history = propagation.GetOutputDataObject(1)  # port 1: the convergence history

print(f"{arguments.scene}: {reader.GetOutput().GetNumberOfCells()} surfaces, {patches} patches, "
      f"{lit.GetNumberOfPoints()} characteristic points, {arguments.theta_bins} x "
      f"{arguments.phi_bins} hemisphere grid; camera {camera!r}, "
      f"{arguments.size[0]} x {arguments.size[1]} pixels, {arguments.spp} samples per pixel")
print()
# Areas are in the scene's unit (its file's "unit", carried as the field data SceneUnit); the
# powers below are already watts.
unit = lit.GetFieldData().GetAbstractArray("SceneUnit")
area_title = f"area ({unit.GetValue(0) if unit else 'm'}^2)"
print(f"{'surface':<20} {area_title:>14}   mean radiosity R, G, B (W m^-2 sr^-1)")
for sid in sorted(set(surface.tolist())):
    mine = surface == sid
    mean = (radiosity[mine] * area[mine, None]).sum(axis=0) / area[mine].sum()
    name = surface_names.GetValue(int(name_id[mine][0])) if surface_names else str(sid)
    print(f"{name:<20} {area[mine].sum():14.6g}   "
          + "  ".join(f"{value:10.5f}" for value in mean))

# Emitted and absorbed power per band (W); in an open scene such as the Cornell box, without
# its front wall, the difference is the light that leaves the scene plus what is still unshot.
emitted, absorbed = (vtk_to_numpy(lit.GetFieldData().GetArray("EnergyBalance")))
print()
print("energy (W)           emitted " + "  ".join(f"{v:.6g}" for v in emitted))
print("                     absorbed " + "  ".join(f"{v:.6g}" for v in absorbed))
print("                     absorbed / emitted " + "  ".join(f"{a / e:.4f}" if e > 0 else "-"
                                                          for a, e in zip(absorbed, emitted)))
rows = history.GetNumberOfRows()
unshot = history.GetColumnByName("UnshotEnergy").GetValue(rows - 1) if rows else 0.0
print(f"shots                {rows} (the history's rows), unshot at the end {unshot:.6g} W "
      f"= {unshot / max(emitted.sum(), 1e-300):.2e} of the emitted power")
print("timings (s)          " + ", ".join(f"{stage.name} {stage.seconds:.3f}" for stage in stages))
print(f"wrote {arguments.output}: Radiance (R, G, B), Depth (as Z) and SurfaceId, "
      f"{arguments.size[0]} x {arguments.size[1]}")
