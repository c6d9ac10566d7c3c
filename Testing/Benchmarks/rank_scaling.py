"""Rank scaling: one solve on 1 rank against the same solve on K ranks (issue 19).

Runs from the source tree after building sphcover, with OpenMPI's mpiexec on the path:

    /usr/bin/python3 Testing/Benchmarks/rank_scaling.py --build build --json scaling.json

For each scene (default: the Cornell box and the teapot room) it runs

    sphcover solve SCENE --threads 1 -q --report R.json [--set k=v ...]
    mpiexec -n K sphcover solve SCENE --threads 1 -q --report R.json [--set k=v ...]

in turn, --repeats times (the two alternate, so that the shared machine's load of the moment
falls on both alike), and prints per scene the fastest wall time of each (the whole process,
mpiexec's start included), their ratio, the reports' stages and per-rank figures (cover rows,
propagation state, peak resident memory) and whether the two reports' results are equal (the
surfaces' mean radiances and the form factors: a distributed solve must give the serial one).
One thread per rank, so that K ranks use K cores. As root, OpenMPI needs
OMPI_ALLOW_RUN_AS_ROOT=1 and OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 (set here when running as root).
--mca key=value passes an Open MPI parameter to mpiexec (`--mca pml=ob1`: on one machine,
shared memory without UCX, whose start costs about 0.2 s a run here). Each alternating pair's
ratio is printed too: on a shared machine their spread shows the noise.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

SCENES = ("cornell_box", "teapot_room")


def solve(binary, scene, ranks, sets, mca, report):
    command = [binary, "solve", scene, "--threads", "1", "-q", "--report", report]
    for item in sets:
        command += ["--set", item]
    if ranks > 1:
        launcher = ["mpiexec", "-n", str(ranks)]
        for item in mca:
            key, _, value = item.partition("=")
            launcher += ["--mca", key, value]
        command = launcher + command
    start = time.monotonic()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    seconds = time.monotonic() - start
    with open(report) as f:
        return seconds, json.load(f)


def results(report):
    """What must not depend on the ranks: per surface its mean radiance and form factors."""
    return json.dumps({"surfaces": report.get("surfaces"),
                       "form_factors": report.get("form_factors")}, sort_keys=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--scene", action="append",
                        help="a scene of Data/scenes (repeatable; default: %s)" % ", ".join(SCENES))
    parser.add_argument("--set", action="append", default=[], dest="sets",
                        help="a scene setting, as sphcover's --set (repeatable)")
    parser.add_argument("--mca", action="append", default=[],
                        help="an Open MPI parameter for mpiexec, key=value (repeatable)")
    parser.add_argument("--json", help="write the figures here")
    args = parser.parse_args()
    if os.geteuid() == 0:
        os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
        os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    binary = os.path.join(args.build, "bin", "sphcover")
    data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data", "scenes")
    figures = {"ranks": args.ranks, "repeats": args.repeats, "sets": args.sets, "mca": args.mca,
               "load_average_at_start": os.getloadavg()[0], "scenes": {}}
    with tempfile.TemporaryDirectory() as folder:
        for name in args.scene or SCENES:
            scene = os.path.join(data, name + ".scene")
            best = {}
            pairs = []
            for repeat in range(args.repeats):
                pair = {}
                for ranks in (1, args.ranks):
                    report_path = os.path.join(folder, "%s-%d.json" % (name, ranks))
                    seconds, report = solve(binary, scene, ranks, args.sets, args.mca,
                                            report_path)
                    print("%s, %d rank(s), run %d: %.2f s" % (name, ranks, repeat + 1, seconds),
                          flush=True)
                    pair[ranks] = seconds
                    if ranks not in best or seconds < best[ranks][0]:
                        best[ranks] = (seconds, report)
                pairs.append(pair[args.ranks] / pair[1])
            one, many = best[1], best[args.ranks]
            entry = {
                "wall_s": {"1": one[0], str(args.ranks): many[0]},
                "ratio": many[0] / one[0],
                "pair_ratios": pairs,
                "results_equal": results(one[1]) == results(many[1]),
                "shots": {"1": one[1]["counts"].get("shots"),
                          str(args.ranks): many[1]["counts"].get("shots")},
            }
            for key in ("timings_s", "cover_stages_s", "peak_resident_bytes", "cover_ranks",
                        "propagation_ranks", "memory_bytes"):
                entry[key] = {"1": one[1].get(key), str(args.ranks): many[1].get(key)}
            figures["scenes"][name] = entry
            peaks = entry["peak_resident_bytes"]
            print("%s: %.2f s on 1 rank, %.2f s on %d ranks: %.2fx (pairs %s); results equal: %s; "
                  "peak resident MB per rank: %s against %s" % (
                      name, one[0], many[0], args.ranks, entry["ratio"],
                      ", ".join("%.2f" % r for r in pairs), entry["results_equal"],
                      [round(b / 1e6, 1) for b in peaks[str(args.ranks)] or []],
                      [round(b / 1e6, 1) for b in peaks["1"] or []]), flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(figures, f, indent=2)
    return 0 if all(s["results_equal"] for s in figures["scenes"].values()) else 1


if __name__ == "__main__":
    sys.exit(main())
