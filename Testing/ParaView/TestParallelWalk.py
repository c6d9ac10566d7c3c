"""Issue 19: a distributed solution renders and walks in pvbatch. parallel_walk.py (the mixed
box's solution shown with the View-Dependent Radiance representation along five cameras) runs
serially (pvbatch) and on two ranks (`mpiexec -n 2 pvbatch --symmetric`, through
RunParallelPvbatch.py: every rank completes, no error or warning); every frame of the two runs
is the same image (within 1 byte per channel: compositing). Frames must not be black.
Without mpiexec the test is skipped (exit 77).

usage: TestParallelWalk.py PVBATCH PLUGIN DATA"""
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

pvbatch, plugin, data = sys.argv[1:4]
if shutil.which("mpiexec") is None:
    print("SKIPPED: mpiexec is not on the PATH (install mpi-default-bin to run the parallel test)")
    sys.exit(77)
here = os.path.dirname(os.path.abspath(__file__))
script = os.path.join(here, "parallel_walk.py")
folder = tempfile.mkdtemp()
serial_out = os.path.join(folder, "serial")
parallel_out = os.path.join(folder, "parallel")
os.makedirs(serial_out)
os.makedirs(parallel_out)
failures = []
serial = subprocess.run([pvbatch, script, plugin, data, serial_out], capture_output=True,
                        text=True, timeout=600)
print(serial.stdout + serial.stderr)
if serial.returncode != 0 or "rank 0 of 1: pipeline completed" not in serial.stdout:
    failures.append(f"the serial run failed (exit {serial.returncode})")
parallel = subprocess.run([sys.executable, os.path.join(here, "RunParallelPvbatch.py"), "2",
                           pvbatch, script, plugin, data, parallel_out],
                          capture_output=True, text=True, timeout=900)
print(parallel.stdout + parallel.stderr)
if parallel.returncode != 0:
    failures.append(f"the run on two ranks failed (exit {parallel.returncode})")


def pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    values = vtk_to_numpy(image.GetPointData().GetScalars())
    return values.reshape(height, width, -1)[:, :, :3].astype(int)


for k in range(5):
    a_path = os.path.join(serial_out, f"frame_{k}.png")
    b_path = os.path.join(parallel_out, f"frame_{k}.png")
    if not (os.path.exists(a_path) and os.path.exists(b_path)):
        failures.append(f"frame {k}: missing")
        continue
    a, b = pixels(a_path), pixels(b_path)
    lit = (a.max(axis=2) > 10).mean()
    difference = np.abs(a - b).max()
    print(f"frame {k}: {lit:.0%} of the pixels lit, largest difference serial / 2 ranks "
          f"{difference}")
    if lit < 0.25:
        failures.append(f"frame {k}: only {lit:.0%} of the pixels are lit")
    if a.shape != b.shape or difference > 1:
        failures.append(f"frame {k}: the two ranks' image differs from the serial one by "
                        f"{difference} (more than 1)")
shutil.rmtree(folder, ignore_errors=True)
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
