"""`sphcover render` (README.md#command-line, paper §5.3): the Cornell box rendered to PNG through the scene's
camera at a small size (read back by VTK: the size asked for, the lamp the brightest pixel, the
red wall red and the green wall green); the report's timings include the render, its stages'
processor seconds add up to no more than the process's, and its cover holds at least the 10
bytes per strip of its storage (Core/cover/SphericalCover.h); a solution
saved by `sphcover solve -o` and rendered with --solution gives the identical image (the
walk-through case: only the render runs, and its report has the same figures); the image does
not depend on the thread count; the report's figures are those the light propagation filter
puts in its output's field data, and the reader's scene fingerprint reaches it and the saved
solution; light behind more panes than are followed (pane_stack.scene) is counted in the
report's pane_limit and said in one warning line per stage; bad input (a corrupted saved solution
too) gives one line, a non-zero exit and no output file."""
import json
import os
import resource
import subprocess
import sys
import tempfile

from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataReader, vtkXMLMultiBlockDataWriter

sphcover, data = sys.argv[1:3]
failures = []
folder = tempfile.mkdtemp()
scene = f"{data}/scenes/cornell_box.scene"
# Coarse settings keep the test in seconds; the image checks below hold at any setting.
coarse = ["--set", "max_level=1", "--set", "theta_bins=16", "--set", "phi_bins=64"]


def run(*arguments):
    return subprocess.run([sphcover, *arguments], capture_output=True, text=True, timeout=600)


def pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    values = [scalars.GetTuple3(k) for k in range(scalars.GetNumberOfTuples())]
    return image.GetDimensions(), values


first = os.path.join(folder, "first.png")
report_file = os.path.join(folder, "report.json")
before = resource.getrusage(resource.RUSAGE_CHILDREN)
result = run("render", scene, "-o", first, "--size", "64x48", "--report", report_file, "--quiet",
             *coarse)
after = resource.getrusage(resource.RUSAGE_CHILDREN)
process_cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
if result.returncode != 0:
    failures.append(f"render failed: {result.stderr.strip()}")
else:
    dimensions, values = pixels(first)
    if dimensions != (64, 48, 1):
        failures.append(f"the PNG is {dimensions}, not 64 x 48")
    # The lamp (emission 18, 11, 2.8) saturates; the walls are darker.
    brightest = max(range(len(values)), key=lambda k: sum(values[k]))
    if values[brightest] != (255.0, 255.0, 255.0) or brightest < len(values) * 3 // 4:
        failures.append(f"the brightest pixel {values[brightest]} at {brightest} is not the lamp "
                        "near the top")
    # Row 24 (the middle): the red wall at the left, the green wall at the right (the square
    # camera's view in a 4:3 frame leaves dark margins at the sides).
    left = values[24 * 64 + 14]
    right = values[24 * 64 + 50]
    if not (left[0] > 3 * left[1] and right[1] > 1.2 * right[0] and right[1] > 3 * right[2]):
        failures.append(f"the left wall {left} is not red or the right wall {right} not green")
    report = json.load(open(report_file))
    timings = report.get("timings_s", {})
    for key in ["read", "subdivide", "cover", "propagate", "render"]:
        if not timings.get(key, -1) >= 0:
            failures.append(f"report timings_s lacks {key}")
    cpu = report.get("timings_cpu_s", {})
    for key in ["read", "subdivide", "cover", "propagate", "render"]:
        if not cpu.get(key, -1) >= 0:
            failures.append(f"report timings_cpu_s lacks {key}")
    # Each stage's processor seconds are a part of the process's (the kernel's accounting of
    # the child, sampled to within a clock tick per thread).
    stages_cpu = sum(cpu.get(key, 0) for key in ["read", "subdivide", "cover", "propagate",
                                                  "render"])
    if stages_cpu > 1.02 * process_cpu + 0.05:
        failures.append(f"the stages' processor seconds {stages_cpu:.3f} exceed the process's "
                        f"{process_cpu:.3f}")
    strips = report.get("counts", {}).get("strips", 0)
    cover_bytes = report.get("memory_bytes", {}).get("cover", 0)
    if not strips > 0 or cover_bytes < 10 * strips:
        failures.append(f"memory_bytes.cover {cover_bytes} is less than 10 bytes for each of the "
                        f"{strips} strips")
    if len(report.get("surfaces", [])) != 16:
        failures.append("the report lacks the 16 surfaces")
    # No pane: nothing left out behind the panes' limit, and the report says so.
    limit = report.get("pane_limit", {})
    if limit.get("cover_cells") != 0 or limit.get("direct_light_rays") != 0 or \
            limit.get("render_samples") != 0:
        failures.append(f"the Cornell box's report has pane_limit {limit}, not zeros")

