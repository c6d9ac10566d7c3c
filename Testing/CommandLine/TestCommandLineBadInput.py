"""`sphcover info` on every malformed input of Testing/Data/bad: a non-zero exit (not a crash:
no signal), exactly one line on stderr naming the file, the location and the problem, and
nothing on stdout. A missing file and a bad command line fail the same way."""
import json
import os
import subprocess
import shutil
import sys
import tempfile

from one_line_error import check_one_line_error

sphcover, bad = sys.argv[1:3]
expected = json.load(open(os.path.join(bad, "expected.json")))
failures = []


def check(path, fragments):
    run = subprocess.run([sphcover, "info", path], capture_output=True, text=True, timeout=60)
    check_one_line_error(os.path.basename(path), run, fragments, failures)


cases = 0
for name, fragments in sorted(expected.items()):
    if name.endswith((".scene", ".bpt")):
        check(os.path.join(bad, name), fragments)
        cases += 1
if cases < 20:
    failures.append(f"only {cases} bad inputs were tried")
check(os.path.join(bad, "no_such_file.scene"), ["no_such_file.scene", "cannot open file"])

# Inputs git cannot hold: devices, a FIFO (must not block), directories, a file over the
# size limit (sparse: no disk space), as the scene or .bpt itself and as files a scene names.
folder = tempfile.mkdtemp()
fifo = os.path.join(folder, "pipe.scene")
os.mkfifo(fifo)
os.symlink("/dev/zero", os.path.join(folder, "zero.bpt"))
os.mkfifo(os.path.join(folder, "pipe.bpt"))
os.mkdir(os.path.join(folder, "folder.scene"))
os.mkdir(os.path.join(folder, "folder.bpt"))
with open(os.path.join(folder, "huge.scene"), "wb") as f:
    f.truncate(65 << 20)
base = json.load(open(os.path.join(bad, "support", "base.scene")))
for kind, file in [("bpt", "pipe.bpt"), ("mesh", "pipe.bpt"), ("bpt", "huge.scene")]:
    scene = json.loads(json.dumps(base))
    scene["surfaces"].append({"name": "x", "type": kind, "material": "white", "file": file})
    json.dump(scene, open(os.path.join(folder, f"{kind}_{file}.scene"), "w"))
generated = [
    ("/dev/zero", ["/dev/zero", "not a regular file (a device)"]),
    (os.path.join(folder, "zero.bpt"), ["zero.bpt", "not a regular file (a device)"]),
    (fifo, ["pipe.scene", "not a regular file (a FIFO)"]),
    (os.path.join(folder, "pipe.bpt"), ["pipe.bpt", "not a regular file (a FIFO)"]),
    (os.path.join(folder, "folder.scene"), ["folder.scene", "is a directory"]),
    (os.path.join(folder, "folder.bpt"), ["folder.bpt", "is a directory"]),
    (os.path.join(folder, "huge.scene"), ["huge.scene", "file too large (68157440 bytes; the limit is 64 MiB)"]),
    (os.path.join(folder, "bpt_pipe.bpt.scene"), ["/surfaces/3/file", "pipe.bpt: not a regular file (a FIFO)"]),
    (os.path.join(folder, "mesh_pipe.bpt.scene"), ["/surfaces/3/file", "pipe.bpt: not a regular file (a FIFO)"]),
    (os.path.join(folder, "bpt_huge.scene.scene"), ["/surfaces/3/file", "huge.scene: file too large"]),
]
for path, fragments in generated:
    check(path, fragments)
shutil.rmtree(folder)

# Every corpus file is one change away from these valid files: they must read.
for valid in ["support/base.scene", "support/base.bpt"]:
    run = subprocess.run([sphcover, "info", os.path.join(bad, valid)], capture_output=True, text=True, timeout=60)
    if run.returncode != 0 or "Surfaces:" not in run.stdout:
        failures.append(f"{valid}: the valid base file does not read: {run.stderr.strip()}")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
