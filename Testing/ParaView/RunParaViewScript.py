"""Runs a Python script inside ParaView's own GUI client, `paraview --dr --script=SCRIPT --exit`
(--dr: without the user's settings, so no first-start dialog waits for a click), and passes or
fails by the result file the script writes: the client's exit status does not tell whether the
script failed. The script gets its arguments from the environment variable SPHCOVER_GUI_ARGS
(a JSON list) and writes RESULT_FILE: "PASSED" on its first line, or its failures.

usage: RunParaViewScript.py PARAVIEW SCRIPT RESULT_FILE [ARG...]"""
import json
import os
import subprocess
import sys

paraview, script, result, *arguments = sys.argv[1:]
os.makedirs(os.path.dirname(os.path.abspath(result)), exist_ok=True)
if os.path.exists(result):
    os.remove(result)
environment = dict(os.environ, SPHCOVER_GUI_ARGS=json.dumps([result, *arguments]))
try:
    run = subprocess.run([paraview, "--dr", f"--script={script}", "--exit"], env=environment,
                         capture_output=True, text=True, timeout=600)
except subprocess.TimeoutExpired:
    sys.exit("FAILED: paraview did not exit within 600 s (a dialog waiting?)")
if not os.path.isfile(result):
    print(run.stdout[-4000:], run.stderr[-4000:])
    sys.exit(f"FAILED: the script wrote no result (paraview exited with {run.returncode})")
with open(result) as stream:
    text = stream.read()
print(text)
sys.exit(0 if text.startswith("PASSED") else 1)
