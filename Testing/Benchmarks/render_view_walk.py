"""Frames per second of ParaView's render view walking through a saved solution (issue 18): the
Illumination Field shown with the plug-in's "View-Dependent Radiance" representation (mirrors and
glossy surfaces toward the camera, paper §5.3.1) and, for comparison, as a plain Surface coloured
by its DisplayRGB (the diffuse part only, no evaluation), the camera orbiting the scene's first
camera (around the point of its view axis nearest the scene's centre, as `sphcover walk --orbit`)
with nothing else changed. Every frame is one timed `Render()` of a pvbatch view. Then the
evaluation alone: vtkViewDependentRadiance on the field for the same eyes, its milliseconds and
evaluated vertices per eye (the first eye evaluates every vertex, later ones the view-dependent
vertices only).

    nice pvbatch Testing/Benchmarks/render_view_walk.py \\
        build/lib/paraview-plugins/SphericalCover/SphericalCover.so teapot.vtm \\
        --frames 24 --size 1024x768 --resolution 4 --backend STDThread

(PYTHONPATH must hold the `sphericalcover` package for the evaluation figures:
build/lib/python3.11/site-packages.) Timings only; nothing is checked
(Testing/Benchmarks/README.md).
"""
import argparse
import math
import os
import time
import xml.etree.ElementTree as ET

from paraview.simple import (ColorBy, CreateRenderView, Delete, GetViews, Hide, LoadPlugin,
                             OpenDataFile, Render, Show)
from vtkmodules.vtkCommonCore import vtkSMPTools

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("plugin")
parser.add_argument("solution", help="a solution saved by sphcover solve -o X.vtm")
parser.add_argument("--frames", type=int, default=24)
parser.add_argument("--size", default="1024x768")
parser.add_argument("--resolution", type=int, default=4, help="Illumination Field's Resolution")
parser.add_argument("--backend", default="", help="vtkSMPTools backend (default: ParaView's)")
arguments = parser.parse_args()
if arguments.backend:
    vtkSMPTools.SetBackend(arguments.backend)
width, height = (int(v) for v in arguments.size.split("x"))
LoadPlugin(arguments.plugin, remote=False, ns=globals())

# The .vtm's two blocks, Patches (.vtu) and Illumination (.vtp), read apart: the field wants the
# illumination as polydata.
folder = os.path.dirname(os.path.abspath(arguments.solution))
blocks = {d.get("name"): os.path.join(folder, d.get("file"))
          for d in ET.parse(arguments.solution).getroot().iter("DataSet")}
illumination = OpenDataFile(blocks["Illumination"])
patches = OpenDataFile(blocks["Patches"])
field = globals()["IlluminationField"](Input=illumination, Patches=patches)
field.Resolution = arguments.resolution
start = time.perf_counter()
field.UpdatePipeline()
print(f"{arguments.solution}: field of {field.GetDataInformation().GetNumberOfPoints()} vertices "
      f"built in {time.perf_counter() - start:.2f} s; SMP backend {vtkSMPTools.GetBackend()}, "
      f"{vtkSMPTools.GetEstimatedNumberOfThreads()} threads")

# The scene's first camera, carried by the illumination's field data.
camera = illumination.GetClientSideObject().GetOutputDataObject(0).GetFieldData().GetArray(
    "CameraParameters")
eye = [camera.GetComponent(0, c) for c in range(3)]
focal = [camera.GetComponent(0, 3 + c) for c in range(3)]
up = [camera.GetComponent(0, 6 + c) for c in range(3)]
angle = camera.GetComponent(0, 9)
bounds = patches.GetDataInformation().GetBounds()
centre = [(bounds[2 * c] + bounds[2 * c + 1]) / 2 for c in range(3)]
axis = [f - e for f, e in zip(focal, eye)]
length = math.sqrt(sum(a * a for a in axis))
axis = [a / length for a in axis]
ahead = sum((c - e) * a for c, e, a in zip(centre, eye, axis))
pivot = [e + max(ahead, length) * a for e, a in zip(eye, axis)] if ahead > 0 else focal


def orbit_eyes(count):
    """The eyes of the orbit: the first camera's eye turned about the view up through the pivot."""
    norm = math.sqrt(sum(u * u for u in up))
    k = [u / norm for u in up]
    r = [e - p for e, p in zip(eye, pivot)]
    eyes = []
    for frame in range(count):
        t = 2 * math.pi * frame / count
        cross = [k[1] * r[2] - k[2] * r[1], k[2] * r[0] - k[0] * r[2], k[0] * r[1] - k[1] * r[0]]
        dot = sum(a * b for a, b in zip(k, r))
        rotated = [r[c] * math.cos(t) + cross[c] * math.sin(t) + k[c] * dot * (1 - math.cos(t))
                   for c in range(3)]
        eyes.append([p + v for p, v in zip(pivot, rotated)])
    return eyes


eyes = orbit_eyes(arguments.frames)
view = CreateRenderView()
view.ViewSize = [width, height]
view.OrientationAxesVisibility = 0


def walk(representation):
    display = Show(field, view)
    if representation == "Surface":
        ColorBy(display, ("POINTS", "DisplayRGB"))
        display.MapScalars = 0
        display.Ambient = 1.0
        display.Diffuse = 0.0
    display.SetRepresentationType(representation)
    times = []
    for k, position in enumerate(eyes + eyes[:1]):
        view.CameraPosition = position
        view.CameraFocalPoint = pivot
        view.CameraViewUp = up
        view.CameraViewAngle = angle
        start = time.perf_counter()
        Render(view)
        times.append(time.perf_counter() - start)
    Hide(field, view)
    later = times[1:]
    mean = sum(later) / len(later)
    print(f"{representation}: first frame {1000 * times[0]:.0f} ms; frames 1-{len(later)}: mean "
          f"{1000 * mean:.1f} ms ({1 / mean:.2f} fps), min {1000 * min(later):.1f}, max "
          f"{1000 * max(later):.1f} ms at {width}x{height}")


walk("Surface")
walk("View-Dependent Radiance")

try:
    from sphericalcover import vtkViewDependentRadiance
except ImportError:
    vtkViewDependentRadiance = None
if vtkViewDependentRadiance:
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    data = vtkPolyData()
    data.DeepCopy(field.GetClientSideObject().GetOutputDataObject(0))
    evaluator = vtkViewDependentRadiance()
    start = time.perf_counter()
    evaluator.SetSolution(illumination.GetClientSideObject().GetOutputDataObject(0),
                          patches.GetClientSideObject().GetOutputDataObject(0))
    print(f"evaluation: solution built in {time.perf_counter() - start:.2f} s")
    seconds = []
    for k, position in enumerate(eyes):
        evaluator.Update(data, *position, 0.0)
        seconds.append(evaluator.GetLastUpdateSeconds())
        if k < 2:
            print(f"evaluation, eye {k}: {1000 * seconds[-1]:.0f} ms, "
                  f"{evaluator.GetLastEvaluatedVertices()} of {data.GetNumberOfPoints()} vertices")
    later = seconds[1:]
    print(f"evaluation, eyes 1-{len(later)}: mean {1000 * sum(later) / len(later):.1f} ms, "
          f"max {1000 * max(later):.1f} ms")

for created in GetViews():
    Delete(created)