# Reuse a saved solution: only the render runs, and the image is identical.
solution = os.path.join(folder, "solution.vtm")
reused_report = os.path.join(folder, "reused.json")
result = run("solve", scene, "-o", solution, "--quiet", *coarse)
if result.returncode != 0:
    failures.append(f"solve failed: {result.stderr.strip()}")
else:
    reused = os.path.join(folder, "reused.png")
    result = run("render", scene, "--solution", solution, "--png", reused, "--size", "64x48",
                 "--report", reused_report, "--quiet")
    if result.returncode != 0:
        failures.append(f"render --solution failed: {result.stderr.strip()}")
    elif open(reused, "rb").read() != open(first, "rb").read():
        failures.append("render --solution gives a different image")
    else:
        timings = json.load(open(reused_report))["timings_s"]
        if "cover" in timings or "render" not in timings:
            failures.append(f"render --solution timings {timings}: expected read and render only")

# -o out.exr writes the HDR Radiance (and Depth, as the channel Z: TestCommandLineVersionProgressDepth)
# that vtkOpenEXRReader reads back: finite,
# non-negative, and brighter where the PNG is brighter (the PNG is its tone mapping).
hdr = os.path.join(folder, "hdr.exr")
hdr_png = os.path.join(folder, "hdr.png")
result = run("render", scene, "-o", hdr, "--png", hdr_png, "--size", "64x48", "--quiet", *coarse)
if result.returncode != 0:
    failures.append(f"render -o .exr failed: {result.stderr.strip()}")
else:
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from sphericalcover import vtkOpenEXRReader
    reader = vtkOpenEXRReader()
    reader.SetFileName(hdr)
    reader.Update()
    image = reader.GetOutput()
    radiance = image.GetPointData().GetArray("Radiance")
    depth = image.GetPointData().GetArray("Depth")
    if image.GetDimensions()[:2] != (64, 48) or radiance is None or depth is None:
        failures.append(f"EXR: dimensions {image.GetDimensions()}, arrays Radiance/Depth missing")
    else:
        values = vtk_to_numpy(radiance)
        png = vtkPNGReader()
        png.SetFileName(hdr_png)
        png.Update()
        rgb = vtk_to_numpy(png.GetOutput().GetPointData().GetScalars())[:, :3].astype(float)
        # The PNG is the sRGB encoding (IEC 61966-2-1) of the radiance at exposure 1.
        linear = numpy.clip(values.astype(float), 0.0, 1.0)
        encoded = numpy.where(linear <= 0.0031308, 12.92 * linear,
                              1.055 * numpy.power(linear, 1.0 / 2.4) - 0.055)
        difference = numpy.abs(numpy.round(255.0 * encoded) - rgb).max()
        if not numpy.isfinite(values).all() or values.min() < 0 or values.max() <= 0:
            failures.append("EXR radiance not finite and non-negative")
        elif difference > 1:
            failures.append(f"EXR radiance is not what the PNG shows (largest difference "
                            f"{difference} levels)")
        else:
            print(f"EXR: radiance max {values.max():.3f}, sRGB of it = PNG within {difference:.0f} level")

