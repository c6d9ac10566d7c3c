"""Runs a pvbatch script under `mpiexec -n RANKS pvbatch --symmetric` and checks that every rank
completed ("rank k of RANKS: pipeline completed"), the exit status is 0 and no rank printed a
VTK error or warning. Without mpiexec on the PATH the test is skipped (exit 77) with a message.

usage: RunParallelPvbatch.py RANKS PVBATCH SCRIPT [ARGS...]"""
import re
import shutil
import subprocess
import sys

ranks, pvbatch, script, *arguments = sys.argv[1:]
mpiexec = shutil.which("mpiexec")
if mpiexec is None:
    print("SKIPPED: mpiexec is not on the PATH (install mpi-default-bin to run the parallel test)")
    sys.exit(77)

# --allow-run-as-root: Open MPI refuses root otherwise (CI containers run as root);
# --oversubscribe: the test may run on a machine with fewer cores than ranks.
command = [mpiexec, "--allow-run-as-root", "--oversubscribe", "-n", ranks, pvbatch, "--symmetric",
           script, *arguments]
result = subprocess.run(command, capture_output=True, text=True, timeout=600)
output = result.stdout + result.stderr
print(output)
failures = []
if result.returncode != 0:
    failures.append(f"exit status {result.returncode}")
for rank in range(int(ranks)):
    if f"rank {rank} of {ranks}: pipeline completed" not in output:
        failures.append(f"rank {rank} did not complete the pipeline")
for line in output.splitlines():
    if re.match(r"\s*(\x1b\[[0-9;]*m)?(ERROR|Warning|WARNING|FAILED)\b", line):
        failures.append(f"a rank reported: {line.strip()}")
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
