"""pvbatch: the plug-in's OpenEXR writer and reader proxies (Documentation/Pipeline.md#rendering).
- "Save Data" on image data with a .exr name picks the OpenEXR Writer; every property's XML
  default equals the C++ constructor's value;
- the file it writes (a float Radiance, a double positive Depth as extra channel, written as
  OpenEXR's depth channel Z, a non-zero extent origin) opens through the reader factory as the
  OpenEXR Reader and gives back the extent, Radiance bit for bit and Depth rounded to float;
- a standard tool, exrheader (Debian package openexr), reads the file and lists the channels
  B, G, R, Z as 32-bit float and the data window of the extent (skipped with a message only
  if exrheader is not installed);
- a file that is not an EXR is refused by the reader factory (CanReadFile) and, opened with the
  reader proxy by name, gives an empty output without a crash."""
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy
from paraview import servermanager
from paraview.simple import (Calculator, CreateWriter, Delete, LoadPlugin, OpenDataFile, SaveData,
                             Wavelet)
from vtkmodules.util.numpy_support import vtk_to_numpy

plugin = sys.argv[1]
LoadPlugin(plugin, remote=False, ns=globals())
from sphericalcover import vtkOpenEXRReader, vtkOpenEXRWriter  # noqa: E402

failures = []
folder = tempfile.mkdtemp()

# An image with a non-zero extent origin: float Radiance, double Depth (positive: a negative
# depth means "nothing seen" and is written as +infinity, TestOpenEXRRoundTrip).
wavelet = Wavelet(WholeExtent=[-10, 10, -5, 7, 0, 0])
radiance = Calculator(Input=wavelet, ResultArrayName="Radiance", ResultArrayType="Float",
                      Function="RTData*iHat + coordsX*jHat + (coordsY/3)*kHat")
image = Calculator(Input=radiance, ResultArrayName="Depth", ResultArrayType="Double",
                   Function="abs(coordsX*coordsY)/7 + 0.1")
image.UpdatePipeline()

# The writer the factory picks for .exr, and its defaults against C++.
path = os.path.join(folder, "image.exr")
writer = CreateWriter(path, image)
if writer.GetXMLName() != "OpenEXRWriter":
    failures.append(f"Save Data picks {writer.GetXMLName()} for .exr, not OpenEXRWriter")
cxx = vtkOpenEXRWriter()
for name in ["PixelType", "Compression"]:
    default = writer.SMProxy.GetProperty(name).GetElement(0)
    if default != getattr(cxx, "Get" + name)():
        failures.append(f"writer {name}: XML default {default} != C++ {getattr(cxx, 'Get' + name)()}")
if writer.ColorArrayName != cxx.GetColorArrayName():
    failures.append(f"writer ColorArrayName: XML default {writer.ColorArrayName} != C++ "
                    f"{cxx.GetColorArrayName()}")
if len(writer.ChannelArrays) != cxx.GetNumberOfChannelArrays():
    failures.append(f"writer ChannelArrays: XML default {list(writer.ChannelArrays)} is not empty")
Delete(writer)
del writer

# Save Data, as the GUI does it.
SaveData(path, proxy=image, ChannelArrays=["Depth"])
if not os.path.isfile(path):
    failures.append("Save Data wrote no .exr file")
leftovers = [f for f in os.listdir(folder) if f != "image.exr"]
if leftovers:
    failures.append(f"temporary files left: {leftovers}")

# The reader factory opens it back.
reader = OpenDataFile(path)
if reader is None or reader.GetXMLName() != "OpenEXRReader":
    failures.append(f"{path} does not open with the OpenEXR Reader")
else:
    cxx_reader = vtkOpenEXRReader()
    default = reader.SMProxy.GetProperty("MaximumPixels").GetElement(0)
    if default != cxx_reader.GetMaximumPixels():
        failures.append(f"reader MaximumPixels: XML default {default} != C++ "
                        f"{cxx_reader.GetMaximumPixels()}")
    reader.UpdatePipeline()
    read = servermanager.Fetch(reader)
    original = servermanager.Fetch(image)
    if tuple(read.GetExtent()) != (-10, 10, -5, 7, 0, 0):
        failures.append(f"read extent {read.GetExtent()}")
    written_radiance = vtk_to_numpy(original.GetPointData().GetArray("Radiance"))
    read_radiance = read.GetPointData().GetArray("Radiance")
    if read_radiance is None or not numpy.array_equal(
            vtk_to_numpy(read_radiance).view(numpy.uint32), written_radiance.view(numpy.uint32)):
        failures.append("Radiance did not come back bit for bit")
    written_depth = vtk_to_numpy(original.GetPointData().GetArray("Depth")).astype(numpy.float32)
    read_depth = read.GetPointData().GetArray("Depth")
    if read_depth is None or not numpy.array_equal(vtk_to_numpy(read_depth), written_depth):
        failures.append("Depth did not come back as the double values rounded to float")

# A standard EXR tool reads the file.
exrheader = shutil.which("exrheader")
if exrheader is None:
    print("SKIPPED: the exrheader check (exrheader is not installed: Debian package openexr)")
else:
    header = subprocess.run([exrheader, path], capture_output=True, text=True)
    if header.returncode != 0:
        failures.append(f"exrheader failed: {header.stderr.strip()}")
    channels = re.findall(r"^\s+(\S+), 32-bit floating-point, sampling 1 1$", header.stdout,
                          re.MULTILINE)
    if channels != ["B", "G", "R", "Z"]:
        failures.append(f"exrheader lists the float channels {channels}, not B, G, R, Z")
    if "dataWindow (type box2i): (-10 -5) - (10 7)" not in header.stdout:
        failures.append("exrheader does not show the data window (-10 -5) - (10 7):\n"
                        + header.stdout)
    if "compression (type compression): zip" not in header.stdout:
        failures.append("exrheader does not show ZIP compression")

# Not an EXR: an empty output, no crash.
bad = os.path.join(folder, "text.exr")
with open(bad, "w") as out:
    out.write("not an image\n")
try:
    OpenDataFile(bad)
    failures.append("the reader factory accepts a text file named .exr")
except RuntimeError:
    pass  # CanReadFile refuses it: "No reader found"
bad_reader = globals()["OpenEXRReader"](FileName=bad)
bad_reader.UpdatePipeline()
if bad_reader.GetDataInformation().GetNumberOfPoints() != 0:
    failures.append("a text file with the .exr extension produced points")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
