"""pvbatch --symmetric on 2 MPI ranks: a solution kept in pieces rendered by ParaView on the ranks
that hold them, as `sphcover render` renders them under mpiexec. The mixed box (a glossy back
wall and mirror blocks, so that the image reads the directional part of rows held by both ranks)
through the plug-in's proxies: Spherical Cover with GatherRows off (each rank builds and keeps
its rows), Light Propagation with GatherSolution off (each rank keeps its piece), Radiance Image
(vtkPRadianceImageFilter: rank 0 traces, each rank evaluates its own points' directional values).
- rank 0's image equals the serial image of the same pipeline in plain VTK, value for value;
- rank 1's image is empty, and no rank reports an error (the launcher checks).
The launcher (RunParallelPvbatch.py) checks that every rank completed without a failure or an
error message."""
import sys

from paraview import servermanager  # noqa: F401  (initialises the session)
from paraview.simple import LoadPlugin, OpenDataFile, OutputPort
from vtkmodules.vtkCommonCore import vtkDoubleArray
from vtkmodules.vtkParallelCore import vtkCommunicator, vtkMultiProcessController

plugin, data = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
from sphericalcover import (vtkIntervalSubdivisionFilter, vtkLightPropagationFilter,  # noqa: E402
                            vtkPatchSceneReader, vtkRadianceImageFilter, vtkSphericalCoverFilter)

controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId()
ranks = controller.GetNumberOfProcesses()
failures = []
if ranks != 2:
    failures.append(f"expected 2 MPI ranks, pvbatch runs on {ranks}")

SCENE = f"{data}/scenes/mixed_box.scene"
SIZE = dict(Width=32, Height=24, SamplesPerPixel=1)


def values(array):
    return None if array is None else [array.GetValue(i) for i in range(array.GetNumberOfValues())]


scene = OpenDataFile(SCENE)
subdivision = globals()["IntervalSubdivision"](Input=scene, MaxLevel=1)
cover = globals()["SphericalCover"](Input=OutputPort(subdivision, 0), ThetaBins=8, PhiBins=32,
                                    GatherRows=0)
propagation = globals()["LightPropagation"](Input=OutputPort(cover, 0), GatherSolution=0)
image = globals()["RadianceImage"](Input=OutputPort(propagation, 0), **SIZE)
image.UpdatePipeline()
rendered = image.GetClientSideObject().GetOutputDataObject(0)
piece = propagation.GetClientSideObject().GetOutputDataObject(0)
marker = piece.GetFieldData().GetArray("CoverRowShare")
if marker is None or (marker.GetComponent(0, 0), marker.GetComponent(0, 1)) != (rank, ranks):
    failures.append(f"rank {rank}'s solution is not its piece of a solution kept in pieces")

# The same pipeline in plain VTK, serial filters on each rank alone: the reference image.
reader = vtkPatchSceneReader()
reader.SetFileName(SCENE)
serial_subdivision = vtkIntervalSubdivisionFilter()
serial_subdivision.SetInputConnection(reader.GetOutputPort())
serial_subdivision.SetMaxLevel(1)
serial_cover = vtkSphericalCoverFilter()
serial_cover.SetInputConnection(serial_subdivision.GetOutputPort(0))
serial_cover.SetThetaBins(8)
serial_cover.SetPhiBins(32)
serial_propagation = vtkLightPropagationFilter()
serial_propagation.SetInputConnection(serial_cover.GetOutputPort(0))
serial_image = vtkRadianceImageFilter()
serial_image.SetInputConnection(0, serial_propagation.GetOutputPort(0))
serial_image.SetPatchesConnection(serial_subdivision.GetOutputPort(0))
serial_image.SetWidth(SIZE["Width"])
serial_image.SetHeight(SIZE["Height"])
serial_image.SetSamplesPerPixel(SIZE["SamplesPerPixel"])
serial_image.Update()
reference = values(serial_image.GetOutput().GetPointData().GetArray("Radiance"))
if not reference:
    failures.append("the serial image is empty")

if rank == 0:
    if values(rendered.GetPointData().GetArray("Radiance")) != reference:
        failures.append("the image of the pieces on rank 0 is not the serial image")
elif rendered.GetNumberOfPoints() != 0:
    failures.append(f"rank {rank} rendered an image of its piece")

for failure in failures:
    print(f"FAILED (rank {rank}):", failure)
status = vtkDoubleArray()
status.InsertNextValue(len(failures))
all_status = vtkDoubleArray()
controller.AllReduce(status, all_status, vtkCommunicator.SUM_OP)
# No sys.exit under mpiexec (it would skip MPI_Finalize); the launcher reads the verdict.
if all_status.GetValue(0) == 0:
    print(f"rank {rank} of {ranks}: pipeline completed")
