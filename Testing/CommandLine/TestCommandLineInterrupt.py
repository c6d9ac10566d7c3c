"""`sphcover` interrupted: SIGINT or SIGTERM while it writes its output ends it by that signal
with one line on stderr, leaves no staging folder or temporary file behind, and leaves the
output of an earlier run intact (or, if the signal came while the output was moved into
place, the new output complete). SIGKILL leaves nothing either (a janitor process cleans up);
SIGKILL of the whole process group leaves the staging folder under a name that says whose it
is (`.<name>.sphcover-<pid>.*`), and the next run writing into that folder removes it.

The signal is sent the moment the staging folder appears, i.e. during the write; a run that
finished its write first is tried again (up to 8 times)."""
import hashlib
import os
import signal
import subprocess
import sys
import tempfile
import time

sphcover, data = sys.argv[1:3]
scene = os.path.join(data, "scenes", "cornell_box.scene")
coarse = ["--set", "max_level=2", "--set", "theta_bins=16", "--set", "phi_bins=64", "--quiet"]
failures = []


def snapshot(folder):
    """Every file under `folder` with the hash of its bytes."""
    files = {}
    for root, _, names in os.walk(folder):
        for name in names:
            path = os.path.join(root, name)
            files[os.path.relpath(path, folder)] = hashlib.sha256(open(path, "rb").read()).hexdigest()
    return files


def leftovers(folder, wait=10.0):
    """The staging folders and temporary files in `folder`, once the janitor (which removes them
    when sphcover has ended) had up to `wait` seconds to do so."""
    deadline = time.monotonic() + wait
    while True:
        left = sorted(name for name in os.listdir(folder)
                      if ".sphcover-" in name or ".tmp" in name or ".partial" in name)
        if not left or time.monotonic() > deadline:
            return left
        time.sleep(0.01)


def interrupt_while_writing(arguments, folder, sent, group=False):
    """Runs sphcover and sends `sent` (to its whole process group if `group`) as soon as a
    staging folder appears in `folder`; returns the finished process and whether the signal
    arrived during the write."""
    for _ in range(8):
        run = subprocess.Popen([sphcover, *arguments], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, start_new_session=group)
        caught = False
        while run.poll() is None:
            if any(".sphcover-" in name for name in os.listdir(folder)):
                if group:
                    os.killpg(run.pid, sent)
                else:
                    run.send_signal(sent)
                caught = True
                break
            time.sleep(0.0005)
        out, err = run.communicate(timeout=300)
        if caught and run.returncode == -sent:
            return run, err, True
    return run, err, False


with tempfile.TemporaryDirectory() as folder:
    solution = os.path.join(folder, "solution.vtm")
    first = subprocess.run([sphcover, "solve", scene, "-o", solution, *coarse],
                           capture_output=True, text=True, timeout=600)
    if first.returncode != 0:
        print(first.stderr)
        sys.exit(1)
    before = snapshot(folder)
    # A signal that arrives while the output is moved into place waits for the move: then the
    # new solution is there, complete (as this run writes it), instead of the old one.
    arguments = ["solve", scene, "-o", solution, *coarse, "--set", "theta_bins=12"]
    with tempfile.TemporaryDirectory() as other:
        complete = subprocess.run([sphcover, *arguments[:3], os.path.join(other, "solution.vtm"),
                                   *arguments[4:]], capture_output=True, timeout=600)
        after = snapshot(other)
    whole = [before, after]

    for sent in (signal.SIGINT, signal.SIGTERM):
        run, err, caught = interrupt_while_writing(arguments, folder, sent)
        name = signal.Signals(sent).name
        if not caught:
            failures.append(f"{name}: never arrived during the write (exit {run.returncode})")
            continue
        lines = err.strip().splitlines()
        if lines != ["sphcover: interrupted"]:
            failures.append(f"{name}: stderr {err!r}, expected one line 'sphcover: interrupted'")
        if leftovers(folder):
            failures.append(f"{name}: left {leftovers(folder)}")
        if snapshot(folder) not in whole:
            failures.append(f"{name}: the solution is neither the earlier one nor the new one")
        if snapshot(folder) == after:
            before = after  # what the next run must leave intact
        print(f"{name} during the write: exit {run.returncode}, left {leftovers(folder)}")

    # Interrupted before any output: nothing written, the report of an earlier run intact.
    run = subprocess.Popen([sphcover, "render", scene, "-o", os.path.join(folder, "image.exr"),
                            "--report", os.path.join(folder, "image.json"), *coarse],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.0)
    run.send_signal(signal.SIGINT)
    run.communicate(timeout=300)
    if run.returncode != -signal.SIGINT:
        failures.append(f"SIGINT during the solve: exit {run.returncode}")
    if snapshot(folder) != before or leftovers(folder):
        failures.append(f"SIGINT during the solve: files changed {sorted(snapshot(folder))}")

    # SIGKILL cannot be handled, but the janitor process removes the staging folder when
    # sphcover is gone.
    run, err, caught = interrupt_while_writing(arguments, folder, signal.SIGKILL)
    if not caught:
        failures.append("SIGKILL never arrived during the write")
    elif leftovers(folder) or snapshot(folder) not in whole:
        failures.append(f"SIGKILL: left {leftovers(folder)}, solution whole: "
                        f"{snapshot(folder) in whole}")
    # SIGKILL to the process group kills the janitor too: the staging folder stays, named after
    # the run, and the next run writing into this folder removes it.
    run, err, caught = interrupt_while_writing(arguments, folder, signal.SIGKILL, group=True)
    if not caught:
        failures.append("SIGKILL of the group never arrived during the write")
    else:
        left = leftovers(folder, wait=0.5)
        print(f"SIGKILL of the process group during the write left {left}")
        if len(left) != 1 or not left[0].startswith(f".solution.vtm.sphcover-{run.pid}."):
            failures.append(f"SIGKILL of the group: left {left}, "
                            f"expected .solution.vtm.sphcover-{run.pid}.*")
        if {k: v for k, v in snapshot(folder).items() if not k.startswith(".")} not in whole:
            failures.append("SIGKILL of the group: the solution is not whole")
        report = os.path.join(folder, "report.json")
        again = subprocess.run([sphcover, "solve", scene, "--report", report, *coarse],
                               capture_output=True, text=True, timeout=600)
        if again.returncode != 0 or leftovers(folder, wait=0):
            failures.append(f"the next run left {leftovers(folder)} ({again.stderr.strip()})")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
