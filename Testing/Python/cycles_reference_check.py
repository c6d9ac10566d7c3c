"""The comparison shared by the Cycles reference tests: `sphcover render` of a scene at its own
settings, 256 x 256, 16 spp, against a committed Cycles EXR by the issue-16 metric of
Testing/Benchmarks/time_to_accuracy.py (the relative RMS of luminance block means on a 16 x 16
and a 64 x 64 grid) and the image's mean luminance. Exits the test with its verdict."""
import os
import subprocess
import sys
import tempfile


def check_against_cycles(scene, reference, block16, block64, mean_limit):
    """argv: sphcover, the Data folder, Testing/Benchmarks. Fails above the limits (fractions)."""
    sphcover, data, benchmarks = sys.argv[1:4]
    sys.path.insert(0, benchmarks)
    sys.path.insert(0, os.path.join(data, "reference"))
    import compare_sphcover  # noqa: E402
    import time_to_accuracy  # noqa: E402

    exr = os.path.join(tempfile.mkdtemp(), "image.exr")
    run = subprocess.run([sphcover, "render", os.path.join(data, "scenes", scene),
                          "-o", exr, "--size", "256x256", "--spp", "16", "--quiet"],
                         capture_output=True, text=True, timeout=1800)
    if run.returncode != 0:
        sys.exit(f"FAILED: render: {run.stderr.strip()}")
    image = compare_sphcover.read_exr(exr)
    expected = compare_sphcover.read_exr(os.path.join(data, "reference", reference))
    errors = time_to_accuracy.errors_against(image, expected)
    mean = time_to_accuracy.luminance(image).mean() / time_to_accuracy.luminance(expected).mean() - 1
    print(f"luminance block errors: 16 x 16 {100 * errors[16]:.2f} %, "
          f"64 x 64 {100 * errors[64]:.2f} %; mean luminance {100 * mean:+.2f} %")
    failures = []
    if errors[16] > block16 or errors[64] > block64:
        failures.append(f"block errors above {100 * block16:g} % / {100 * block64:g} %")
    if abs(mean) > mean_limit:
        failures.append(f"mean luminance off by more than {100 * mean_limit:g} %")
    for failure in failures:
        print("FAILED:", failure)
    sys.exit(1 if failures else 0)
