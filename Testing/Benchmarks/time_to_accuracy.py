"""Time to accuracy: SphericalCover's first view against Blender Cycles at equal error (issue 16).

Runs under /usr/bin/python3 (numpy, ParaView's vtkmodules) from the source tree, after building
sphcover and the Python package:

    /usr/bin/python3 Testing/Benchmarks/time_to_accuracy.py --build build --json tta.json

In one run it

1. renders the Cornell box (Data/scenes/cornell_box.scene) with `sphcover render SCENE -o X.exr
   --report X.json --size 256x256 --spp 16 --threads T --quiet [--set k=v ...]` for each run
   (default: the scene's settings, --set max_level=3, --set max_level=4; `--run "label:ARGS"`,
   repeated, replaces the list), each as a child process whose processor seconds (user + sys,
   os.wait4) and peak resident memory (ru_maxrss) are measured; the per-stage processor seconds
   are the report's `timings_cpu_s`. The first run (or every run with --all-512) is rendered
   again at the reference's 512 x 512 (another whole child process: the solve is repeated);
2. compares each image with Data/reference/cornell_box_cycles.exr (Cycles, 512 x 512, 4 x 2048
   spp, box pixel filter of 1 pixel: a pixel is the mean radiance over its area) by the issue's
   metric: the relative RMS over blocks of the luminance block means,

       Y = 0.2126 R + 0.7152 G + 0.0722 B,
       e = sqrt( mean over lit blocks b of ((A_b - B_b) / B_b)^2 ),

   A_b, B_b the image's and the reference's mean Y over block b, a block lit when B_b > 1e-3
   of the reference's mean Y (compare_sphcover.DARK_FRACTION). Two grids of blocks: 16 x 16
   ("16-px" blocks at 256 x 256) and 64 x 64 ("4-px" blocks at 256 x 256). A 256 x 256 image
   is compared with the reference box-downsampled 2 x 2 (a pixel's mean over its area, the
   same filter as both renderers'), a 512 x 512 image with the reference itself; the same
   grids, so the same regions (32- and 8-px blocks at 512 x 512);
3. when `blender` is on the path (and not --no-cycles), renders Cycles with
   Data/reference/render_cycles.py at --cycles-spp (16, 64, 256, 1024) spp, 256 x 256, seed
   --cycles-seed (7: not one of the reference's seeds 0-3) and the same --threads, measuring the
   blender child in the same way, and its errors on both grids; plus one render at 1 spp, shown
   as a separate column ("blender 1 spp", the fixed cost of starting Blender and building its
   scene). Nothing is subtracted: both sides are the whole process's processor seconds;
4. prints, per sphcover run and grid (at 256 x 256), the Cycles processor seconds that reach
   the same error, interpolated log-log between the bracketing Cycles points, or extrapolated
   beyond them with error ~ time^-1/2 (marked "x": below 16 spp the extrapolation ignores
   Blender's fixed cost, so the real Cycles time would be higher), and the ratio sphcover cpu /
   Cycles cpu (< 1: sphcover is faster);
5. prints a Markdown table and, with --json FILE, writes all the numbers.

sphcover's samples (Core/render/RadianceRenderer.h): --spp stratified, deterministic positions in
each pixel (Hammersley: one per column of width 1/N, the rows by the base-2 radical inverse,
the same positions in every pixel), Radiance their mean: a box filter over the pixel, as
Cycles' 1-pixel box filter, whose samples are random.

`--scene teapot_room` (or any scene without a reference): times and memory only, no Cycles.

`--suite`: the same for every scene of SUITE in one invocation (issue 38: rooms of different
kinds, each at the filters' defaults, i.e. without its file's `settings` block, which is left out
of a temporary copy of the scene), each against its own Cycles reference and Cycles at
--cycles-spp in the same run, then one summary table: per scene and run, sphcover's processor
seconds and errors beside Cycles-64's, and whether both errors and the time are at most
Cycles-64's.

`--scaling`: `sphcover solve` of the Cornell box at max_level 2, 3, 4, 5 on 1 and 2 threads; the
cover's and the propagation's processor and wall seconds, the cover's bytes, the strips and the
points (the report's counts, `timings_cpu_s`, `timings_s`, `memory_bytes`), the fitted exponent
(least squares of log processor seconds against log points) and the 2-thread speed-up (1-thread
wall seconds / 2-thread wall seconds) of each stage and of the whole process.

Times are noisy on a shared machine: the ratios of paired runs in one invocation are what to
compare between invocations.
"""
import argparse
import json
import math
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DATA = os.path.join(ROOT, "Data")
sys.path.insert(0, os.path.join(DATA, "reference"))

