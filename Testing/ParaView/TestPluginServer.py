"""The plug-in on a parallel pvserver with a client connected, as the ParaView GUI connects to
one (README.md, "Running on a cluster"): `mpiexec -n 2 pvserver` is started on a free port, a
pvpython client connects, loads the plug-in on the server and builds the Cornell box pipeline
(reader -> Interval Subdivision -> Spherical Cover -> Light Propagation) there. It checks that
- the light propagation ran on both server ranks together (the proxy's RankCount information,
  2), not on rank 0 alone;
- the illumination the client fetches from the server equals, value for value, the same
  pipeline run serially in the client (plain VTK, no server), and ParaView's data information
  counts its points.
Skipped (exit 77) where mpiexec is not installed.

usage: TestPluginServer.py PVSERVER PVPYTHON PLUGIN DATA          (the driver)
       pvpython TestPluginServer.py --client PORT PLUGIN DATA      (the client)"""
import os
import shutil
import signal
import socket
import subprocess
import sys
import time


def client(port, plugin, data):
    from paraview.simple import Connect, Disconnect, LoadPlugin, OpenDataFile, OutputPort
    from paraview import servermanager

    failures = []
    # The serial reference in this process first, with the plug-in's classes loaded locally.
    LoadPlugin(plugin, remote=False, ns=globals())
    # The pipeline the Python.* tests share, in Testing/Python.
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, os.path.join(here, os.pardir, "Python"))
    from coarse_cornell_pipeline import ErrorCollector, coarse_cornell_pipeline
    collector = ErrorCollector()
    # The serial filters: this process alone, whatever MPI this client was started with.
    _, _, cover, propagation = coarse_cornell_pipeline(data, collector)
    propagation.Update()
    failures += [f"serial reference: {message}" for message in collector.messages]
    reference = propagation.GetOutput().GetPointData().GetArray("Radiosity")
    scene_file = f"{data}/scenes/cornell_box.scene"

    Connect("localhost", port)
    LoadPlugin(plugin, remote=True, ns=globals())
    scene = OpenDataFile(scene_file)
    remote_subdivision = globals()["IntervalSubdivision"](Input=scene, MaxLevel=1)
    remote_cover = globals()["SphericalCover"](Input=OutputPort(remote_subdivision, 0),
                                               ThetaBins=8, PhiBins=32)
    remote = globals()["LightPropagation"](Input=OutputPort(remote_cover, 0))
    remote.UpdatePipeline()
    remote.UpdatePropertyInformation()
    ranks = remote.GetProperty("RankCount").GetData()
    if ranks != 2:
        failures.append(f"the propagation ran on {ranks} server rank(s), not on both")
    points = remote.GetDataInformation(0).GetNumberOfPoints()
    if points != reference.GetNumberOfTuples():
        failures.append(f"ParaView counts {points} illuminated points, serial "
                        f"{reference.GetNumberOfTuples()}")
    fetched = servermanager.Fetch(remote).GetPointData().GetArray("Radiosity")
    if fetched is None:
        failures.append("the fetched illumination lacks Radiosity")
    elif [fetched.GetValue(i) for i in range(fetched.GetNumberOfValues())] != \
            [reference.GetValue(i) for i in range(reference.GetNumberOfValues())]:
        failures.append("the server's Radiosity differs from the serial solution")
    Disconnect()
    for failure in failures:
        print("FAILED:", failure)
    if not failures:
        print("the server's solution is the serial one")
    return 1 if failures else 0


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def driver(pvserver, pvpython, plugin, data):
    mpiexec = shutil.which("mpiexec")
    if mpiexec is None:
        print("SKIPPED: mpiexec is not on the PATH (install mpi-default-bin to run the test)")
        return 77
    # Open MPI refuses to run as root (CI containers) unless told (RunParallelPvbatch.py).
    environment = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                       OMPI_MCA_rmaps_base_oversubscribe="1")
    port = free_port()
    server = subprocess.Popen([mpiexec, "-n", "2", pvserver, f"--server-port={port}"],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              env=environment, start_new_session=True)
    try:
        # The server says when it listens; give up after a minute.
        deadline = time.monotonic() + 60
        listening = False
        while not listening and time.monotonic() < deadline and server.poll() is None:
            line = server.stdout.readline()
            print("server:", line.rstrip())
            listening = "Accepting connection" in line
        if not listening:
            print("FAILED: pvserver did not start listening")
            return 1
        result = subprocess.run([pvpython, os.path.abspath(__file__), "--client", str(port),
                                 plugin, data], capture_output=True, text=True, timeout=600,
                                env=environment)
        print(result.stdout + result.stderr)
        output = result.stdout + result.stderr
        if result.returncode != 0 or "the server's solution is the serial one" not in output:
            print(f"FAILED: the client exited with {result.returncode}")
            return 1
        return 0
    finally:
        # The server exits when the client disconnects; stop it if it did not.
        try:
            server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(server.pid, signal.SIGTERM)
            server.wait()
        rest = server.stdout.read()
        if rest:
            print("server:", rest)


if __name__ == "__main__":
    if sys.argv[1] == "--client":
        sys.exit(client(int(sys.argv[2]), sys.argv[3], sys.argv[4]))
    sys.exit(driver(*sys.argv[1:5]))