# The thread count does not change the image.
single = os.path.join(folder, "single.png")
result = run("render", scene, "-o", single, "--size", "64x48", "--threads", "1", "--quiet", *coarse)
if result.returncode != 0 or open(single, "rb").read() != open(first, "rb").read():
    failures.append("the image depends on the thread count")

# A saved solution whose first point names a surface that does not exist (SurfaceNameId out of
# range): the report cannot be made, and nothing is written (not even the image).
corrupt = os.path.join(folder, "corrupt_solution.vtm")
if os.path.exists(solution):
    reader = vtkXMLMultiBlockDataReader()
    reader.SetFileName(solution)
    reader.Update()
    blocks = reader.GetOutput()
    blocks.GetBlock(1).GetPointData().GetArray("SurfaceNameId").SetComponent(0, 0, 99)
    writer = vtkXMLMultiBlockDataWriter()
    writer.SetDataModeToBinary()  # appended data does not read back under expat >= 2.6
    writer.SetFileName(corrupt)
    writer.SetInputData(blocks)
    writer.Write()

# The report's figures are the light propagation filter's (its output's field data): the same
# pipeline built with the sphericalcover package carries what the CLI printed, and the scene's
# fingerprint that the reader passes on is the one the saved solution carries.
from sphericalcover import (vtkIntervalSubdivisionFilter, vtkLightPropagationFilter,
                            vtkPatchSceneReader, vtkSphericalCoverFilter)

reader = vtkPatchSceneReader()
reader.SetFileName(scene)
subdivision = vtkIntervalSubdivisionFilter()
subdivision.SetInputConnection(reader.GetOutputPort())
reader.Update()
tolerance = reader.GetOutput().GetFieldData().GetArray("SceneSettings").GetComponent(0, 3)
subdivision.SetMaxLevel(1)
subdivision.SetThetaBins(16)
subdivision.SetPhiBins(64)
subdivision.SetTolerance(tolerance)
cover = vtkSphericalCoverFilter()
cover.SetInputConnection(subdivision.GetOutputPort(0))
cover.SetThetaBins(16)
cover.SetPhiBins(64)
propagation = vtkLightPropagationFilter()
propagation.SetInputConnection(cover.GetOutputPort(0))
propagation.Update()
fd = propagation.GetOutput().GetFieldData()


def close(a, b):
    return abs(a - b) <= 1e-9 * max(abs(a), abs(b), 1e-300)


def field(name):
    array = fd.GetArray(name)
    if array is None:
        failures.append(f"the propagation's field data lacks {name}")
    return array


if os.path.exists(report_file):
    report = json.load(open(report_file))
    arrays = [field(n) for n in ["SurfaceArea", "SurfaceMeanIrradiance", "SurfaceMeanExitantRadiance",
                                 "SurfaceFormFactorPairs", "SurfaceFormFactorValues",
                                 "EnergyBalance", "SolutionStatistics", "PropagationStatistics"]]
    if all(a is not None for a in arrays):
        area, irradiance, radiance, pairs, factors, balance, statistics, shots = arrays
        names = fd.GetAbstractArray("SurfaceNames")
        mismatches = []
        for k, surface in enumerate(report["surfaces"]):
            if names.GetValue(k) != surface["name"] or not close(area.GetValue(k), surface["area"]):
                mismatches.append(f"surface {k} name/area")
            for band in range(3):
                if not (close(irradiance.GetComponent(k, band), surface["mean_irradiance"][band]) and
                        close(radiance.GetComponent(k, band), surface["mean_exitant_radiance"][band])):
                    mismatches.append(f"surface {k} band {band} means")
        # The form factors: the report's pairs are the field data's, and its matrix (a scene of
        # few surfaces) holds them and zeros elsewhere.
        listed = [[int(pairs.GetComponent(k, 0)), int(pairs.GetComponent(k, 1)),
                   factors.GetValue(k)] for k in range(pairs.GetNumberOfTuples())]
        if listed != report["form_factors"]["pairs"]:
            mismatches.append("form factor pairs")
        matrix = report["form_factors"]["matrix"]
        seen = {(a, b): value for a, b, value in listed}
        for i, row in enumerate(matrix):
            for j, value in enumerate(row):
                if value != seen.get((i, j), 0.0):
                    mismatches.append(f"form factor {i} {j}")
        for band in range(3):
            if not (close(balance.GetComponent(0, band), report["energy"]["emitted_w"][band]) and
                    close(balance.GetComponent(1, band), report["energy"]["absorbed_w"][band])):
                mismatches.append(f"energy band {band}")
        counts = report["counts"]
        if (statistics.GetComponent(0, 0), statistics.GetComponent(0, 1),
                shots.GetComponent(0, 0)) != (counts["characteristic_points"], counts["strips"],
                                              counts["shots"]):
            mismatches.append("counts")
        if not close(statistics.GetComponent(0, 2), report["energy"]["relative_imbalance"]):
            mismatches.append("relative imbalance")
        if len(report["surfaces"]) != names.GetNumberOfValues() or mismatches:
            failures.append(f"the filter's figures are not the report's: {mismatches[:5]}")
        else:
            print(f"the filter's field data carries the report's figures ({len(report['surfaces'])} "
                  f"surfaces, {counts['shots']} shots)")
