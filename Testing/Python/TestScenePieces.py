"""/usr/bin/python3: the piece policy of Readers/vtkScenePieces.h in plain VTK, piece by piece.
- the scene reader gives the whole scene to piece 0 of 2 and an empty grid to piece 1;
- every filter asked for piece 1 of 2 of the reader's pipeline gives empty outputs and no
  error (the idle ranks of an MPI run), piece 0 of 2 the same outputs as a serial update;
- a filter asked for piece 1 of 2 of a whole scene (a producer that ignores pieces) refuses
  with an error naming the piece; an empty scene on piece 0 is still an error.

usage: TestScenePieces.py DATA_DIR"""
import sys

from sphericalcover import vtkHemisphereExtractor, vtkIntervalSubdivisionFilter
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
from vtkmodules.vtkCommonExecutionModel import vtkTrivialProducer

from coarse_cornell_pipeline import ErrorCollector, coarse_cornell_pipeline  # noqa: E402

data = sys.argv[1]
failures = []
collector = ErrorCollector()
errors = collector.messages
observe = collector.observe
reader, subdivision, cover, propagation = coarse_cornell_pipeline(data, collector)
hemisphere = observe(vtkHemisphereExtractor())
hemisphere.SetInputConnection(cover.GetOutputPort(0))
STAGES = [("reader", reader, 1), ("subdivision", subdivision, 2), ("cover", cover, 2),
          ("propagation", propagation, 2), ("hemisphere", hemisphere, 2)]


def sizes():
    found = []
    for name, algorithm, ports in STAGES:
        for port in range(ports):
            output = algorithm.GetOutputDataObject(port)
            found.append(output.GetNumberOfRows() if output.IsA("vtkTable")
                         else output.GetNumberOfPoints())
    return found


for name, algorithm, ports in STAGES:
    if not algorithm.UpdatePiece(1, 2, 0):
        failures.append(f"{name}: piece 1 of 2 failed")
if any(sizes()):
    failures.append(f"piece 1 of 2 is not empty: {sizes()}")
if errors:
    failures.append(f"piece 1 of 2 reported errors: {errors}")

for name, algorithm, ports in STAGES:
    algorithm.UpdatePiece(0, 2, 0)
piece_zero = sizes()
for name, algorithm, ports in STAGES:
    algorithm.UpdatePiece(0, 1, 0)
serial = sizes()
if piece_zero != serial or not all(serial):
    failures.append(f"piece 0 of 2 {piece_zero} differs from the serial update {serial}")
if errors:
    failures.append(f"the full updates reported errors: {errors}")

# A producer that hands its whole dataset to every piece: piece 1 holds part of a scene.
reader.Update()
whole = vtkTrivialProducer()
whole.SetOutput(reader.GetOutput())
partial = observe(vtkIntervalSubdivisionFilter())
partial.SetInputConnection(whole.GetOutputPort())
del errors[:]
if partial.UpdatePiece(1, 2, 0) or partial.GetOutput().GetNumberOfCells():
    failures.append("piece 1 of 2 of a whole scene was subdivided")
if len(errors) != 1 or "piece 1 of 2" not in errors[0]:
    failures.append(f"piece 1 of 2 of a whole scene: expected one error naming the piece, {errors}")

empty = vtkTrivialProducer()
empty.SetOutput(vtkUnstructuredGrid())
serial_empty = observe(vtkIntervalSubdivisionFilter())
serial_empty.SetInputConnection(empty.GetOutputPort())
del errors[:]
serial_empty.Update()
if len(errors) != 1 or "no surfaces" not in errors[0]:
    failures.append(f"an empty scene in serial: expected one error, {errors}")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
