"""pvbatch --symmetric on every MPI rank: the Cornell box pipeline of the plug-in (reader ->
Interval Subdivision -> Spherical Cover -> Light Propagation, and the Hemisphere Extractor)
completes on 2 ranks, under the piece policy of Readers/vtkScenePieces.h:
- rank 0 (piece 0) holds the whole scene and computes; rank 1 (piece 1) holds empty outputs;
- the totals gathered over the ranks (points, cells, rows of every output port, both by an
  explicit MPI sum of the local pieces) equal those of the same pipeline run serially (plain
  VTK, no pieces); each rank's ParaView data information describes its piece; piece 0's
  illumination equals the serial one value for value.
The launcher (RunParallelPvbatch.py) checks that every rank completed without a failure or an
error message."""
import sys

from paraview import servermanager  # noqa: F401  (initialises the session)
from paraview.simple import LoadPlugin, OpenDataFile, OutputPort
from vtkmodules.vtkCommonCore import vtkDoubleArray
from vtkmodules.vtkParallelCore import vtkCommunicator, vtkMultiProcessController

plugin, data = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
from sphericalcover import (vtkHemisphereExtractor, vtkIntervalSubdivisionFilter,  # noqa: E402
                            vtkLightPropagationFilter, vtkPatchSceneReader, vtkSphericalCoverFilter)

controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId()
ranks = controller.GetNumberOfProcesses()
failures = []
if ranks != 2:
    failures.append(f"expected 2 MPI ranks, pvbatch runs on {ranks}")

SCENE = f"{data}/scenes/cornell_box.scene"
scene = OpenDataFile(SCENE)
subdivision = globals()["IntervalSubdivision"](Input=scene, MaxLevel=1)
cover = globals()["SphericalCover"](Input=OutputPort(subdivision, 0), ThetaBins=8, PhiBins=32)
propagation = globals()["LightPropagation"](Input=OutputPort(cover, 0))
hemisphere = globals()["HemisphereExtractor"](Input=OutputPort(cover, 0), PointId=3)
for proxy in (propagation, hemisphere):
    proxy.UpdatePipeline()

# The same pipeline serially in plain VTK (no piece requests): the reference totals.
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
serial_hemisphere = vtkHemisphereExtractor()
serial_hemisphere.SetInputConnection(serial_cover.GetOutputPort(0))
serial_hemisphere.SetPointId(3)
serial_propagation.Update()
serial_hemisphere.Update()

STAGES = [("reader", scene, reader, 0), ("patches", subdivision, serial_subdivision, 0),
          ("characteristic points", subdivision, serial_subdivision, 1),
          ("cover points", cover, serial_cover, 0), ("strips", cover, serial_cover, 1),
          ("illumination", propagation, serial_propagation, 0),
          ("history", propagation, serial_propagation, 1),
          ("hemisphere image", hemisphere, serial_hemisphere, 0),
          ("hemisphere mesh", hemisphere, serial_hemisphere, 1)]


def size(data_object):
    """(points, cells) of a dataset, (rows, columns) of a table."""
    if data_object.IsA("vtkTable"):
        return data_object.GetNumberOfRows(), data_object.GetNumberOfColumns()
    return data_object.GetNumberOfPoints(), data_object.GetNumberOfCells()


local = vtkDoubleArray()
for name, proxy, native, port in STAGES:
    for value in size(proxy.GetClientSideObject().GetOutputDataObject(port)):
        local.InsertNextValue(value)
gathered = vtkDoubleArray()
controller.AllReduce(local, gathered, vtkCommunicator.SUM_OP)

for k, (name, proxy, native, port) in enumerate(STAGES):
    serial = size(native.GetOutputDataObject(port))
    total = (int(gathered.GetValue(2 * k)), int(gathered.GetValue(2 * k + 1)))
    piece = size(proxy.GetClientSideObject().GetOutputDataObject(port))
    if serial[0] == 0:
        failures.append(f"{name}: the serial pipeline produced nothing")
    if total != serial:
        failures.append(f"{name}: gathered over the ranks {total}, serial {serial}")
    if rank > 0 and piece[0] != 0:
        failures.append(f"{name}: piece {rank} is not empty {piece}")
    # Under --symmetric each rank's session describes its own piece.
    info = proxy.GetDataInformation(port)
    counted = ((info.GetNumberOfRows(), piece[1]) if info.GetDataClassName() == "vtkTable"
               else (info.GetNumberOfPoints(), info.GetNumberOfCells()))
    if counted != piece:
        failures.append(f"{name}: ParaView's data information {counted}, piece {rank} {piece}")

if rank == 0:
    # Piece 0 is the whole solution: its radiosity equals the serial one, value for value.
    lit = propagation.GetClientSideObject().GetOutputDataObject(0).GetPointData().GetArray(
        "Radiosity")
    reference = serial_propagation.GetOutputDataObject(0).GetPointData().GetArray("Radiosity")
    if lit is None or reference is None:
        failures.append("the illumination lacks Radiosity")
    elif [lit.GetValue(i) for i in range(lit.GetNumberOfValues())] != \
            [reference.GetValue(i) for i in range(reference.GetNumberOfValues())]:
        failures.append("piece 0's Radiosity differs from the serial solution")

for failure in failures:
    print(f"FAILED (rank {rank}):", failure)
status = vtkDoubleArray()
status.InsertNextValue(len(failures))
all_status = vtkDoubleArray()
controller.AllReduce(status, all_status, vtkCommunicator.SUM_OP)
# No sys.exit: under mpiexec it would skip MPI_Finalize, which Open MPI reports as an abort. The
# launcher reads the verdict from the output instead.
if all_status.GetValue(0) == 0:
    print(f"rank {rank} of {ranks}: pipeline completed")
