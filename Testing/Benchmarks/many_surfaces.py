"""Scenes of many named surfaces (issue 39, item 2): load time and peak memory against the count.

Runs from the source tree after building sphcover:

    /usr/bin/python3 Testing/Benchmarks/many_surfaces.py --build build [--counts 1000,5000,20000]
        [--solve] [--json figures.json]

For each count n it writes a closed room of about n named quads (Data/scenes/tools/tiled_room.py:
its six walls, each cut into k x k tiles, k = round(sqrt(n / 6)); one ceiling tile is the lamp,
every tile a surface of its own name and, with --materials, a material of its own) and runs,
each as a child process whose wall seconds and peak resident memory (wait4's ru_maxrss) are
measured:

    sphcover info ROOM.scene                      (reading alone: the loader)
    sphcover solve ROOM.scene --report R.json ... (with --solve: the whole method, at settings
                                                   that keep the points few: one patch per
                                                   tile, a 4 x 16 hemisphere grid, no nodes;
                                                   with --render, render and a 64 x 64 view)

--address-limit MIB runs each child under that address-space limit (ulimit -v): a run that would
exhaust the machine fails instead (the dense form factors of 20,000 surfaces took 17 GB).

and prints one line per count. The figures are in Documentation/notes/many-surfaces.md.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data",
                                "scenes", "tools"))
from tiled_room import write_room  # noqa: E402


def run_measured(command, address_limit_mib=0):
    """The child's wall seconds, peak resident MiB, stderr and exit code (wait4: its own rusage).

    With address_limit_mib the child runs under that address-space limit (`ulimit -v`, set by
    the shell it is exec'd from), so that a run that would exhaust the machine fails in it
    instead. No preexec_fn: with one Python forks instead of vforking, and the child's peak
    would start at this interpreter's (which holds the last report read).
    """
    if address_limit_mib > 0:
        command = ["sh", "-c", f'ulimit -v {address_limit_mib * 1024} && exec "$0" "$@"'] + command
    start = time.monotonic()
    child = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    stderr = child.stderr.read().decode()
    _, status, usage = os.wait4(child.pid, 0)
    seconds = time.monotonic() - start
    child.returncode = os.waitstatus_to_exitcode(status)
    return seconds, usage.ru_maxrss / 1024.0, stderr, child.returncode


def report_figures(report):
    """The points, pairs and imbalance of a report, read by a child interpreter.

    A child, because a forked process's peak resident memory starts at its parent's: this one
    must not hold a large report (the dense matrix of 5,000 surfaces is 322 MiB of JSON, 1 GB
    parsed) when it starts the next measured run.
    """
    script = """
import json, sys
r = json.load(open(sys.argv[1]))
f = r["form_factors"]
# A report from before the pairs has the dense matrix alone.
pairs = len(f["pairs"]) if "pairs" in f else sum(1 for row in f["matrix"] for v in row if v != 0.0)
print(json.dumps({"points": r["counts"]["characteristic_points"], "pairs": pairs,
                  "imbalance": r["energy"]["relative_imbalance"]}))
"""
    return json.loads(subprocess.run([sys.executable, "-c", script, report], check=True,
                                     capture_output=True, text=True).stdout)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--counts", default="1000,5000,20000")
    parser.add_argument("--materials", action="store_true",
                        help="give every tile a material of its own")
    parser.add_argument("--solve", action="store_true", help="also time sphcover solve")
    parser.add_argument("--binary", help="the sphcover to run (default: BUILD/bin/sphcover)")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--address-limit", type=int, default=0, metavar="MIB",
                        help="run sphcover under this address-space limit (ulimit -v)")
    parser.add_argument("--render", action="store_true",
                        help="render (a 64 x 64 view) instead of solve")
    parser.add_argument("--json", help="write the figures here")
    arguments = parser.parse_args()
    binary = arguments.binary or os.path.join(arguments.build, "bin", "sphcover")
    if not os.path.exists(binary):
        sys.exit(f"no {binary}: build sphcover first")
    figures = []
    with tempfile.TemporaryDirectory() as folder:
        for count in [int(c) for c in arguments.counts.split(",")]:
            scene = os.path.join(folder, f"room_{count}.scene")
            surfaces = write_room(scene, count, arguments.materials)
            row = {"surfaces": surfaces, "file_mib": os.path.getsize(scene) / 2**20}
            seconds, peak, stderr, code = run_measured([binary, "info", scene],
                                                       arguments.address_limit)
            if code != 0:
                sys.exit(f"info {surfaces} surfaces failed: {stderr.strip()}")
            row.update(load_s=seconds, load_peak_mib=peak)
            line = (f"{surfaces:6d} surfaces ({row['file_mib']:.1f} MiB of JSON): "
                    f"load {seconds:7.2f} s, peak {peak:7.1f} MiB")
            if arguments.solve:
                report = os.path.join(folder, f"room_{count}.json")
                command = [binary, "render" if arguments.render else "solve", scene, "--report",
                           report, "-q", "--direct-nodes", "0", "--threads",
                           str(arguments.threads)]
                if arguments.render:
                    command += ["-o", os.path.join(folder, f"room_{count}.png")]
                seconds, peak, stderr, code = run_measured(command, arguments.address_limit)
                if code != 0:
                    line += f"; {command[1]} failed ({seconds:.1f} s, peak {peak:.0f} MiB): " + \
                        stderr.strip().splitlines()[-1]
                    row.update(solve_s=seconds, solve_peak_mib=peak, solve_error=stderr.strip())
                else:
                    counted = report_figures(report)
                    pairs = counted["pairs"]
                    row["report_mib"] = os.path.getsize(report) / 2**20
                    row.update(solve_s=seconds, solve_peak_mib=peak, **counted)
                    line += (f"; {command[1]} {seconds:7.2f} s, peak {peak:7.1f} MiB, "
                             f"{row['points']} points, {pairs} pairs, report "
                             f"{row['report_mib']:.1f} MiB")
            print(line, flush=True)
            figures.append(row)
    if arguments.json:
        with open(arguments.json, "w") as f:
            json.dump(figures, f, indent=1)


if __name__ == "__main__":
    main()
