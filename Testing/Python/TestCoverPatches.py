"""/usr/bin/python3: the rendering filters' optional Patches port (Filters/vtkCoverPatches.h) in
plain VTK, on the Cornell box at a coarse setting.
- vtkRadianceImageFilter and vtkIlluminationField with port 1 left unconnected give, bit for
  bit, what they give with the subdivision's patches connected (the patches the Spherical
  Cover upstream was built from);
- after the subdivision changes (MaxLevel 1 -> 2) the unconnected filters follow it: the field
  has the new patch count's quads;
- an illumination with no Spherical Cover upstream (a copy through a trivial producer, as a
  saved solution) and port 1 unconnected: one error naming the Patches port, empty output;
- the camera names the filter announces (GetCameraNames, ParaView's CameraName drop-down) are
  the scene's, after UpdateInformation alone;
- every stage names itself in the progress text ParaView's status bar shows
  (Filters/vtkStageProgress.h): "Interval Subdivision: subdividing", "Spherical Cover: cover",
  "Light Propagation: shooting", "Radiance Image: rendering", "Illumination Field:
  interpolating", and the pipeline's own 0 % and 100 % events the filter's label, never the
  class name;
- the scene's unit (Cornell box: "unit": "mm") reaches the illumination's field data
  (SceneUnit, SceneUnitMetres) and its EnergyBalance is in watts: the lamp's pi Le A with A in
  m^2, 0.79 W in red; the History's UnshotEnergy in the same watts.

usage: TestCoverPatches.py DATA_DIR"""
import sys

from sphericalcover import vtkIlluminationField, vtkRadianceImageFilter
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkCommonExecutionModel import vtkTrivialProducer

from coarse_cornell_pipeline import ErrorCollector, coarse_cornell_pipeline  # noqa: E402

data = sys.argv[1]
failures = []
collector = ErrorCollector()
errors = collector.messages
observe = collector.observe
reader, subdivision, cover, propagation = coarse_cornell_pipeline(data, collector)
texts = set()


def record_progress_text(algorithm):
    algorithm.AddObserver(vtkCommand.ProgressEvent,
                          lambda caller, event: texts.add(caller.GetProgressText() or
                                                          caller.GetClassName()))
    return algorithm


for stage in (subdivision, cover, propagation):
    record_progress_text(stage)


def renderer(connect_patches, producer=propagation):
    render = record_progress_text(observe(vtkRadianceImageFilter()))
    render.SetInputConnection(0, producer.GetOutputPort(0))
    if connect_patches:
        render.SetPatchesConnection(subdivision.GetOutputPort(0))
    render.SetWidth(48)
    render.SetHeight(36)
    return render


def field_of(connect_patches):
    field = record_progress_text(observe(vtkIlluminationField()))
    field.SetInputConnection(0, propagation.GetOutputPort(0))
    if connect_patches:
        field.SetPatchesConnection(subdivision.GetOutputPort(0))
    field.SetResolution(2)
    return field


def array(algorithm, name):
    algorithm.Update()
    values = algorithm.GetOutput().GetPointData().GetArray(name)
    return vtk_to_numpy(values).copy() if values else None


probe = renderer(False)
probe.UpdateInformation()
names = [probe.GetCameraNames().GetValue(k) for k in range(probe.GetCameraNames().GetNumberOfValues())]
if names != ["main"]:
    failures.append(f"GetCameraNames after UpdateInformation: {names}, expected ['main']")

for label, connected, unconnected, name in (
        ("Radiance Image", renderer(True), renderer(False), "Radiance"),
        ("Illumination Field", field_of(True), field_of(False), "Radiance")):
    want, got = array(connected, name), array(unconnected, name)
    if want is None or got is None or want.shape != got.shape or (want != got).any():
        failures.append(f"{label}: port 1 unconnected differs from the subdivision's patches")
    else:
        print(f"{label}: {len(got)} values, the same with port 1 unconnected")

field = field_of(False)
field.Update()
quads = field.GetOutput().GetNumberOfCells()
subdivision.SetMaxLevel(2)
field.Update()
patches = subdivision.GetOutput(0).GetNumberOfCells()
if field.GetOutput().GetNumberOfCells() != 4 * patches or field.GetOutput().GetNumberOfCells() <= quads:
    failures.append(f"Illumination Field after MaxLevel 2: {field.GetOutput().GetNumberOfCells()} "
                    f"quads for {patches} patches (was {quads})")

if errors:
    failures.append(f"errors on good input: {errors}")
stages = {"Interval Subdivision: subdividing", "Spherical Cover: cover",
          "Light Propagation: shooting", "Radiance Image: rendering",
          "Illumination Field: interpolating"}
named = {text.split(", about")[0] for text in texts}
if not stages <= named or any(text.startswith("vtk") for text in texts):
    failures.append(f"progress texts {sorted(texts)}: expected every stage of {sorted(stages)} "
                    "and no bare class name")
else:
    print("progress texts:", sorted(texts))
errors.clear()

# Units: the Cornell box is in mm; the powers are watts.
propagation.Update()
fd = propagation.GetOutput().GetFieldData()
unit, metres = fd.GetAbstractArray("SceneUnit"), fd.GetArray("SceneUnitMetres")
emitted = fd.GetArray("EnergyBalance").GetComponent(0, 0)
lamp_area_m2 = 0.130 * 0.105  # the Cornell light, 130 x 105 mm
expected = 3.141592653589793 * 18.387 * lamp_area_m2
history = propagation.GetOutputDataObject(1)
unshot = history.GetColumnByName("UnshotEnergy").GetValue(0) if history.GetNumberOfRows() else -1
if unit is None or unit.GetValue(0) != "mm" or metres is None or metres.GetValue(0) != 0.001:
    failures.append("the illumination lacks SceneUnit 'mm' and SceneUnitMetres 0.001")
elif abs(emitted / expected - 1) > 1e-3 or \
        not 0 < unshot <= sum(fd.GetArray("EnergyBalance").GetTuple3(0)):
    # UnshotEnergy sums the three bands; after the first shot it is below the total emitted.
    failures.append(f"EnergyBalance emitted {emitted} W (expected pi Le A = {expected} W), "
                    f"first unshot {unshot} W")
else:
    print(f"Cornell box in mm: emitted {emitted:.4f} W in red (pi Le A = {expected:.4f} W)")

# A solution with nothing upstream: the Patches must be given.
propagation.Update()
copy = vtkPolyData()
copy.DeepCopy(propagation.GetOutput())
producer = vtkTrivialProducer()
producer.SetOutput(copy)
alone = renderer(False, producer)
alone.Update()
if len(errors) != 1 or "Patches" not in errors[0] or \
        alone.GetOutput().GetNumberOfPoints() not in (0, 48 * 36) or \
        alone.GetOutput().GetPointData().GetArray("Radiance") is not None:
    failures.append(f"Radiance Image without patches: errors {errors}, "
                    f"{alone.GetOutput().GetNumberOfPoints()} points")
else:
    print("without a Spherical Cover upstream:", errors[0].strip())

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
