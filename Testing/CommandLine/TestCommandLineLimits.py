"""Commands beyond `info` on input that is bad or beyond the limits (Testing/Data/bad/commands.json):
each must fail within a timeout (a hang fails the test) with a non-zero exit (not a signal: no
crash, no abort inside Embree), exactly one line on stderr holding the expected fragments, and no
output file left behind.

Placeholders in the arguments: {bad} the corpus folder, {base} its valid base scene, {tmp} a
fresh folder holding a solution of the base scene (base.vtm), a copy of it without its scene
fingerprint (unmarked.vtm) and two folders named like outputs (folder.vtm, folder.png)."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

from one_line_error import check_one_line_error

sphcover, bad = sys.argv[1:3]
cases = json.load(open(os.path.join(bad, "commands.json")))
failures = []
tmp = tempfile.mkdtemp(prefix="sphcover_limits_")
base = os.path.join(bad, "support", "base.scene")

# The fixtures: a solution, the same without its fingerprint, folders where files are expected.
setup = subprocess.run([sphcover, "solve", base, "-o", os.path.join(tmp, "base.vtm"), "--quiet"],
                       capture_output=True, text=True, timeout=120)
if setup.returncode != 0:
    failures.append(f"solving the base scene failed: {setup.stderr.strip()}")
else:
    shutil.copytree(os.path.join(tmp, "base"), os.path.join(tmp, "unmarked"))
    with open(os.path.join(tmp, "base.vtm")) as f:
        text = f.read().replace("base/base_", "unmarked/base_")
    with open(os.path.join(tmp, "unmarked.vtm"), "w") as f:
        f.write(text)
    illumination = os.path.join(tmp, "unmarked", "base_1.vtp")
    with open(illumination) as f:
        text = f.read()
    stripped = re.sub(r'<Array type="String" Name="SceneFingerprint".*?</Array>\s*', "", text,
                      flags=re.S)
    if stripped == text:
        failures.append("the solution holds no SceneFingerprint array to strip")
    with open(illumination, "w") as f:
        f.write(stripped)
for folder in ["folder.vtm", "folder.png"]:
    os.mkdir(os.path.join(tmp, folder))
fixtures = set(os.listdir(tmp))

for name, case in sorted(cases.items()):
    arguments = [a.format(bad=bad, base=base, tmp=tmp) for a in case["args"]]
    try:
        run = subprocess.run([sphcover, *arguments, "--quiet"], capture_output=True, text=True,
                             timeout=60)
    except subprocess.TimeoutExpired:
        failures.append(f"{name}: no answer within 60 s")
        continue
    check_one_line_error(name, run, case["expect"], failures)
    left = set(os.listdir(tmp)) - fixtures
    if left:
        failures.append(f"{name}: left {sorted(left)} behind")
        for entry in left:
            path = os.path.join(tmp, entry)
            shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)
if len(cases) < 20:
    failures.append(f"only {len(cases)} cases were tried")

shutil.rmtree(tmp, ignore_errors=True)
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
