"""pvbatch --symmetric on every MPI rank: the Cornell box pipeline of the plug-in (reader ->
Interval Subdivision -> Spherical Cover -> Light Propagation, and the Hemisphere Extractor)
completes on 2 ranks, under the piece policy of Readers/vtkScenePieces.h:
- rank 0 (piece 0) holds the whole scene and computes; rank 1 (piece 1) holds empty outputs;
- the totals gathered over the ranks (points, cells, rows of every output port, both by an
  explicit MPI sum of the local pieces) equal those of the same pipeline run serially (plain
  VTK, no pieces); each rank's ParaView data information describes its piece; piece 0's
  illumination equals the serial one value for value;
- the light propagation ran on both ranks together (rank 0 dealing each rank its rows, each
  shooting into its own), not on rank 0 alone;
- with the cover's GatherRows off, each rank's cover output holds every point and only the rows
  of its own receivers (r, r + K, ...: CoverRowShare), the propagation runs on these shares, and
  rank 0's solution (the whole cover, Radiosity, IncidentRadiance) equals the serial one while
  rank 1's is empty; a FixedOrder propagation of the shares, one refused (MemoryLimit), or
  shares kept for another number of ranks, is one error on each rank;
- with the propagation's GatherSolution off (of the kept rows and of the gathered cover), each
  rank's solution is its piece: every point with the serial Radiosity, Irradiance and
  Brightness, only its own rows and their regions' serial IncidentRadiance, marked as its share,
  and on rank 0 the serial figures (form factors, means, statistics) bit for bit;
- the Radiance Image of the gathered solution, and of the pieces (GatherSolution off, rendered on
  the ranks that hold them), is the serial image on rank 0 and an empty image, without an
  error, on rank 1;
- a propagation refused (a MemoryLimit below a rank's share) is one error on each rank, and
  neither waits for the other; so is one that rank 0 aborts while it balances the exchange (the
  other rank waiting to be dealt its rows).
The launcher (RunParallelPvbatch.py) checks that every rank completed without a failure or an
error message."""
import os
import sys

from paraview import servermanager  # noqa: F401  (initialises the session)
from paraview.simple import LoadPlugin, OpenDataFile, OutputPort
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIntArray
from vtkmodules.vtkCommonDataModel import vtkFieldData, vtkPolyData
from vtkmodules.vtkParallelCore import vtkCommunicator, vtkMultiProcessController

plugin, data = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
from sphericalcover import (vtkHemisphereExtractor, vtkPLightPropagationFilter,  # noqa: E402
                            vtkRadianceImageFilter)

# The pipeline the Python.* tests share, in Testing/Python.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "Python"))
from coarse_cornell_pipeline import ErrorCollector, coarse_cornell_pipeline  # noqa: E402

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

# The same pipeline in plain VTK (no piece requests, every rank holding the whole scene, the
# distributed filters sharing the work as before the pieces): the reference totals.
serial_errors = ErrorCollector()
reader, serial_subdivision, serial_cover, serial_propagation = coarse_cornell_pipeline(
    data, serial_errors, distributed=True)
serial_hemisphere = vtkHemisphereExtractor()
serial_hemisphere.SetInputConnection(serial_cover.GetOutputPort(0))
serial_hemisphere.SetPointId(3)
serial_propagation.Update()
serial_hemisphere.Update()
failures += [f"serial reference: {message}" for message in serial_errors.messages]

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

# The propagation is shared: every rank shot into its own rows (vtkLightPropagationFilter's
# RankCount), the rows of rank 0's cover tiling the points.
shared_ranks = propagation.GetClientSideObject().GetRankCount()
if shared_ranks != ranks:
    failures.append(f"the propagation ran on {shared_ranks} rank(s), not on all {ranks}")


