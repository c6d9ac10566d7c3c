"""pvbatch: a filter of the plug-in given the wrong input reports one clear error in ParaView's
output messages (the vtkOutputWindow that the GUI's Output Messages panel shows), naming the
filter and the problem, and leaves its outputs empty; nothing crashes and a correct update of
the same proxy afterwards works.

Wrong inputs: Light Propagation fed the reader's raw surfaces (an unstructured grid where cover
points are needed) and the subdivision's characteristic points (no cover); Spherical Cover fed
the characteristic points (vertices, not patches); Interval Subdivision fed them too; Hemisphere
Extractor fed the reader's surfaces (no cover)."""
import sys

from paraview.simple import LoadPlugin, OutputPort
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow

plugin, data = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())

failures = []
# pvbatch routes Python's print through the output window too: the original one is put back
# before reporting.
original_window = vtkOutputWindow.GetInstance()


def capture():
    """A fresh string output window in place of ParaView's: the messages from now on."""
    window = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(window)
    return window


scene = globals()["PatchSceneReader"](FileName=f"{data}/scenes/cornell_box.scene")
subdivision = globals()["IntervalSubdivision"](Input=scene, MaxLevel=1)
characteristic_points = OutputPort(subdivision, 1)

# (label, filter, wrong input, the expected words of the error, a correct input).
CASES = [
    ("LightPropagation fed raw surfaces", "LightPropagation", scene,
     ["vtkLightPropagationFilter", "vtkUnstructuredGrid", "vtkPolyData"], None),
    ("LightPropagation fed characteristic points", "LightPropagation", characteristic_points,
     ["vtkLightPropagationFilter", "Cannot propagate light"], None),
    ("SphericalCover fed characteristic points", "SphericalCover", characteristic_points,
     ["vtkSphericalCoverFilter", "Cannot build a spherical cover"], OutputPort(subdivision, 0)),
    ("IntervalSubdivision fed characteristic points", "IntervalSubdivision", characteristic_points,
     ["vtkIntervalSubdivisionFilter", "Cannot subdivide"], scene),
    ("HemisphereExtractor fed raw surfaces", "HemisphereExtractor", scene,
     ["vtkHemisphereExtractor", "Cannot extract a hemisphere"], None),
]


def check(label, name, wrong, words, right):
    messages = capture()
    proxy = globals()[name](Input=wrong)
    if name == "SphericalCover":
        proxy.ThetaBins, proxy.PhiBins = 8, 32
    proxy.UpdatePipeline()
    text = messages.GetOutput()
    # The executive follows a filter's own error with "returned failure for request"; apart
    # from that, one message states the problem.
    errors = [m for m in text.split("ERROR")[1:] if "returned failure for request" not in m]
    if len(errors) != 1:
        failures.append(f"{label}: {len(errors)} errors in the output messages, expected one: "
                        f"{text.strip()[:600]}")
    for word in words:
        if word not in text:
            failures.append(f"{label}: the error does not mention {word!r}: {text.strip()[:400]}")
    for port in range(proxy.SMProxy.GetNumberOfOutputPorts()):
        info = proxy.GetDataInformation(port)
        if info.GetNumberOfPoints() or info.GetNumberOfCells() or info.GetNumberOfRows():
            failures.append(f"{label}: output port {port} is not empty")
    if right is not None:
        # The same proxy given the right input recovers.
        messages = capture()
        proxy.Input = right
        proxy.UpdatePipeline()
        if "ERROR" in messages.GetOutput():
            failures.append(f"{label}: still failing with the right input: "
                            f"{messages.GetOutput().strip()[:400]}")
        if proxy.GetDataInformation(0).GetNumberOfPoints() == 0:
            failures.append(f"{label}: empty output with the right input")


try:
    for case in CASES:
        check(*case)
finally:
    vtkOutputWindow.SetInstance(original_window)
for failure in failures:
    print("FAILED:", failure)
print(f"{len(CASES)} wrong inputs reported")
sys.exit(1 if failures else 0)