fingerprint = reader.GetOutput().GetFieldData().GetAbstractArray("SceneFingerprint")
carried = fd.GetAbstractArray("SceneFingerprint")
if fingerprint is None or carried is None or fingerprint.GetValue(0) != carried.GetValue(0):
    failures.append("the reader's SceneFingerprint does not reach the propagation's output")
elif os.path.exists(solution):
    saved = vtkXMLMultiBlockDataReader()
    saved.SetFileName(solution)
    saved.Update()
    stored = saved.GetOutput().GetBlock(1).GetFieldData().GetAbstractArray("SceneFingerprint")
    if stored is None or stored.GetValue(0) != fingerprint.GetValue(0):
        failures.append("the saved solution does not carry the reader's SceneFingerprint")
# A saved solution's report (its figures computed again from its arrays) is the fresh one's.
if os.path.exists(report_file) and os.path.exists(reused_report):
    fresh, reused = json.load(open(report_file)), json.load(open(reused_report))
    for key in ["surfaces", "form_factors", "energy"]:
        if fresh[key] != reused[key]:
            failures.append(f"render --solution reports other {key} than render")

# Bad input: one line on stderr, non-zero exit, no output file.
bad_output = os.path.join(folder, "bad.png")
for arguments, words in [
        (["render", scene, "-o", bad_output, "--solution", corrupt, "--report",
          os.path.join(folder, "bad.json")], "SurfaceNameId 99"),
        (["render", scene, "-o", os.path.join(folder, "bad.tiff")], "unknown image format"),
        (["render", scene, "-o", os.path.join(folder, "nofolder", "bad.exr")], "no folder"),
        (["render", scene, "-o", bad_output, "--camera", "nowhere"], "nowhere"),
        (["render", scene, "-o", bad_output, "--size", "0x10"], "--size"),
        (["render", scene, "-o", bad_output, "--solution", os.path.join(folder, "none.vtm")],
         "none.vtm"),
        # Not XML: the reader's XML parser complains too, but only the command's error shows.
        (["render", scene, "-o", bad_output, "--solution", scene], "not a solution"),
        (["render", scene], "no output"),
        (["render", f"{data}/scenes/missing.scene", "-o", bad_output], "missing.scene")]:
    result = run(*arguments, "--quiet")
    lines = result.stderr.strip().splitlines()
    if result.returncode == 0 or len(lines) != 1 or words not in lines[0]:
        failures.append(f"{arguments[2:]}: exit {result.returncode}, stderr {result.stderr!r}")
    else:
        print(lines[0])
