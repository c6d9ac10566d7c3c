"""What `sphcover` shows a user outside the pipeline's figures (README.md#command-line, issue 17):
- `sphcover --version` exits 0 and prints the CMake project version and the versions of VTK,
  Embree and OpenEXR it was built with;
- with stderr redirected to a file (not a terminal) a solve prints plain progress lines, no
  carriage return: lines `STAGE: P% (T s elapsed...)` of every stage (read, subdivide, cover,
  propagate), rising, each stage's last one at 100 %, the cover's (2 s) also before its end with
  the time left; with --quiet nothing;
- `sphcover render -o x.exr` writes OpenEXR's channels R, G, B, Z (exrheader lists them, when
  installed) and Z is +infinity where the camera sees no surface (the Cornell box's open front
  shows the background) and the renderer's Depth elsewhere: the file is decoded here with
  zlib (scanline file, ZIP or no compression, as vtkOpenEXRWriter writes by default), not with
  our reader, which reads Z back as Depth with -1 where nothing is seen (checked as well).

usage: python3 TestCommandLineVersionProgressDepth.py SPHCOVER DATA_DIR PROJECT_VERSION"""
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

sphcover, data, project_version = sys.argv[1:4]
failures = []
folder = tempfile.mkdtemp()
scene = f"{data}/scenes/cornell_box.scene"
# Coarse settings keep the test in seconds.
coarse = ["--set", "max_level=1", "--set", "theta_bins=16", "--set", "phi_bins=64"]

# --version: exit 0, the project's version and the libraries'.
version = subprocess.run([sphcover, "--version"], capture_output=True, text=True, timeout=60)
print(version.stdout.strip())
if version.returncode != 0:
    failures.append(f"--version: exit {version.returncode}, stderr {version.stderr!r}")
first = version.stdout.splitlines()[0] if version.stdout else ""
if first != f"sphcover {project_version}":
    failures.append(f"--version: first line {first!r}, not 'sphcover {project_version}'")
for library in ["VTK", "Embree", "OpenEXR"]:
    if not re.search(rf"\b{library} \d+\.\d+(\.\d+)*\b", version.stdout):
        failures.append(f"--version: no version of {library} in {version.stdout!r}")

# Progress in a log: stderr is a file here, as in `2> log`.
log_path = os.path.join(folder, "solve.log")
with open(log_path, "w") as log:
    # A cover of about 2 s on one thread: long enough for lines before its end (one after a
    # second and a 10 % step at the earliest).
    solve = subprocess.run([sphcover, "solve", scene, "--report", os.path.join(folder, "r.json"),
                            "--threads", "1", "--set", "max_level=2", "--set", "theta_bins=24",
                            "--set", "phi_bins=96"],
                           stdout=subprocess.DEVNULL, stderr=log, timeout=600)
with open(log_path) as log:
    text = log.read()
print(text, end="")
if solve.returncode != 0:
    failures.append(f"solve with stderr to a file: exit {solve.returncode}: {text[-300:]!r}")
if "\r" in text:
    failures.append("the log holds carriage returns (the terminal's bar), not plain lines")
line_form = re.compile(r"^(\w+): (\d+)% \((\d+\.\d+) s elapsed(, about \d+(\.\d+)? s left)?\)$")
lines = [line for line in text.splitlines() if line]
matches = [line_form.match(line) for line in lines]
for line, match in zip(lines, matches):
    if not match:
        failures.append(f"log line {line!r} is not a progress line 'STAGE: P% (T s elapsed...)'")
stages = {}
for match in filter(None, matches):
    stages.setdefault(match.group(1), []).append(int(match.group(2)))
for stage in ["read", "subdivide", "cover", "propagate"]:
    if stage not in stages:
        failures.append(f"no progress line of the stage {stage}")
    elif stages[stage][-1] != 100 or stages[stage].count(100) != 1:
        failures.append(f"{stage}: the percentages {stages[stage]} do not end with one 100 %")
    elif len(stages[stage]) > 12 or stages[stage] != sorted(set(stages[stage])):
        failures.append(f"{stage}: the percentages {stages[stage]}: not rising, or more than one "
                        "line per 10 %")
running = [m for m in filter(None, matches) if m.group(1) == "cover" and m.group(4)]
if not running:
    failures.append("no line of the cover while it runs (with the time left)")
quiet = subprocess.run([sphcover, "solve", scene, "--quiet", *coarse], capture_output=True,
                       text=True, timeout=600)
if quiet.returncode != 0 or quiet.stderr:
    failures.append(f"--quiet: exit {quiet.returncode}, stderr {quiet.stderr!r}")


