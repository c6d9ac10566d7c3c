"""`sphcover info` on every malformed input of Testing/Data/bad: a non-zero exit (not a crash:
no signal), exactly one line on stderr naming the file, the location and the problem, and
nothing on stdout. A missing file and a bad command line fail the same way."""
import json
import os
import subprocess
import sys

sphcover, bad = sys.argv[1:3]
expected = json.load(open(os.path.join(bad, "expected.json")))
failures = []


def check(path, fragments):
    run = subprocess.run([sphcover, "info", path], capture_output=True, text=True, timeout=60)
    name = os.path.basename(path)
    if run.returncode <= 0:
        failures.append(f"{name}: exit status {run.returncode} (expected a failure, not a signal)")
    lines = run.stderr.strip().splitlines()
    if len(lines) != 1:
        failures.append(f"{name}: {len(lines)} lines on stderr, expected one: {run.stderr!r}")
    message = run.stderr.strip()
    print(f"{name}: {message}")
    for fragment in fragments:
        if fragment not in message:
            failures.append(f"{name}: message lacks {fragment!r}")
    if run.stdout:
        failures.append(f"{name}: printed on stdout: {run.stdout!r}")


cases = 0
for name, fragments in sorted(expected.items()):
    if name.endswith((".scene", ".bpt")):
        check(os.path.join(bad, name), fragments)
        cases += 1
if cases < 20:
    failures.append(f"only {cases} bad inputs were tried")
check(os.path.join(bad, "no_such_file.scene"), ["no_such_file.scene", "cannot open file"])

# Every corpus file is one change away from these valid files: they must read.
for valid in ["support/base.scene", "support/base.bpt"]:
    run = subprocess.run([sphcover, "info", os.path.join(bad, valid)], capture_output=True, text=True, timeout=60)
    if run.returncode != 0 or "Surfaces:" not in run.stdout:
        failures.append(f"{valid}: the valid base file does not read: {run.stderr.strip()}")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