# --lamps: the lamp's regions measured on the lamp (the default) or counted in cells. The same
# cells either way, so the same rows' totals; the floor's form factor to the lamp moves by the
# cells' error (here, on a 16 x 64 grid, about 7 %).
if os.path.exists(report_file):
    cells_report = os.path.join(folder, "cells.json")
    result = run("solve", scene, "--report", cells_report, "--quiet", "--lamps", "cells", *coarse)
    if result.returncode != 0:
        failures.append(f"solve --lamps cells failed: {result.stderr.strip()}")
    else:
        measured = json.load(open(report_file))["form_factors"]
        counted = json.load(open(cells_report))["form_factors"]
        names = measured["names"]
        floor, light = names.index("floor"), names.index("light")
        a, b = measured["matrix"][floor][light], counted["matrix"][floor][light]
        rows_a = [sum(row) for row in measured["matrix"]]
        rows_b = [sum(row) for row in counted["matrix"]]
        print(f"--lamps: floor -> light {a:.6f} measured, {b:.6f} in cells")
        if not abs(a - b) > 1e-4 * b:
            failures.append(f"--lamps cells gives the same floor -> light form factor {a}")
        if any(abs(x - y) > 1e-5 for x, y in zip(rows_a, rows_b)):
            failures.append(f"--lamps changes the rows' totals: {rows_a} vs {rows_b}")
# An unknown --lamps value is CLI11's error (its line and a pointer to --help), nothing written.
result = run("render", scene, "-o", bad_output, "--lamps", "exact", "--quiet")
if result.returncode == 0 or "--lamps" not in result.stderr.splitlines()[0]:
    failures.append(f"--lamps exact: exit {result.returncode}, stderr {result.stderr!r}")
# The nodes of the direct light: an even count (no centre node), too many bounce rays or a
# refinement tolerance outside [0, 1] are CLI11's errors too.
for option, value in (("--direct-nodes", "4"), ("--bounce-rays", "300"), ("--bounce-rays", "-1"),
                      ("--direct-tolerance", "-0.1"), ("--direct-tolerance", "2")):
    result = run("render", scene, "-o", bad_output, option, value, "--quiet")
    if result.returncode == 0 or option not in result.stderr.splitlines()[0]:
        failures.append(f"{option} {value}: exit {result.returncode}, stderr {result.stderr!r}")
# Light behind more panes than are followed (issue 39 item 6): pane_stack.scene stacks ten panes
# between a floor and a lamp, more than the cover's layers (5), the direct light's rays and the
# render's samples (8) follow. What is left out is counted in the report and said once per stage
# in one line, not per ray nor as VTK's multi-line block.
stack_report = os.path.join(folder, "stack.json")
result = run("render", f"{data}/scenes/pane_stack.scene", "-o", os.path.join(folder, "stack.exr"),
             "--report", stack_report, "--quiet")
if result.returncode != 0:
    failures.append(f"pane_stack: exit {result.returncode}, stderr {result.stderr!r}")
else:
    limit = json.load(open(stack_report)).get("pane_limit", {})
    for key in ("cover_cells", "cover_projected_solid_angle_fraction", "direct_light_rays",
                "render_samples", "render_sample_fraction"):
        if not limit.get(key, 0) > 0:
            failures.append(f"pane_stack: the report's pane_limit.{key} is {limit.get(key)}")
    if limit.get("render_samples") != 32 * 32 * 4 or limit.get("render_sample_fraction") != 1.0:
        failures.append(f"pane_stack: every sample of the view down the stack drops, not {limit}")
    warnings = [line for line in result.stderr.splitlines() if line.strip()]
    if len(warnings) != 2 or not all(line.startswith("sphcover: warning: ") and "panes" in line
                                     for line in warnings):
        failures.append(f"pane_stack: not one warning line per stage: {result.stderr!r}")
leftovers = [name for name in os.listdir(folder) if name.startswith("bad") or "partial" in name]
if leftovers:
    failures.append(f"files left behind by failures: {leftovers}")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
