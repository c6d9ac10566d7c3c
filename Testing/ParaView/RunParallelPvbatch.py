"""Runs a pvbatch script under `mpiexec -n RANKS pvbatch --symmetric` and checks that every rank
completed ("rank k of RANKS: pipeline completed"), the exit status is 0 and no rank printed a
VTK error or warning. Without mpiexec on the PATH the test is skipped (exit 77) with a message.

usage: RunParallelPvbatch.py RANKS PVBATCH SCRIPT [ARGS...]"""
import os
import re
import shutil
import subprocess
import sys

ranks, pvbatch, script, *arguments = sys.argv[1:]
mpiexec = shutil.which("mpiexec")
if mpiexec is None:
    print("SKIPPED: mpiexec is not on the PATH (install mpi-default-bin to run the parallel test)")
    sys.exit(77)

# Open MPI (Debian's default MPI) refuses to run as root, as CI containers do, and to start more
# ranks than cores unless told; its environment variables say so (the command-line flags
# --allow-run-as-root and --oversubscribe would break other MPI implementations).
environment = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")
command = [mpiexec, "-n", ranks, pvbatch, "--symmetric", script, *arguments]
result = subprocess.run(command, capture_output=True, text=True, timeout=600, env=environment)
output = result.stdout + result.stderr
print(output)
failures = []
if result.returncode != 0:
    failures.append(f"exit status {result.returncode}")
for rank in range(int(ranks)):
    if f"rank {rank} of {ranks}: pipeline completed" not in output:
        failures.append(f"rank {rank} did not complete the pipeline")
# VTK's messages: "ERR|"/"WARN|" in ParaView's log format, "ERROR:"/"Warning:" in VTK's own.
for line in output.splitlines():
    if re.search(r"\b(ERR|WARN)\||\b(ERROR|Warning|WARNING):|^\s*FAILED", line):
        failures.append(f"a rank reported: {line.strip()}")
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
