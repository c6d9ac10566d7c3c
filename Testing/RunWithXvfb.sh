#!/bin/sh
# Runs one test on an X server of its own: a fresh Xvfb through xvfb-run, which picks a free
# display number (retrying the next one if another server takes it first) and a private
# authorization cookie, and kills the server when the test ends. CTest runs every test that
# opens an X display through this (label x11, Testing/CMakeLists.txt), so the tests share no
# display with each other, with another suite or with a desktop: nothing needs DISPLAY.
#
# -noreset is what makes it deterministic. Without it Xvfb resets whenever its last client
# disconnects, and pvbatch (vtkXOpenGLRenderWindow) opens the display, closes it and opens it
# again: when the second open falls in the reset, VTK prints "bad X server connection" and
# aborts (SIGABRT, CTest's "Subprocess aborted"). Measured: 1 pvbatch render in 12 aborted on a
# display of its own without -noreset, 0 in 12 with it.
#
# Xvfb's own messages go to a file that is printed when the test fails.
#
# usage: RunWithXvfb.sh COMMAND [ARG...]
log="$(mktemp -t sphcover-xvfb.XXXXXX)"
# Start the search for a free display at a number that depends on this process, so that tests
# started at the same moment rarely try the same number first.
first=$((100 + $$ % 800))
xvfb-run --auto-servernum --server-num="$first" --error-file="$log" \
  --server-args="-screen 0 1280x1024x24 -noreset" "$@"
status=$?
if [ "$status" -ne 0 ] && [ -s "$log" ]; then
  echo "RunWithXvfb.sh: exit status $status; the X server said:" >&2
  tail -n 20 "$log" >&2
fi
rm -f "$log"
exit "$status"
