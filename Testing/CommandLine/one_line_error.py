"""The project's rule for bad input, checked on a finished `sphcover` run: a non-zero exit (not
a signal), exactly one line on stderr holding every expected fragment (file, location,
problem), no message longer than 1000 characters, nothing on stdout."""


def check_one_line_error(name, run, fragments, failures):
    """Appends to `failures` what `run` (a subprocess.CompletedProcess with text output) breaks
    of the rule."""
    if run.returncode <= 0:
        failures.append(f"{name}: exit status {run.returncode} (expected a failure, not a signal)")
    lines = run.stderr.strip().splitlines()
    if len(lines) != 1:
        failures.append(f"{name}: {len(lines)} lines on stderr, expected one: {run.stderr!r}")
    message = run.stderr.strip()
    print(f"{name}: {message[:300]}")
    if len(message) > 1000:
        failures.append(f"{name}: a {len(message)}-character message (quoted excerpts are capped)")
    for fragment in fragments:
        if fragment not in message:
            failures.append(f"{name}: message lacks {fragment!r}")
    if run.stdout:
        failures.append(f"{name}: printed on stdout: {run.stdout!r}")