import compare_sphcover  # noqa: E402

CORNELL = os.path.join(DATA, "scenes", "cornell_box.scene")
# --suite: (scene, its Cycles reference in Data/reference, what kind of room it is).
SUITE = (
    ("cornell_box", "cornell_box_cycles.exr", "the Cornell box (mm, a small lamp, blocks)"),
    ("metre_room", "metre_room_cycles.exr", "4 x 3 x 5 m, a large ceiling panel, a bicubic mound"),
    ("gap_room", "gap_room_cycles.exr", "the viewed half lit only through a gap"),
    ("window_room", "window_room_cycles.exr", "lit only through a window pane"),
    # A perfect mirror's reference is the room unfolded across the mirror plane, all diffuse: the
    # same picture (Cycles' sharp glossy is no reference for a mirror, issue 39), so Cycles
    # renders the unfolded room for its time and error.
    ("mirror_room", "mirror_room_unfolded_cycles.exr", "a perfect mirror wall",
     "mirror_room_unfolded"),
    ("glossy_room", "glossy_room_cycles.exr", "a GGX glossy floor (Cycles' own lobe, tabulated)"),
)
RENDER_CYCLES = os.path.join(DATA, "reference", "render_cycles.py")
# Rec. 709 luminance of linear RGB.
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])
# Blocks across the image of the two grids: 16-px and 4-px blocks at 256 x 256.
GRIDS = (16, 64)
STAGES = ("subdivide", "cover", "propagate", "render")


# ---------------------------------------------------------------------------------- the metric

def luminance(image):
    """Y of an array [row, column, channel] of linear RGB: [row, column]."""
    return np.asarray(image, dtype=np.float64)[..., :3] @ LUMINANCE


def downsample(image, factor):
    """Box-downsampled by an integer factor: each pixel the mean of factor x factor pixels (the
    mean over its area, the pixel filter of both renderers)."""
    if factor == 1:
        return image
    if image.ndim == 2:
        return compare_sphcover.block_means(image[..., None], factor)[..., 0]
    return compare_sphcover.block_means(image, factor)