def errors_of(proxy):
    """Updates the proxy's pipeline and returns the errors its filter reported (caught, so that
    the launcher's check for error lines stays meaningful; the executive's failure notice too)."""
    errors = []
    algorithm = proxy.GetClientSideObject()
    algorithm.AddObserver("ErrorEvent",
                          calldata_type(VTK_STRING)(lambda caller, event, text: errors.append(text)))
    algorithm.GetExecutive().AddObserver(
        "ErrorEvent", calldata_type(VTK_STRING)(lambda caller, event, text: None))
    proxy.UpdatePipeline()
    if algorithm.GetOutputDataObject(0).GetNumberOfPoints() != 0:
        failures.append(f"{proxy.GetXMLName()} that failed has an output")
    return errors


# A refused propagation: each rank reports one error and returns.
refused = globals()["LightPropagation"](Input=OutputPort(cover, 0), MemoryLimit=0.001)
errors = errors_of(refused)
if len(errors) != 1 or "MemoryLimit" not in errors[0] or f"of {ranks})" not in errors[0]:
    failures.append(f"the refused propagation reported {errors}, not one MemoryLimit error "
                    "naming the rank")

# Rank 0 aborts while it balances the exchange (it alone holds the whole cover): every rank
# stops with the one error, none waits for rows that are never dealt.
aborted = globals()["LightPropagation"](Input=OutputPort(cover, 0))


def abort_while_balancing(algorithm, event):
    if rank == 0 and "balancing" in (algorithm.GetProgressText() or ""):
        algorithm.SetAbortExecute(1)


aborted.GetClientSideObject().AddObserver("ProgressEvent", abort_while_balancing)
errors = errors_of(aborted)
if len(errors) != 1 or "aborted" not in errors[0] or "(rank 0 of" not in errors[0]:
    failures.append(f"the propagation aborted on rank 0 reported {errors}, not one error naming "
                    "rank 0")

# GatherRows off: the rows stay on the ranks that built them, the propagation takes them there.
kept = globals()["SphericalCover"](Input=OutputPort(subdivision, 0), ThetaBins=8, PhiBins=32,
                                   GatherRows=0)
kept_propagation = globals()["LightPropagation"](Input=OutputPort(kept, 0))
kept_propagation.UpdatePipeline()
share = kept.GetClientSideObject().GetOutputDataObject(0)
serial_points = serial_cover.GetOutputDataObject(0)
marker = share.GetFieldData().GetArray("CoverRowShare")
if marker is None or (marker.GetComponent(0, 0), marker.GetComponent(0, 1)) != (rank, ranks):
    failures.append(f"the kept cover of rank {rank} is not marked as its share")
if share.GetNumberOfPoints() != serial_points.GetNumberOfPoints():
    failures.append(f"the kept cover of rank {rank} has {share.GetNumberOfPoints()} points, "
                    f"not all {serial_points.GetNumberOfPoints()}")
offsets = share.GetFieldData().GetArray("CoverRowOffsets")
serial_offsets = serial_points.GetFieldData().GetArray("CoverRowOffsets")
if offsets is None or offsets.GetNumberOfTuples() != serial_offsets.GetNumberOfTuples():
    failures.append(f"the kept cover of rank {rank} lacks one row offset per point")
else:
    mine = [offsets.GetValue(i + 1) - offsets.GetValue(i)
            for i in range(offsets.GetNumberOfTuples() - 1)]
    whole = [serial_offsets.GetValue(i + 1) - serial_offsets.GetValue(i)
             for i in range(serial_offsets.GetNumberOfTuples() - 1)]
    expected = [whole[i] if i % ranks == rank else 0 for i in range(len(whole))]
    if mine != expected:
        failures.append(f"rank {rank}'s kept rows are not the serial rows of its receivers")