def read_exr_channels(path):
    """The float channels of a single-part scanline OpenEXR file without or with ZIP/ZIPS
    compression: (width, height, {name: [rows of values, top row first]})."""
    with open(path, "rb") as f:
        raw = f.read()
    if raw[:4] != b"\x76\x2f\x31\x01":
        raise ValueError("not an OpenEXR file")
    if raw[5] & 0x16:
        raise ValueError("tiled, deep, multi-part or long-name files are not decoded here")
    at = 8
    channels, compression, window = [], None, None
    while raw[at] != 0:
        end = raw.index(b"\0", at)
        name = raw[at:end].decode()
        type_end = raw.index(b"\0", end + 1)
        kind = raw[end + 1:type_end].decode()
        size = struct.unpack_from("<i", raw, type_end + 1)[0]
        value = raw[type_end + 5:type_end + 5 + size]
        if name == "channels":
            k = 0
            while value[k] != 0:
                name_end = value.index(b"\0", k)
                pixel_type = struct.unpack_from("<i", value, name_end + 1)[0]
                channels.append((value[k:name_end].decode(), pixel_type))
                k = name_end + 1 + 16
        elif name == "compression":
            compression = value[0]
        elif name == "dataWindow":
            window = struct.unpack("<4i", value)
        at = type_end + 5 + size
    at += 1
    if compression not in (0, 2, 3):
        raise ValueError(f"compression {compression} is not decoded here")
    if any(pixel_type != 2 for _, pixel_type in channels):
        raise ValueError("only 32-bit float channels are decoded here")
    width, height = window[2] - window[0] + 1, window[3] - window[1] + 1
    lines_per_block = 16 if compression == 3 else 1
    blocks = (height + lines_per_block - 1) // lines_per_block
    offsets = struct.unpack_from(f"<{blocks}Q", raw, at)
    planes = {name: [None] * height for name, _ in channels}
    for offset in offsets:
        y, size = struct.unpack_from("<ii", raw, offset)
        rows = min(lines_per_block, window[3] - y + 1)
        packed = raw[offset + 8:offset + 8 + size]
        expected = rows * len(channels) * width * 4
        if compression == 0 or size == expected:  # stored raw when compressing did not pay
            block = packed
        else:
            # OpenEXR's ZIP: zlib, then a byte predictor, then the two halves interleaved.
            t = bytearray(zlib.decompress(packed))
            for k in range(1, len(t)):
                t[k] = (t[k - 1] + t[k] - 128) & 0xFF
            half = (len(t) + 1) // 2
            block = bytearray(len(t))
            block[0::2] = t[:half]
            block[1::2] = t[half:]
        k = 0
        for row in range(rows):
            for name, _ in channels:  # in the file's (alphabetical) order
                planes[name][y - window[1] + row] = struct.unpack_from(f"<{width}f", block, k)
                k += 4 * width
    return width, height, planes


# Z in the rendered EXR.
exr = os.path.join(folder, "render.exr")
render = subprocess.run([sphcover, "render", scene, "-o", exr, "--size", "64x48", "--quiet",
                         *coarse], capture_output=True, text=True, timeout=600)
if render.returncode != 0:
    failures.append(f"render -o .exr failed: {render.stderr.strip()}")
else:
    exrheader = shutil.which("exrheader")
    if exrheader is None:
        print("SKIPPED: the exrheader check (exrheader is not installed: Debian package openexr)")
    else:
        header = subprocess.run([exrheader, exr], capture_output=True, text=True, timeout=60)
        listed = re.findall(r"^\s+(\S+), 32-bit floating-point, sampling 1 1$", header.stdout,
                            re.MULTILINE)
        print("exrheader channels:", listed)
        if header.returncode != 0 or listed != ["B", "G", "R", "Z"]:
            failures.append(f"exrheader lists the channels {listed}, not B, G, R, Z "
                            f"(exit {header.returncode})")
    width, height, planes = read_exr_channels(exr)
    if (width, height) != (64, 48) or sorted(planes) != ["B", "G", "R", "Z"]:
        failures.append(f"decoded {width} x {height} with channels {sorted(planes)}")
    else:
        z = [value for row in planes["Z"] for value in row]
        background = [k for k, value in enumerate(z) if value == math.inf]
        seen = [value for value in z if value != math.inf]
        print(f"Z: {len(background)} background pixels (+inf), seen in "
              f"[{min(seen):.1f}, {max(seen):.1f}]")
        if not background:
            failures.append("no pixel has Z = +inf: the open front of the box shows background")
        if any(not (value > 0 and math.isfinite(value)) for value in seen):
            failures.append("a pixel that sees a surface has a Z that is not positive and finite")
        # Our reader: the array Depth, -1 exactly where Z is +inf, Z elsewhere.
        try:
            from sphericalcover import vtkOpenEXRReader
            from vtkmodules.util.numpy_support import vtk_to_numpy
        except ImportError as error:
            failures.append(f"the sphericalcover package does not import: {error}")
        else:
            reader = vtkOpenEXRReader()
            reader.SetFileName(exr)
            reader.Update()
            arrays = reader.GetOutput().GetPointData()
            depth = arrays.GetArray("Depth")
            if depth is None or arrays.GetArray("Z") is not None:
                failures.append("vtkOpenEXRReader does not read Z as the array Depth")
            else:
                # VTK's rows go up, the file's down.
                d = vtk_to_numpy(depth).reshape(height, width)[::-1].ravel()
                expected = [-1.0 if value == math.inf else value for value in z]
                if any(float(a) != b for a, b in zip(d, expected)):
                    failures.append("vtkOpenEXRReader's Depth is not Z with -1 for +inf")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
