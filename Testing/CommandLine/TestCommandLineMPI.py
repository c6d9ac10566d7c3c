"""sphcover under mpiexec (issue 19): the solve (the cover's rows, the direct light and the
propagation) on 2 and 3 ranks gives the serial solution, and a failure is one clear error with a
non-zero exit, without a hang.

- `sphcover render` of the Cornell box (small grid and subdivision) serially and under
  `mpiexec -n 2` and `-n 3` (3 ranks oversubscribe a 2-core machine): the reports' form factors
  and mean radiances equal the serial ones to 1e-12 relative (they are in fact the same bits),
  the images are equal byte for byte, and the report says "ranks" and each rank's rows;
- `solve -o` under `mpiexec -n 2` writes the solution in pieces (each rank its share of the
  cover, no rank holding the whole): the serial report's form factors, surfaces and counts bit
  for bit, a block of 2 shares, `render --solution` of it the serial image and a walk through
  it under `mpiexec -n 2` the serial walk's three frames, byte for byte; a missing piece is one
  error naming it;
- a solution in pieces of a scene with a glossy wall and a mirror (the mixed box) rendered by
  the ranks that hold the pieces (`render --solution` and `walk` under `mpiexec -n 2`: each rank
  evaluates the directional part of its own points) gives the serial image and frames byte for
  byte, and on 3 ranks (rank 0 joining the 2 pieces) the same image, as does `render` solving
  and rendering in one run on 2 ranks (the pieces never gathered); a missing piece is one
  error on 2 ranks, without a hang;
- a solve whose propagation state exceeds --memory-limit in one process (refused, one error)
  fits on 2 ranks, each of which holds its share (memory per rank falls with K);
- a scene that does not load, under `mpiexec -n 2`: a non-zero exit within the timeout and one
  `sphcover: error:` line (rank 0 speaks; every rank fails alike).
Without mpiexec on the PATH the test is skipped (exit 77) with a message.

usage: TestCommandLineMPI.py SPHCOVER DATA"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
from xml.etree import ElementTree

sphcover, data = sys.argv[1:3]
mpiexec = shutil.which("mpiexec")
if mpiexec is None:
    print("SKIPPED: mpiexec is not on the PATH (install mpi-default-bin to run the MPI test)")
    sys.exit(77)

# Open MPI refuses to run as root (CI containers) and to start more ranks than cores unless told;
# its environment variables say so without breaking other MPI implementations' command lines.
environment = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")
SCENE = f"{data}/scenes/cornell_box.scene"
SMALL = ["--set", "max_level=2", "--set", "theta_bins=8", "--set", "phi_bins=32", "--threads", "1",
         "--size", "48x48", "--spp", "1", "-q"]
failures = []


def run(command, timeout=600):
    result = subprocess.run(command, capture_output=True, text=True, timeout=timeout,
                            env=environment)
    return result


def render(folder, ranks):
    """The report and the PNG bytes of a render on `ranks` ranks (0: no mpiexec)."""
    report = os.path.join(folder, f"report{ranks}.json")
    image = os.path.join(folder, f"image{ranks}.png")
    launcher = [mpiexec, "-n", str(ranks)] if ranks else []
    result = run(launcher + [sphcover, "render", SCENE, "-o", image, "--report", report, *SMALL])
    if result.returncode != 0:
        failures.append(f"{ranks} ranks: exit {result.returncode}: {result.stderr.strip()}")
        return None, None
    with open(report, encoding="utf-8") as file, open(image, "rb") as png:
        return json.load(file), png.read()


def relative(a, b):
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def compare(serial, parallel, ranks):
    pairs = list(zip(sum(serial["form_factors"]["matrix"], []),
                     sum(parallel["form_factors"]["matrix"], [])))
    for s, p in zip(serial["surfaces"], parallel["surfaces"]):
        pairs += list(zip(s["mean_exitant_radiance"] + s["mean_irradiance"],
                          p["mean_exitant_radiance"] + p["mean_irradiance"]))
    worst = max(relative(a, b) for a, b in pairs)
    if worst > 1e-12:
        failures.append(f"{ranks} ranks: form factors or mean radiances differ by {worst:.3g}")
    if parallel.get("ranks") != ranks:
        failures.append(f"{ranks} ranks: the report says ranks {parallel.get('ranks')}")
    rows = parallel.get("cover_ranks", [])
    if len(rows) != ranks or any(r["bytes"] <= 0 or r["seconds"] < 0 for r in rows):
        failures.append(f"{ranks} ranks: cover_ranks {rows}")
    elif sum(r["receivers"] for r in rows) != serial["counts"]["characteristic_points"]:
        failures.append(f"{ranks} ranks: the ranks' receivers do not add up: {rows}")
    # The propagation on the ranks: each rank's receivers and rows, whose state is its own
    # share (memory per rank falls with K), and the serial shots.
    shooting = parallel.get("propagation_ranks", [])
    if parallel["counts"]["shots"] != serial["counts"]["shots"]:
        failures.append(f"{ranks} ranks: {parallel['counts']['shots']} shots, serial "
                        f"{serial['counts']['shots']}")
    if len(shooting) != ranks or any(r["receivers"] <= 0 or r["state_bytes"] <= 0
                                     for r in shooting):
        failures.append(f"{ranks} ranks: propagation_ranks {shooting}")
    elif sum(r["receivers"] for r in shooting) != serial["counts"]["characteristic_points"]:
        failures.append(f"{ranks} ranks: the propagation's receivers do not add up: {shooting}")
    elif max(r["state_bytes"] for r in shooting) > 0.8 * sum(r["state_bytes"] for r in shooting):
        failures.append(f"{ranks} ranks: one rank holds most of the propagation's state: "
                        f"{shooting}")
    # Every rank's peak resident memory, in rank order (what each machine must hold).
    peaks = parallel.get("peak_resident_bytes", [])
    if len(peaks) != ranks or any(not isinstance(b, int) or b <= 0 for b in peaks):
        failures.append(f"{ranks} ranks: peak_resident_bytes {peaks}")


with tempfile.TemporaryDirectory() as folder:
    serial, serial_image = render(folder, 0)
    if serial is not None and serial.get("ranks") != 1:
        failures.append(f"serial: the report says ranks {serial.get('ranks')}")
    if serial is not None and len(serial.get("peak_resident_bytes", [])) != 1:
        failures.append(f"serial: peak_resident_bytes {serial.get('peak_resident_bytes')}")
    states = []
    for ranks in (2, 3):
        parallel, image = render(folder, ranks)
        if serial is None or parallel is None:
            continue
        compare(serial, parallel, ranks)
        if image != serial_image:
            failures.append(f"{ranks} ranks: the image differs from the serial one")
        if ranks == 2:
            states = [r["state_bytes"] for r in parallel.get("propagation_ranks", [])]

    # A limit between one rank's propagation state and the whole state: one process is refused
    # (the whole state is about the two ranks' sum), two ranks solve it.
    if len(states) == 2:
        limit = f"{1.3 * max(states) / 2**20:.2f}"
        alone = run([sphcover, "solve", SCENE, *SMALL[:8], "-q", "--memory-limit", limit])
        if alone.returncode == 0 or "MemoryLimit" not in alone.stderr:
            failures.append(f"--memory-limit {limit} MiB on one process: exit {alone.returncode}, "
                            f"not the propagation's MemoryLimit error: {alone.stderr.strip()}")
        shared = run([mpiexec, "-n", "2", sphcover, "solve", SCENE, *SMALL[:8], "-q",
                      "--memory-limit", limit])
        if shared.returncode != 0:
            failures.append(f"--memory-limit {limit} MiB on 2 ranks: exit {shared.returncode}: "
                            f"{shared.stderr.strip()}")

    # A solve on 2 ranks writes its solution in pieces, no rank holding the whole cover: the
    # serial report, a third block of the ranks' 2 shares, and the serial solution once joined
    # (render --solution gives the serial image; a walk under mpiexec -n 2 the serial walk's
    # frames, byte for byte). A missing piece is one error naming it.
    solution = os.path.join(folder, "solution.vtm")
    pieces = os.path.join(folder, "pieces.vtm")
    solved = run([sphcover, "solve", SCENE, "-o", solution, "--report",
                  os.path.join(folder, "solve0.json"), *SMALL[:8], "-q"])
    split = run([mpiexec, "-n", "2", sphcover, "solve", SCENE, "-o", pieces, "--report",
                 os.path.join(folder, "solve2.json"), *SMALL[:8], "-q"])
    for result, what in [(solved, "serial solve"), (split, "solve on 2 ranks")]:
        if result.returncode != 0:
            failures.append(f"{what}: exit {result.returncode}: {result.stderr.strip()}")
    if solved.returncode == 0 and split.returncode == 0:
        with open(os.path.join(folder, "solve0.json"), encoding="utf-8") as file:
            serial_solve = json.load(file)
        with open(os.path.join(folder, "solve2.json"), encoding="utf-8") as file:
            pieces_solve = json.load(file)
        compare(serial_solve, pieces_solve, 2)
        if (pieces_solve["form_factors"] != serial_solve["form_factors"] or
                pieces_solve["surfaces"] != serial_solve["surfaces"] or
                pieces_solve["counts"] != serial_solve["counts"]):
            failures.append("the solve kept in pieces reports other form factors, surfaces or "
                            "counts than the serial solve (not bit for bit)")
        if (pieces_solve["memory_bytes"]["incident_radiance"] !=
                serial_solve["memory_bytes"]["incident_radiance"]):
            failures.append(f"the pieces hold {pieces_solve['memory_bytes']} bytes of incident "
                            f"radiance, the whole solution {serial_solve['memory_bytes']}")
        root = ElementTree.parse(pieces).getroot()
        shares = [block for block in root.iter("Piece") if block.get("name") == "CoverShares"]
        files = [entry.get("file") for entry in shares[0]] if len(shares) == 1 else []
        if len(files) != 2 or not all(files):
            failures.append(f"the solution of 2 ranks has no block CoverShares of 2 files: "
                            f"{ElementTree.tostring(root, encoding='unicode')}")
        joined_image = os.path.join(folder, "joined.png")
        rendered = run([sphcover, "render", SCENE, "--solution", pieces, "-o", joined_image,
                        *SMALL[6:]])
        if rendered.returncode != 0:
            failures.append(f"render --solution of the pieces: exit {rendered.returncode}: "
                            f"{rendered.stderr.strip()}")
        elif serial_image is not None and open(joined_image, "rb").read() != serial_image:
            failures.append("render --solution of the pieces differs from the serial image")
        frames = {}
        for ranks, walked_solution in [(0, solution), (2, pieces)]:
            out = os.path.join(folder, f"walk{ranks}")
            launcher = [mpiexec, "-n", str(ranks)] if ranks else []
            walked = run(launcher + [sphcover, "walk", walked_solution, "--orbit", "3", "-o", out,
                                     "--size", "48x48", "-q"])
            if walked.returncode != 0:
                failures.append(f"walk on {ranks} ranks: exit {walked.returncode}: "
                                f"{walked.stderr.strip()}")
                continue
            names = sorted(os.listdir(out))
            frames[ranks] = [open(os.path.join(out, name), "rb").read() for name in names]
        if len(frames) == 2 and (len(frames[0]) != 3 or frames[0] != frames[2]):
            failures.append(f"the walk of the pieces on 2 ranks gave {len(frames[2])} frames, "
                            f"not the serial walk's {len(frames[0])} frames byte for byte")
        if len(files) == 2:
            os.remove(os.path.join(folder, files[1]))
            lost = os.path.join(folder, "lost.png")
            result = run([sphcover, "render", SCENE, "--solution", pieces, "-o", lost, "-q"])
            errors = [line for line in result.stderr.splitlines() if "sphcover: error:" in line]
            if (result.returncode == 0 or len(errors) != 1 or files[1] not in errors[0] or
                    os.path.exists(lost)):
                failures.append(f"a solution missing a piece: exit {result.returncode}, "
                                f"{result.stderr.strip()}")

    # Rendered by the ranks that hold the pieces (a glossy wall and a mirror: the directional
    # part of paper §5.3.1 of each rank's points from its own share of the cover): render
    # --solution and walk under mpiexec -n 2 give the serial image and frames byte for byte;
    # on 3 ranks (not the pieces' 2) rank 0 joins them and renders alone, the same image. A
    # missing piece is one error, without a hang.
    MIXED = f"{data}/scenes/mixed_box.scene"
    mixed_serial = os.path.join(folder, "mixed.vtm")
    mixed_pieces = os.path.join(folder, "mixed_pieces.vtm")
    view = ["--size", "64x48", "--spp", "2", "-q"]
    solved = [run([sphcover, "solve", MIXED, "-o", mixed_serial, *SMALL[:8], "-q"]),
              run([mpiexec, "-n", "2", sphcover, "solve", MIXED, "-o", mixed_pieces, *SMALL[:8],
                   "-q"])]
    if any(result.returncode != 0 for result in solved):
        failures.append(f"solving the mixed box: {[r.stderr.strip() for r in solved]}")
    else:
        images = {}
        for label, launcher, source in [("serial", [], mixed_serial),
                                        ("2 ranks", [mpiexec, "-n", "2"], mixed_pieces),
                                        ("3 ranks", [mpiexec, "-n", "3"], mixed_pieces)]:
            image = os.path.join(folder, f"mixed {label}.png")
            result = run(launcher + [sphcover, "render", MIXED, "--solution", source, "-o",
                                     image, *view])
            if result.returncode != 0:
                failures.append(f"render --solution of the mixed box on {label}: exit "
                                f"{result.returncode}: {result.stderr.strip()}")
            else:
                images[label] = open(image, "rb").read()
        if len(images) == 3 and not images["serial"] == images["2 ranks"] == images["3 ranks"]:
            failures.append("the mixed box rendered from its pieces on 2 or 3 ranks differs "
                            "from the serial image")
        # Solved and rendered in one run on 2 ranks, the solution kept in pieces throughout.
        solved_image = os.path.join(folder, "mixed solved.png")
        result = run([mpiexec, "-n", "2", sphcover, "render", MIXED, "-o", solved_image,
                      *SMALL[:8], *view])
        if result.returncode != 0:
            failures.append(f"render of the mixed box on 2 ranks: {result.stderr.strip()}")
        elif "serial" in images and open(solved_image, "rb").read() != images["serial"]:
            failures.append("the mixed box solved and rendered on 2 ranks differs from the "
                            "serial image")
        walks = {}
        for label, launcher, source in [("serial", [], mixed_serial),
                                        ("2 ranks", [mpiexec, "-n", "2"], mixed_pieces)]:
            out = os.path.join(folder, f"mixed walk {label}")
            result = run(launcher + [sphcover, "walk", source, "--orbit", "2", "-o", out,
                                     "--size", "48x48", "-q"])
            if result.returncode != 0:
                failures.append(f"walk of the mixed box on {label}: {result.stderr.strip()}")
            else:
                walks[label] = [open(os.path.join(out, name), "rb").read()
                                for name in sorted(os.listdir(out))]
        if len(walks) == 2 and (len(walks["serial"]) != 2 or walks["serial"] != walks["2 ranks"]):
            failures.append("the walk through the mixed box's pieces on 2 ranks differs from "
                            "the serial walk")
        root = ElementTree.parse(mixed_pieces).getroot()
        files = [entry.get("file") for block in root.iter("Piece")
                 if block.get("name") == "CoverShares" for entry in block]
        if len(files) == 2:
            os.remove(os.path.join(folder, files[0]))
            try:
                result = run([mpiexec, "-n", "2", sphcover, "render", MIXED, "--solution",
                              mixed_pieces, "-o", os.path.join(folder, "lost.png"), "-q"],
                             timeout=120)
                errors = [line for line in result.stderr.splitlines()
                          if "sphcover: error:" in line]
                if result.returncode == 0 or len(errors) != 1 or files[0] not in errors[0]:
                    failures.append(f"pieces missing one, rendered on 2 ranks: exit "
                                    f"{result.returncode}, {result.stderr.strip()}")
            except subprocess.TimeoutExpired:
                failures.append("pieces missing one, rendered on 2 ranks: hung")

    bad = os.path.join(folder, "bad.scene")
    with open(bad, "w", encoding="utf-8") as file:
        file.write("{ \"surfaces\": [ this is not JSON\n")
    try:
        result = run([mpiexec, "-n", "2", sphcover, "solve", bad, "-q"], timeout=120)
        errors = [line for line in result.stderr.splitlines() if "sphcover: error:" in line]
        if result.returncode == 0:
            failures.append("a bad scene under mpiexec -n 2 exited 0")
        if len(errors) != 1:
            failures.append(f"a bad scene under mpiexec -n 2 gave {len(errors)} errors: "
                            f"{result.stderr.strip()}")
    except subprocess.TimeoutExpired:
        failures.append("a bad scene under mpiexec -n 2 hung (no exit within 120 s)")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
