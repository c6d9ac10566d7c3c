"""`sphcover subdivide`: writes the patches and characteristic points as a multiblock file that
VTK reads back with the Documentation/Pipeline.md#interval-subdivision arrays; the same counts for 1 and 2 threads; --set overrides
the scene's settings; a bad setting or an unwritable output fails with one line and leaves no
file behind."""
import os
import subprocess
import sys
import tempfile

from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataReader

sphcover, data = sys.argv[1:3]
scene = f"{data}/scenes/cornell_box.scene"
failures = []
folder = tempfile.mkdtemp()


def run(*arguments):
    return subprocess.run([sphcover, *arguments], capture_output=True, text=True, timeout=300)


counts = {}
for threads in ["1", "2"]:
    output = os.path.join(folder, f"patches{threads}.vtm")
    result = run("subdivide", scene, "-o", output, "--set", "max_level=2", "--threads", threads, "--quiet")
    if result.returncode != 0:
        failures.append(f"subdivide failed: {result.stderr.strip()}")
        continue
    reader = vtkXMLMultiBlockDataReader()
    reader.SetFileName(output)
    reader.Update()
    blocks = reader.GetOutput()
    patches = blocks.GetBlock(0)
    points = blocks.GetBlock(1)
    if patches is None or points is None:
        failures.append("the .vtm lacks its two blocks")
        continue
    for name in ["SurfaceId", "PatchId", "Level", "UVRange", "Area", "SplitReason"]:
        if patches.GetCellData().GetArray(name) is None:
            failures.append(f"patches lack {name}")
    for name in ["Normals", "PatchId", "SurfaceId", "UV", "Area"]:
        if points.GetPointData().GetArray(name) is None:
            failures.append(f"characteristic points lack {name}")
    levels = patches.GetCellData().GetArray("Level").GetRange()
    if levels[1] > 2:
        failures.append(f"--set max_level=2 was ignored: level {levels[1]}")
    if points.GetNumberOfPoints() != patches.GetNumberOfCells():
        failures.append("one characteristic point per patch expected")
    counts[threads] = (patches.GetNumberOfCells(), result.stdout)
if len(counts) == 2 and counts["1"][0] != counts["2"][0]:
    failures.append(f"thread count changed the result: {counts['1'][0]} vs {counts['2'][0]}")
if "1" in counts and "pair tests:" not in counts["1"][1]:
    failures.append("no pair-test count reported")

bad = run("subdivide", scene, "-o", os.path.join(folder, "bad.vtm"), "--set", "tolerance=-1",
          "--quiet")
if bad.returncode == 0 or "tolerance" not in bad.stderr or len(bad.stderr.strip().splitlines()) != 1:
    failures.append(f"a bad --set did not fail with one line: {bad.stderr!r}")
unwritable = run("subdivide", scene, "-o", "/nonexistent/folder/x.vtm", "--quiet")
if unwritable.returncode == 0 or len(unwritable.stderr.strip().splitlines()) != 1:
    failures.append(f"an unwritable output did not fail with one line: {unwritable.stderr!r}")
leftovers = [name for name in os.listdir(folder) if name.startswith("bad") or name.startswith(".")]
if leftovers:
    failures.append(f"failed runs left files behind: {leftovers}")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