solution = kept_propagation.GetClientSideObject().GetOutputDataObject(0)
if rank == 0:
    reference = serial_propagation.GetOutputDataObject(0)
    for name in ("Radiosity", "Irradiance"):
        a, b = solution.GetPointData().GetArray(name), reference.GetPointData().GetArray(name)
        if a is None or b is None or [a.GetValue(i) for i in range(a.GetNumberOfValues())] != \
                [b.GetValue(i) for i in range(b.GetNumberOfValues())]:
            failures.append(f"the solution of the kept rows: {name} differs from the serial one")
    for name in ("IncidentRadiance", "CoverRowOffsets", "CoverEntries", "CoverStrips"):
        a, b = solution.GetFieldData().GetArray(name), reference.GetFieldData().GetArray(name)
        if a is None or b is None or [a.GetValue(i) for i in range(a.GetNumberOfValues())] != \
                [b.GetValue(i) for i in range(b.GetNumberOfValues())]:
            failures.append(f"the solution of the kept rows: {name} differs from the serial one")
    if solution.GetFieldData().GetArray("CoverRowShare") is not None:
        failures.append("the solution of the kept rows still says it is a share")
elif solution.GetNumberOfPoints() != 0:
    failures.append(f"rank {rank} wrote a solution of the kept rows")
refused = globals()["LightPropagation"](Input=OutputPort(kept, 0), MemoryLimit=0.001)
errors = errors_of(refused)
if len(errors) != 1 or "MemoryLimit" not in errors[0] or f"of {ranks})" not in errors[0]:
    failures.append(f"the refused propagation of the kept rows reported {errors}, not one "
                    "MemoryLimit error naming the rank")
# Shares kept for another number of ranks (the marker altered to 3 ranks): one error on each
# rank, naming the share it holds, and no solution.
foreign = vtkPolyData()
foreign.ShallowCopy(share)
foreign_fields = vtkFieldData()
foreign_fields.ShallowCopy(share.GetFieldData())
foreign_marker = vtkIntArray()
foreign_marker.SetName("CoverRowShare")
foreign_marker.SetNumberOfComponents(2)
foreign_marker.InsertNextTuple2(rank, 3)
foreign_fields.AddArray(foreign_marker)
foreign.SetFieldData(foreign_fields)
mismatched = vtkPLightPropagationFilter()
mismatched.SetInputData(foreign)
errors = []
mismatched.AddObserver("ErrorEvent",
                       calldata_type(VTK_STRING)(lambda caller, event, text: errors.append(text)))
mismatched.GetExecutive().AddObserver(
    "ErrorEvent", calldata_type(VTK_STRING)(lambda caller, event, text: None))
mismatched.Update()
if len(errors) != 1 or "rank 0 of 3's share" not in errors[0] or f"of {ranks})" not in errors[0]:
    failures.append(f"shares kept for 3 ranks reported {errors}, not one error naming them")
if mismatched.GetOutput().GetNumberOfPoints() != 0:
    failures.append("shares kept for 3 ranks gave a solution")
fixed_order = globals()["LightPropagation"](Input=OutputPort(kept, 0), ShootingOrder="Fixed Order")
errors = errors_of(fixed_order)
if len(errors) != 1 or "GatherRows" not in errors[0]:
    failures.append(f"FixedOrder on the kept rows reported {errors}, not one error about them")

# The Radiance Image of the gathered solution: rank 0 renders the serial image, value for
# value; the other rank's piece is an empty image without an error (the launcher fails on one).
image = globals()["RadianceImage"](Input=OutputPort(propagation, 0), Width=32, Height=24,
                                   SamplesPerPixel=1)
image.UpdatePipeline()
rendered = image.GetClientSideObject().GetOutputDataObject(0)
serial_image = vtkRadianceImageFilter()
serial_image.SetInputConnection(0, serial_propagation.GetOutputPort(0))
serial_image.SetPatchesConnection(serial_subdivision.GetOutputPort(0))
serial_image.SetWidth(32)
serial_image.SetHeight(24)
serial_image.SetSamplesPerPixel(1)
serial_image.Update()
if rank == 0:
    radiance = rendered.GetPointData().GetArray("Radiance")
    serial_radiance = serial_image.GetOutput().GetPointData().GetArray("Radiance")
    if radiance is None or [radiance.GetValue(i) for i in range(radiance.GetNumberOfValues())] \
            != [serial_radiance.GetValue(i) for i in range(serial_radiance.GetNumberOfValues())]:
        failures.append("the Radiance Image on rank 0 is not the serial image")
elif rendered.GetNumberOfPoints() != 0:
    failures.append(f"rank {rank} rendered an image of its empty piece")

