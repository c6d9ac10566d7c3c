"""`sphcover solve`: the report of SPEC §5 (surfaces, form factors, counts, timings) from the
spherical cover, checked against Howell's closed form C-11 for the parallel opposed rectangles
of Data/scenes/howell_parallel.scene (dimensions read from the scene, not assumed), reciprocity
for the perpendicular configuration, the solution file read back by VTK, and a clean failure."""
import json
import math
import os
import subprocess
import sys
import tempfile

from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataReader

sphcover, data = sys.argv[1:3]
failures = []
folder = tempfile.mkdtemp()


def solve(scene, *extra):
    report = os.path.join(folder, os.path.basename(scene) + ".json")
    result = subprocess.run([sphcover, "solve", scene, "--report", report, "--quiet", *extra],
                            capture_output=True, text=True, timeout=600)
    if result.returncode != 0:
        failures.append(f"solve {scene} failed: {result.stderr.strip()}")
        return None
    return json.load(open(report))


def parallel_rectangles(a, b, c):
    """Howell C-11: equal parallel coaxial rectangles a x b at distance c."""
    x, y = a / c, b / c
    return 2 / (math.pi * x * y) * (
        math.log(math.sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y)))
        + x * math.sqrt(1 + y * y) * math.atan(x / math.sqrt(1 + y * y))
        + y * math.sqrt(1 + x * x) * math.atan(y / math.sqrt(1 + x * x))
        - x * math.atan(x) - y * math.atan(y))


def distance(p, q):
    return math.dist(p, q)


scene_file = f"{data}/scenes/howell_parallel.scene"
scene = json.load(open(scene_file))
first, second = scene["surfaces"][0]["points"], scene["surfaces"][1]["points"]
a, b = distance(first[0], first[1]), distance(first[1], first[2])
# The separation: the distance from B's corner to A's plane (A's unit normal from two edges).
u = [first[1][k] - first[0][k] for k in range(3)]
v = [first[3][k] - first[0][k] for k in range(3)]
n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
length = math.sqrt(sum(x * x for x in n))
c = abs(sum(n[k] * (second[0][k] - first[0][k]) for k in range(3))) / length
expected = parallel_rectangles(a, b, c)

report = solve(scene_file)
if report:
    for key in ["surfaces", "form_factors", "counts", "timings_s"]:
        if key not in report:
            failures.append(f"report lacks {key}")
    names = report["form_factors"]["names"]
    matrix = report["form_factors"]["matrix"]
    got = matrix[names.index("A")][names.index("B")]
    error = (got - expected) / expected
    print(f"parallel rectangles {a} x {b} at {c}: F_AB = {got:.6f}, Howell C-11 {expected:.6f}, error {100 * error:+.3f}%")
    if abs(error) > 0.005:
        failures.append(f"F_AB off by {100 * error:.3f}% (more than 0.5%)")
    areas = {s["name"]: s["area"] for s in report["surfaces"]}
    if abs(areas["A"] - a * b) > 1e-9 * a * b:
        failures.append(f"area of A {areas['A']} != {a * b}")
    for key in ["surfaces", "patches", "characteristic_points", "strips"]:
        if report["counts"].get(key, 0) <= 0:
            failures.append(f"count {key} missing or zero")

perpendicular = solve(f"{data}/scenes/howell_perpendicular.scene", "-o", os.path.join(folder, "solution.vtm"))
if perpendicular:
    names = perpendicular["form_factors"]["names"]
    matrix = perpendicular["form_factors"]["matrix"]
    areas = {s["name"]: s["area"] for s in perpendicular["surfaces"]}
    i, j = names.index("A"), names.index("B")
    ab, ba = areas["A"] * matrix[i][j], areas["B"] * matrix[j][i]
    print(f"perpendicular rectangles: A F_AB = {ab:.6f}, A F_BA = {ba:.6f}")
    if abs(ab - ba) > 0.01 * max(ab, ba):
        failures.append(f"reciprocity off by more than 1%: {ab} vs {ba}")
    reader = vtkXMLMultiBlockDataReader()
    reader.SetFileName(os.path.join(folder, "solution.vtm"))
    reader.Update()
    cover = reader.GetOutput().GetBlock(1)
    if cover is None or cover.GetFieldData().GetArray("CoverStrips") is None:
        failures.append("the solution file lacks the cover")

bad = subprocess.run([sphcover, "solve", f"{data}/../Testing/Data/bad/unknown_material.scene", "--report",
                      os.path.join(folder, "bad.json")], capture_output=True, text=True, timeout=60)
if bad.returncode == 0 or len(bad.stderr.strip().splitlines()) != 1 or os.path.exists(os.path.join(folder, "bad.json")):
    failures.append(f"a bad scene did not fail cleanly: {bad.stderr!r}")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