def luminance_block_error(image, reference, blocks):
    """The relative RMS over lit blocks of the luminance block means of `image` against
    `reference` (arrays [row, column, channel]) on a grid of `blocks` x `blocks` blocks, each
    image divided at its own resolution (the same regions); blocks whose reference mean is below
    DARK_FRACTION of the reference's mean Y are left out. Returns (error, lit blocks)."""
    for array in (image, reference):
        if array.shape[0] % blocks or array.shape[1] % blocks:
            raise ValueError(f"{array.shape[1]} x {array.shape[0]} pixels do not divide into "
                             f"{blocks} x {blocks} blocks")
    if image.shape[0] * reference.shape[1] != image.shape[1] * reference.shape[0]:
        raise ValueError("the image and the reference differ in aspect")
    y_image, y_reference = luminance(image), luminance(reference)
    a = downsample(y_image, y_image.shape[0] // blocks)
    b = downsample(y_reference, y_reference.shape[0] // blocks)
    lit = b > compare_sphcover.DARK_FRACTION * y_reference.mean()
    if not lit.any():
        raise ValueError("no lit block in the reference")
    relative = (a[lit] - b[lit]) / b[lit]
    return math.sqrt((relative ** 2).mean()), int(lit.sum())


def errors_against(image, reference):
    """{grid: error} for the GRIDS, the reference box-downsampled to the image's resolution
    first when it is an integer multiple of it (the same block means, computed as the issue
    states it)."""
    factor = reference.shape[0] // image.shape[0]
    if factor > 1 and reference.shape[0] == factor * image.shape[0]:
        reference = downsample(reference, factor)
    return {grid: luminance_block_error(image, reference, grid)[0] for grid in GRIDS}


# ----------------------------------------------------------------------------- child processes

def run_child(command, log_prefix):
    """Runs `command`, its output in log files; returns (exit code, processor seconds user +
    sys, peak RSS in MiB, wall seconds) of that child alone (os.wait4)."""
    with open(log_prefix + ".out", "w") as out, open(log_prefix + ".err", "w") as err:
        start = time.perf_counter()
        child = subprocess.Popen(command, stdout=out, stderr=err)
        _, status, usage = os.wait4(child.pid, 0)
        wall = time.perf_counter() - start
    child.returncode = os.waitstatus_to_exitcode(status)
    # ru_maxrss is in KiB on Linux.
    return child.returncode, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0, wall


def fail_child(what, code, log_prefix):
    with open(log_prefix + ".err") as err:
        tail = err.read().strip().splitlines()[-5:]
    raise RuntimeError(f"{what} failed (exit {code}): " + " | ".join(tail))


def sphcover_render(args, label, extra, size, folder):
    """One `sphcover render` child: its figures, report and image."""
    tag = f"{slug(label)}_{size[0]}x{size[1]}"
    exr = os.path.join(folder, tag + ".exr")
    report_file = os.path.join(folder, tag + ".json")
    command = [args.sphcover, "render", args.scene, "-o", exr, "--report", report_file,
               "--size", f"{size[0]}x{size[1]}", "--spp", str(args.spp), "--threads",
               str(args.threads), "--quiet", *extra]
    print(f"# sphcover {label} at {size[0]}x{size[1]}: {shlex.join(command)}", file=sys.stderr)
    code, cpu, rss, wall = run_child(command, os.path.join(folder, tag))
    if code != 0:
        fail_child(f"sphcover {label}", code, os.path.join(folder, tag))
    report = json.load(open(report_file))
    counts = report.get("counts", {})
    return {"command": command, "size": list(size), "cpu_s": cpu, "wall_s": wall,
            "peak_mib": rss, "points": counts.get("characteristic_points"),
            "strips": counts.get("strips"), "timings_cpu_s": report.get("timings_cpu_s", {}),
            "timings_s": report.get("timings_s", {}),
            "memory_bytes": report.get("memory_bytes", {}), "exr": exr}


def cycles_render(args, samples, folder):
    """One Blender child rendering the scene with Cycles at `samples` spp, 256 x 256 (or --size)."""
    tag = f"cycles_{samples}spp"
    exr = os.path.join(folder, tag + ".exr")
    command = [args.blender, "-b", "--factory-startup", "--python", RENDER_CYCLES, "--",
               "--scene", getattr(args, "cycles_scene", None) or args.scene, "--out", exr, "--samples", str(samples), "--seed",
               str(args.cycles_seed), "--threads", str(args.threads), "--width",
               str(args.size[0]), "--height", str(args.size[1])]
    print(f"# cycles {samples} spp: {shlex.join(command)}", file=sys.stderr)
    code, cpu, rss, wall = run_child(command, os.path.join(folder, tag))
    if code != 0 or not os.path.isfile(exr):
        fail_child(f"blender {samples} spp", code, os.path.join(folder, tag))
    return {"command": command, "samples": samples, "cpu_s": cpu, "wall_s": wall,
            "peak_mib": rss, "exr": exr}


def slug(label):
    return "".join(c if c.isalnum() else "_" for c in label).strip("_") or "run"


# ------------------------------------------------------------------------- equal-error times

def equal_error_time(cycles_points, error):
    """The Cycles processor seconds at which its error is `error`: log-log interpolation between
    the first pair of consecutive points (by time) that brackets it, else extrapolation from the
    nearest end with error ~ time^-1/2 (time ~ error^-2). `cycles_points`: (seconds, error),
    sorted by seconds. Returns (seconds, how): how is "interpolated", "extrapolated below" (the
    error is above every Cycles point's) or "extrapolated above"."""
    points = [(t, e) for t, e in cycles_points if t > 0 and e > 0]
    if not points or not error > 0:
        return None, None
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if min(e0, e1) <= error <= max(e0, e1):
            if e0 == e1:
                return t0, "interpolated"
            s = (math.log(error) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + s * (math.log(t1) - math.log(t0))), "interpolated"
    # Not bracketed: above every point's error (cheaper than the fewest samples) or below
    # every one's (dearer than the most).
    if error > max(e for _, e in points):
        t, e = points[0]
        return t * (e / error) ** 2, "extrapolated below"
    t, e = points[-1]
    return t * (e / error) ** 2, "extrapolated above"


# ------------------------------------------------------------------------------------ the modes

def accuracy_mode(args, folder):
    reference = compare_sphcover.read_exr(args.reference) if args.reference else None
    results = {"scene": args.scene, "reference": args.reference, "size": list(args.size),
               "spp": args.spp, "threads": args.threads, "grids": list(GRIDS), "runs": [],
               "cycles": [], "cycles_startup": None}
    for k, (label, extra) in enumerate(args.runs):
        run = {"label": label, "args": extra}
        run["at"] = {"256": sphcover_render(args, label, extra, args.size, folder)}
        if reference is not None:
            image = compare_sphcover.read_exr(run["at"]["256"]["exr"])
            run["at"]["256"]["errors"] = errors_against(image, reference)
            size = (reference.shape[1], reference.shape[0])
            if (k == 0 or args.all_512) and size != tuple(args.size):
                run["at"]["512"] = sphcover_render(args, label, extra, size, folder)
                image = compare_sphcover.read_exr(run["at"]["512"]["exr"])
                run["at"]["512"]["errors"] = errors_against(image, reference)
        results["runs"].append(run)
    if reference is not None and args.blender:
        if args.cycles_startup:
            results["cycles_startup"] = cycles_render(args, 1, folder)
        for samples in args.cycles_spp:
            point = cycles_render(args, samples, folder)
            point["errors"] = errors_against(compare_sphcover.read_exr(point["exr"]), reference)
            results["cycles"].append(point)
        for run in results["runs"]:
            run["equal_error"] = {}
            for grid in GRIDS:
                curve = sorted((p["cpu_s"], p["errors"][grid]) for p in results["cycles"])
                error = run["at"]["256"]["errors"][grid]
                seconds, how = equal_error_time(curve, error)
                entry = {"cycles_cpu_s": seconds, "how": how,
                         "ratio": run["at"]["256"]["cpu_s"] / seconds if seconds else None}
                startup = results["cycles_startup"]
                if how == "extrapolated below" and startup:
                    # Below the fewest samples the fixed cost stays: time = t1 + (t - t1)
                    # (e / error)^2 with t1 the 1-spp time, more than the bare time^-1/2 law.
                    t, e = curve[0]
                    fixed = startup["cpu_s"] + max(t - startup["cpu_s"], 0.0) * (e / error) ** 2
                    entry["cycles_cpu_s_fixed_cost"] = fixed
                    entry["ratio_fixed_cost"] = run["at"]["256"]["cpu_s"] / fixed
                run["equal_error"][grid] = entry
    return results


def percent(value):
    return "" if value is None else f"{100.0 * value:.2f} %"


def accuracy_table(results):
    startup = results.get("cycles_startup")
    lines = [
        "| run | points | strips | cpu s total | cpu s subdivide / cover / propagate / render "
        "| peak MiB | error 16-px @256 | error 4-px @256 | error 16-px @512 | error 4-px @512 "
        "| time ratio at equal error (16-px / 4-px) |",
        "|---|---|---|---|---|---|---|---|---|---|---|"]
    for run in results["runs"]:
        at = run["at"]["256"]
        stages = " / ".join(f"{at['timings_cpu_s'].get(s, float('nan')):.1f}" for s in STAGES)
        errors = at.get("errors", {})
        errors512 = run["at"].get("512", {}).get("errors", {})
        ratio = ""
        if run.get("equal_error"):
            ratio = " / ".join(
                f"{e['ratio']:.2f}{'x' if e['how'] != 'interpolated' else ''}"
                for e in (run["equal_error"][g] for g in GRIDS))
        strips = at["strips"]
        lines.append(
            f"| sphcover {run['label']} | {at['points']} | "
            f"{strips / 1e6:.2f}M | {at['cpu_s']:.1f} | {stages} | {at['peak_mib']:.0f} | "
            f"{percent(errors.get(16))} | {percent(errors.get(64))} | "
            f"{percent(errors512.get(16))} | {percent(errors512.get(64))} | {ratio} |")
    for point in results["cycles"]:
        lines.append(
            f"| Cycles {point['samples']} spp | | | {point['cpu_s']:.1f} | | "
            f"{point['peak_mib']:.0f} | {percent(point['errors'][16])} | "
            f"{percent(point['errors'][64])} | | | |")
    notes = [f"{results['size'][0]}x{results['size'][1]}, sphcover {results['spp']} spp, "
             f"{results['threads']} threads; cpu s = processor seconds (user + sys) of the whole "
             "process, nothing subtracted."]
    if startup:
        notes.append(f"blender 1 spp (its fixed cost): {startup['cpu_s']:.1f} cpu s, "
                     f"{startup['peak_mib']:.0f} MiB.")
    if results["cycles"]:
        notes.append("time ratio = sphcover cpu s / Cycles cpu s at the same error (@256), "
                     "log-log interpolated between the Cycles points; x: extrapolated with "
                     "error ~ time^-1/2.")
        fixed = [f"{run['label']} {grid}-block grid {e['ratio_fixed_cost']:.2f}"
                 for run in results["runs"] for grid, e in run.get("equal_error", {}).items()
                 if "ratio_fixed_cost" in e]
        if fixed:
            notes.append("below the fewest Cycles samples, keeping Blender's 1-spp time as a "
                         "fixed cost (time = t1 + (t - t1) (e / error)^2): " + ", ".join(fixed)
                         + "; add fewer --cycles-spp (e.g. 4) to bracket instead.")
    return "\n".join(lines) + "\n\n" + "\n".join(notes)


def scene_without_settings(scene, folder):
    """A copy of `scene` in `folder` without its `settings` block (the filters' defaults), its
    relative file names made absolute so that they still resolve."""
    with open(scene) as f:
        data = json.load(f)
    data.pop("settings", None)
    base = os.path.dirname(os.path.abspath(scene))

    def absolute(node):
        if isinstance(node, dict):
            return {k: (os.path.join(base, v) if k in ("file", "texture") and isinstance(v, str)
                        and not os.path.isabs(v) else absolute(v)) for k, v in node.items()}
        if isinstance(node, list):
            return [absolute(v) for v in node]
        return node

    copy = os.path.join(folder, "defaults_" + os.path.basename(scene))
    with open(copy, "w") as f:
        json.dump(absolute(data), f, indent=1)
    return copy


def suite_mode(args, folder):
    """accuracy_mode for every scene of SUITE at the defaults (the settings block left out)."""
    results = []
    for name, reference, kind, *cycles_name in SUITE:
        scene = os.path.join(DATA, "scenes", name + ".scene")
        one = argparse.Namespace(**vars(args))
        sub = os.path.join(folder, name)
        os.makedirs(sub, exist_ok=True)
        one.scene = scene_without_settings(scene, sub)
        if cycles_name:
            cycles_sub = os.path.join(sub, "cycles")
            os.makedirs(cycles_sub, exist_ok=True)
            one.cycles_scene = scene_without_settings(
                os.path.join(DATA, "scenes", cycles_name[0] + ".scene"), cycles_sub)
        one.reference = os.path.join(DATA, "reference", reference)
        print(f"# suite: {name} ({kind})", file=sys.stderr)
        result = accuracy_mode(one, sub)
        result["name"], result["kind"] = name, kind
        results.append(result)
    return results


def suite_table(results):
    lines = ["| scene | run | points | sphcover cpu s | error 16-px / 4-px | Cycles-64 cpu s "
             "| its error 16-px / 4-px | at most Cycles-64's (time, 16-px, 4-px) "
             "| time ratio at equal error (16-px / 4-px) |",
             "|---|---|---|---|---|---|---|---|---|"]
    for result in results:
        c64 = next((p for p in result["cycles"] if p["samples"] == 64), None)
        for run in result["runs"]:
            at = run["at"]["256"]
            e = at.get("errors", {})
            ratio = ""
            if run.get("equal_error"):
                ratio = " / ".join(
                    f"{x['ratio']:.2f}{'x' if x['how'] != 'interpolated' else ''}"
                    for x in (run["equal_error"][g] for g in GRIDS))
            c64_cells = "| |"
            verdict = ""
            if c64:
                c64_cells = (f"| {c64['cpu_s']:.1f} | {percent(c64['errors'][16])} / "
                             f"{percent(c64['errors'][64])} |")
                verdict = ", ".join("yes" if ok else "no" for ok in (
                    at["cpu_s"] <= c64["cpu_s"], e.get(16, 1) <= c64["errors"][16],
                    e.get(64, 1) <= c64["errors"][64]))
            lines.append(f"| {result['name']} | {run['label']} | {at['points']} | "
                         f"{at['cpu_s']:.1f} | {percent(e.get(16))} / {percent(e.get(64))} "
                         f"{c64_cells} {verdict} | {ratio} |")
    return "\n".join(lines)


def scaling_mode(args, folder):
    results = {"scene": args.scene, "levels": args.levels, "threads": [1, 2], "runs": []}
    for threads in (1, 2):
        for level in args.levels:
            tag = f"solve_l{level}_t{threads}"
            report_file = os.path.join(folder, tag + ".json")
            command = [args.sphcover, "solve", args.scene, "--report", report_file,
                       "--threads", str(threads), "--quiet", "--set", f"max_level={level}",
                       *args.solve_args]
            print(f"# {shlex.join(command)}", file=sys.stderr)
            code, cpu, rss, wall = run_child(command, os.path.join(folder, tag))
            if code != 0:
                fail_child(f"solve max_level {level}", code, os.path.join(folder, tag))
            report = json.load(open(report_file))
            results["runs"].append({
                "max_level": level, "threads": threads, "cpu_s": cpu, "wall_s": wall,
                "peak_mib": rss, "points": report["counts"]["characteristic_points"],
                "strips": report["counts"]["strips"], "timings_s": report["timings_s"],
                "timings_cpu_s": report["timings_cpu_s"],
                "memory_bytes": report.get("memory_bytes", {})})
    results["fit"] = {}
    for threads in (1, 2):
        runs = [r for r in results["runs"] if r["threads"] == threads]
        x = np.log([r["points"] for r in runs])
        for stage in ("cover", "propagate"):
            y = np.log([max(r["timings_cpu_s"][stage], 1e-6) for r in runs])
            results["fit"][f"{stage}_t{threads}"] = float(np.polyfit(x, y, 1)[0])
        bytes_ = np.log([max(r["memory_bytes"].get("cover", 0), 1) for r in runs])
        results["fit"][f"cover_bytes_t{threads}"] = float(np.polyfit(x, bytes_, 1)[0])
    results["speedup"] = {}
    for level in args.levels:
        one, two = (next(r for r in results["runs"] if r["max_level"] == level
                         and r["threads"] == t) for t in (1, 2))
        results["speedup"][level] = {
            "cover": one["timings_s"]["cover"] / two["timings_s"]["cover"],
            "propagate": one["timings_s"]["propagate"] / two["timings_s"]["propagate"],
            "process": one["wall_s"] / two["wall_s"]}
    return results


def scaling_table(results):
    lines = ["| max_level | threads | points | strips | cover MiB | incident radiance MiB "
             "| cover cpu s | propagate cpu s | cover wall s | propagate wall s | process cpu s "
             "| process wall s | peak MiB |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results["runs"]:
        mib = {k: v / 2 ** 20 for k, v in r["memory_bytes"].items()}
        lines.append(
            f"| {r['max_level']} | {r['threads']} | {r['points']} | {r['strips']} | "
            f"{mib.get('cover', float('nan')):.1f} | "
            f"{mib.get('incident_radiance', float('nan')):.1f} | "
            f"{r['timings_cpu_s']['cover']:.2f} | {r['timings_cpu_s']['propagate']:.2f} | "
            f"{r['timings_s']['cover']:.2f} | {r['timings_s']['propagate']:.2f} | "
            f"{r['cpu_s']:.1f} | {r['wall_s']:.1f} | {r['peak_mib']:.0f} |")
    fit = results["fit"]
    lines.append("")
    lines.append("fitted exponent (processor seconds ~ points^k, least squares over the levels): "
                 + ", ".join(f"{k} {v:.2f}" for k, v in fit.items()))
    lines.append("2-thread speed-up (1-thread wall / 2-thread wall): " + "; ".join(
        f"max_level {level}: cover {s['cover']:.2f}, propagate {s['propagate']:.2f}, "
        f"process {s['process']:.2f}" for level, s in results["speedup"].items()))
    return "\n".join(lines)


# --------------------------------------------------------------------------------- the command

def parse_size(text):
    return compare_sphcover.parse_size(text)


def parse_run(text):
    label, sep, rest = text.partition(":")
    if not sep or not label:
        raise argparse.ArgumentTypeError(f"'{text}' is not LABEL:ARGS")
    return label, shlex.split(rest)


def parse_list(text):
    try:
        values = [int(v) for v in text.split(",") if v]
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a list of integers") from None
    if not values or min(values) < 1:
        raise argparse.ArgumentTypeError(f"'{text}': positive integers expected")
    return values


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"),
                        help="the build folder (its bin/sphcover and Python package)")
    parser.add_argument("--sphcover", help="the sphcover program (default: BUILD/bin/sphcover)")
    parser.add_argument("--scene", default="cornell_box",
                        help="a scene file or a name in Data/scenes (default cornell_box)")
    parser.add_argument("--reference", help="reference EXR (default: the Cornell box's, for "
                        "the Cornell box only; none: times and memory only)")
    parser.add_argument("--run", type=parse_run, action="append", dest="runs",
                        help="a sphcover run 'LABEL:ARGS' (e.g. 'ml3:--set max_level=3'); "
                        "repeated, replaces the default list")
    parser.add_argument("--size", type=parse_size, default=(256, 256),
                        help="WIDTHxHEIGHT of the runs and of Cycles (default 256x256)")
    parser.add_argument("--spp", type=int, default=16, help="sphcover samples per pixel (16)")
    parser.add_argument("--threads", type=int, default=2, help="threads of both renderers (2)")
    parser.add_argument("--all-512", action="store_true",
                        help="render every run at the reference's resolution, not the first only")
    parser.add_argument("--blender", default=shutil.which("blender"),
                        help="the blender program (default: blender on the path)")
    parser.add_argument("--no-cycles", action="store_true", help="do not render with Cycles")
    parser.add_argument("--cycles-spp", type=parse_list, default=[16, 64, 256, 1024],
                        help="Cycles samples per pixel (default 16,64,256,1024)")
    parser.add_argument("--cycles-seed", type=int, default=7,
                        help="Cycles seed (default 7; the reference used 0-3)")
    parser.add_argument("--no-cycles-startup", dest="cycles_startup", action="store_false",
                        help="do not measure Blender's fixed cost (a 1-spp render)")
    parser.add_argument("--suite", action="store_true",
                        help="every scene of SUITE at the defaults, each against its reference")
    parser.add_argument("--scaling", action="store_true",
                        help="cost against size: sphcover solve at --levels on 1 and 2 threads")
    parser.add_argument("--levels", type=parse_list, default=[2, 3, 4, 5],
                        help="max_level values of --scaling (default 2,3,4,5)")
    parser.add_argument("--solve-arg", action="append", dest="solve_args", default=[],
                        help="an extra argument of every --scaling solve (repeatable)")
    parser.add_argument("--keep", help="keep the images, reports and logs in this folder")
    parser.add_argument("--json", help="write all the numbers to this JSON file")
    args = parser.parse_args()

    site = os.path.join(args.build, "lib", f"python{sys.version_info.major}."
                        f"{sys.version_info.minor}", "site-packages")
    if os.path.isdir(site):
        sys.path.insert(0, site)
    args.sphcover = args.sphcover or os.path.join(args.build, "bin", "sphcover")
    if not os.path.isfile(args.sphcover):
        parser.error(f"{args.sphcover}: no such program (build the sphcover target)")
    if not os.path.isfile(args.scene):
        args.scene = os.path.join(DATA, "scenes", args.scene + ".scene")
    if not os.path.isfile(args.scene):
        parser.error(f"{args.scene}: no such scene")
    if args.reference is None and os.path.samefile(args.scene, CORNELL):
        args.reference = compare_sphcover.REFERENCE
    if args.reference == "none":
        args.reference = None
    if args.no_cycles:
        args.blender = None
    if args.runs is None:
        args.runs = [("defaults", [])]
        if os.path.samefile(args.scene, CORNELL):
            args.runs += [("max_level 3", ["--set", "max_level=3"]),
                          ("max_level 4", ["--set", "max_level=4"])]

    folder = args.keep or tempfile.mkdtemp(prefix="time_to_accuracy_")
    os.makedirs(folder, exist_ok=True)
    try:
        if args.suite:
            results = suite_mode(args, folder)
            for result in results:
                print(f"\n{result['name']}: {result['kind']}\n")
                print(accuracy_table(result))
            print("\nSummary\n")
            print(suite_table(results))
        elif args.scaling:
            results = scaling_mode(args, folder)
            print(scaling_table(results))
        else:
            results = accuracy_mode(args, folder)
            print(accuracy_table(results))
    except (RuntimeError, ValueError) as error:
        print(f"time_to_accuracy.py: {error}", file=sys.stderr)
        return 1
    finally:
        if not args.keep:
            shutil.rmtree(folder, ignore_errors=True)
    if args.json:
        with open(args.json, "w") as out:
            json.dump(results, out, indent=2, default=str)
    return 0


if __name__ == "__main__":
    sys.exit(main())