# GatherSolution off: every rank keeps its piece of the solution, of the kept rows (each rank's
# share as it is) and of the gathered cover (rank 0 deals the rows, each rank stores its own):
# every point with the serial per-point values, only its own rows and their regions' serial
# incident radiance, marked as its share; rank 0's piece alone carries the serial figures.
reference = serial_propagation.GetOutputDataObject(0)


def values(array):
    return None if array is None else [array.GetValue(i) for i in range(array.GetNumberOfValues())]


whole_offsets = values(reference.GetFieldData().GetArray("CoverRowOffsets"))
whole_incident = values(reference.GetFieldData().GetArray("IncidentRadiance"))
own_incident = []
for i in range(rank, len(whole_offsets) - 1, ranks):
    own_incident += whole_incident[3 * whole_offsets[i]:3 * whole_offsets[i + 1]]
for label, source in [("kept rows", kept), ("gathered cover", cover)]:
    kept_apart = globals()["LightPropagation"](Input=OutputPort(source, 0), GatherSolution=0)
    kept_apart.UpdatePipeline()
    piece = kept_apart.GetClientSideObject().GetOutputDataObject(0)
    fields = piece.GetFieldData()
    marker = fields.GetArray("CoverRowShare")
    if marker is None or (marker.GetComponent(0, 0), marker.GetComponent(0, 1)) != (rank, ranks):
        failures.append(f"the solution of the {label} in pieces: rank {rank}'s is not marked as "
                        "its share")
    for name in ("Radiosity", "Irradiance", "Brightness"):
        if values(piece.GetPointData().GetArray(name)) != \
                values(reference.GetPointData().GetArray(name)):
            failures.append(f"the solution of the {label} in pieces: rank {rank}'s {name} is "
                            "not the serial one")
    offsets = values(fields.GetArray("CoverRowOffsets"))
    lengths = None if offsets is None else [b - a for a, b in zip(offsets, offsets[1:])]
    expected = [b - a if i % ranks == rank else 0
                for i, (a, b) in enumerate(zip(whole_offsets, whole_offsets[1:]))]
    if lengths != expected:
        failures.append(f"the solution of the {label} in pieces: rank {rank}'s rows are not the "
                        "serial rows of its receivers")
    if values(fields.GetArray("IncidentRadiance")) != own_incident:
        failures.append(f"the solution of the {label} in pieces: rank {rank}'s IncidentRadiance "
                        "is not the serial radiance of its rows' regions")
    figures = ("SurfaceFormFactorPairs", "SurfaceFormFactorValues", "SurfaceMeanExitantRadiance",
               "SurfaceArea", "SolutionStatistics")
    if rank == 0 and any(values(fields.GetArray(name)) != values(
            reference.GetFieldData().GetArray(name)) for name in figures):
        failures.append(f"the solution of the {label} in pieces: rank 0's figures are not the "
                        "serial ones bit for bit")
    if rank != 0 and fields.GetArray("SurfaceFormFactorValues") is not None:
        failures.append(f"the solution of the {label} in pieces: rank {rank} sums up figures")

# The Radiance Image renders the pieces on the ranks that hold them (vtkPRadianceImageFilter):
# rank 0's image is the serial one value for value, rank 1's empty, without an error. (The
# directional part's exchange is checked on the mixed box by ParaView.PluginParallelPieces.)
piece_image = globals()["RadianceImage"](Input=OutputPort(kept_apart, 0), Width=32, Height=24,
                                         SamplesPerPixel=1)
piece_image.UpdatePipeline()
rendered = piece_image.GetClientSideObject().GetOutputDataObject(0)
if rank == 0 and values(rendered.GetPointData().GetArray("Radiance")) != \
        values(serial_image.GetOutput().GetPointData().GetArray("Radiance")):
    failures.append("the Radiance Image of the pieces on rank 0 is not the serial image")
elif rank != 0 and rendered.GetNumberOfPoints() != 0:
    failures.append(f"rank {rank} rendered an image of its piece")

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
