// SPDX-License-Identifier: BSD-3-Clause
// Bad input for the OpenEXR reader and writer (Documentation/Pipeline.md#rendering, bad-input
// standard):
// - the reader on an empty file, a text file, truncated files (pixels, header), a corrupt
//   header, an unsupported version field, corrupt pixel data, a missing file, no file name and
//   a data window beyond MaximumPixels, a header attribute claiming more bytes than the file
//   holds or than its value has, and a 1 kB file whose data window (within MaximumPixels) needs
//   more memory than the process may have: one error naming the file and the problem, a failed
//   request and an empty output, also after the same reader had read a good file;
// - the writer with no input, no file name, a missing, wrong-sized or integer array, a 3-D
//   image, or an unwritable folder: one error, Write() returns 0, no file (and no temporary
//   file) is left; an aborted write leaves an existing file untouched.
#include "FailureExpectation.h"
#include "TestFailures.h"
#include "vtkOpenEXRReader.h"
#include "vtkOpenEXRWriter.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <sys/resource.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
using TestFailures::Check;

std::string ReadBytes(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteBytes(const fs::path& file, const std::string& bytes)
{
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// Files in `folder` whose name starts with `stem` (the target or a temporary next to it).
int FilesStartingWith(const fs::path& folder, const std::string& stem)
{
  int count = 0;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    count += entry.path().filename().string().rfind(stem, 0) == 0 ? 1 : 0;
  }
  return count;
}

/// A width x height image with a float Radiance (3) and a float Depth.
vtkSmartPointer<vtkImageData> MakeImage(int width, int height)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetExtent(0, width - 1, 0, height - 1, 0, 0);
  vtkNew<vtkFloatArray> radiance;
  radiance->SetName("Radiance");
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(image->GetNumberOfPoints());
  vtkNew<vtkFloatArray> depth;
  depth->SetName("Depth");
  depth->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType k = 0; k < image->GetNumberOfPoints(); ++k)
  {
    radiance->SetTuple3(k, 0.001 * k, std::sin(0.1 * k), 1.0 / (k + 1));
    depth->SetValue(k, static_cast<float>(k % 97));
  }
  image->GetPointData()->AddArray(radiance);
  image->GetPointData()->AddArray(depth);
  return image;
}

/// The reader fails on `file` with one error holding the fragments, and its output is empty.
void CheckReaderFails(vtkOpenEXRReader* reader,
  const std::string& file,
  std::vector<std::string> fragments,
  const std::string& what)
{
  reader->SetFileName(file.c_str());
  TestFailures::Add(FailureExpectation::Check(reader, fragments, what));
  vtkImageData* output = reader->GetOutput();
  Check(output->GetNumberOfPoints() == 0 && output->GetPointData()->GetNumberOfArrays() == 0,
    what + ": the output is not empty");
}

/// The fuzz artifact Testing/Data/bad/fuzz/`name` fails in a new reader with one error naming
/// the file and holding the fragments (CheckReaderFails).
void CheckFuzzArtifactFails(const std::string& name,
  std::vector<std::string> fragments,
  const std::string& what)
{
  const std::string file = std::string(SPHCOVER_TEST_DATA_DIR) + "/bad/fuzz/" + name;
  fragments.insert(fragments.begin(), { "Cannot read OpenEXR file", file });
  vtkNew<vtkOpenEXRReader> reader;
  CheckReaderFails(reader, file, fragments, what);
}

void RecordError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  static_cast<std::vector<std::string>*>(clientData)
    ->push_back(callData ? static_cast<const char*>(callData) : "");
}

/// Write() returns 0 with one error holding the fragments, and no file starts with `stem`.
void CheckWriterFails(vtkOpenEXRWriter* writer,
  const fs::path& folder,
  const std::string& stem,
  const std::vector<std::string>& fragments,
  const std::string& what)
{
  std::vector<std::string> errors;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(RecordError);
  onError->SetClientData(&errors);
  const unsigned long tag = writer->AddObserver(vtkCommand::ErrorEvent, onError);
  const int status = writer->Write();
  writer->RemoveObserver(tag);
  Check(status == 0, what + ": Write() did not return 0");
  if (errors.size() != 1)
  {
    Check(false, what + ": " + std::to_string(errors.size()) + " errors instead of one");
    return;
  }
  const std::string message = errors[0].substr(errors[0].find('\n') + 1);
  std::cout << what << ":\n  " << message << "\n";
  for (const std::string& fragment : fragments)
  {
    Check(
      message.find(fragment) != std::string::npos, what + ": the message lacks '" + fragment + "'");
  }
  Check(FilesStartingWith(folder, stem) == 0, what + ": a file was left behind");
}
}

int TestOpenEXRBadInput(int, char*[])
{
  const fs::path folder = fs::path(SPHCOVER_BINARY_DIR) / "Testing" / "Temporary" / "OpenEXRBad";
  fs::remove_all(folder);
  fs::create_directories(folder);

  // A valid file, from which the broken ones are made.
  const fs::path good = folder / "good.exr";
  {
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetInputData(MakeImage(64, 200));
    writer->SetFileName(good.string().c_str());
    writer->AddChannelArray("Depth");
    Check(writer->Write() == 1, "the valid file was not written");
  }
  const std::string bytes = ReadBytes(good);
  // The header ends with a null byte after the last attribute, followed by the offset table;
  // OpenEXR's header of this file is a few hundred bytes.
  Check(bytes.size() > 2000, "the valid file is implausibly small");

  struct Case
  {
    std::string Name;
    std::string Bytes;
    std::vector<std::string> Fragments;
  };
  std::string badVersion = bytes;
  badVersion[4] = 99; // version 99
  std::string corruptHeader = bytes;
  for (std::size_t k = 10; k < 120; ++k)
  {
    corruptHeader[k] = static_cast<char>(0xA5);
  }
  std::string corruptPixels = bytes;
  for (std::size_t k = bytes.size() / 2; k < bytes.size(); ++k)
  {
    corruptPixels[k] = static_cast<char>((k * 131) & 0xFF);
  }
  const std::vector<Case> cases = {
    { "empty.exr", "", { "the file is empty" } },
    { "text.exr", "This is not an image, only text.\n", { "not an OpenEXR file" } },
    { "short.exr", bytes.substr(0, 3), { "not an OpenEXR file" } },
    { "truncated_header.exr", bytes.substr(0, 60), {} },
    { "truncated.exr", bytes.substr(0, bytes.size() / 2), {} },
    { "bad_version.exr", badVersion, { "version" } },
    { "corrupt_header.exr", corruptHeader, {} },
    { "corrupt_pixels.exr", corruptPixels, {} },
  };
  for (const Case& bad : cases)
  {
    const fs::path file = folder / bad.Name;
    WriteBytes(file, bad.Bytes);
    std::vector<std::string> fragments = bad.Fragments;
    fragments.push_back("Cannot read OpenEXR file");
    fragments.push_back(file.string());
    vtkNew<vtkOpenEXRReader> fresh;
    Check(bad.Name == "truncated.exr" || bad.Name == "corrupt_pixels.exr" ||
        fresh->CanReadFile(file.string().c_str()) == 0,
      bad.Name + ": CanReadFile accepts it");
    CheckReaderFails(fresh, file.string(), fragments, "new reader on " + bad.Name);
    // The same reader after a good read: the failure leaves no stale image.
    vtkNew<vtkOpenEXRReader> used;
    used->SetFileName(good.string().c_str());
    used->Update();
    Check(used->GetOutput()->GetNumberOfPoints() == 64 * 200, "the valid file does not read");
    CheckReaderFails(used, file.string(), fragments, "used reader on " + bad.Name);
  }
  {
    vtkNew<vtkOpenEXRReader> reader;
    CheckReaderFails(reader,
      (folder / "no_such_file.exr").string(),
      { "no_such_file.exr", "cannot open the file" },
      "missing file");
    CheckReaderFails(reader, "", { "No FileName" }, "no file name");
    reader->SetMaximumPixels(1000);
    CheckReaderFails(reader,
      good.string(),
      { "good.exr", "64 x 200", "MaximumPixels" },
      "data window beyond MaximumPixels");
  }

  // Testing/Data/bad/fuzz/exr_attribute_size_beyond_file.exr (FuzzOpenEXRReader): 918 bytes
  // whose `type` attribute claims 1.7 GB; OpenEXR allocates and fills what a string attribute
  // claims before reading it (1.7 GB and seconds per open). Refused before OpenEXR sees it.
  {
    const std::string file =
      std::string(SPHCOVER_TEST_DATA_DIR) + "/bad/fuzz/exr_attribute_size_beyond_file.exr";
    vtkNew<vtkOpenEXRReader> reader;
    Check(
      reader->CanReadFile(file.c_str()) == 0, "CanReadFile accepts an attribute beyond the file");
    CheckFuzzArtifactFails("exr_attribute_size_beyond_file.exr",
      { "corrupt header", "'type' (string)", "1702390128 bytes" },
      "attribute size beyond the file");
  }
  // Testing/Data/bad/fuzz/exr_channel_list_shorter_than_declared.exr (FuzzOpenEXRReader): the
  // channel list declares 77 bytes but ends after 19; OpenEXR reads it by its content and the
  // next attribute from the wrong place, where `type` then claims 1.7 GB.
  CheckFuzzArtifactFails("exr_channel_list_shorter_than_declared.exr",
    { "corrupt header", "'channels' (chlist)", "declares 77 bytes but its value holds 19" },
    "channel list shorter than declared");

  // Testing/Data/bad/fuzz/exr_window_product_overflow.exr (FuzzOpenEXRReader, UBSan): a data
  // window of about 2.8e9 x 4.1e9 pixels, whose pixel count overflows a 64-bit product; refused
  // by the pixel limit without forming it.
  CheckFuzzArtifactFails("exr_window_product_overflow.exr",
    { "exceeds the limit", "MaximumPixels" },
    "data window whose pixel count overflows");

  // Testing/Data/bad/fuzz/exr_tile_larger_than_memory.exr (FuzzOpenEXRReader, OOM): a tiled
  // file whose tile description makes OpenEXR's setFrameBuffer allocate 4 GiB of tile buffer.
  CheckFuzzArtifactFails("exr_tile_larger_than_memory.exr",
    { "tiles of", "larger than the image" },
    "tiles far larger than the image");

  // Testing/Data/bad/fuzz/exr_window_exceeds_memory.exr: the writer's 8 x 6 file with its data
  // window changed to 2^22 x 32 pixels (within MaximumPixels; 1.5 GiB for Radiance alone),
  // read under an address-space limit 768 MiB above the current size. The failed allocation
  // is one error (once vtkFloatArray's own failure left no buffer for OpenEXR to write
  // into: a crash of the process).
  {
    const std::string file =
      std::string(SPHCOVER_TEST_DATA_DIR) + "/bad/fuzz/exr_window_exceeds_memory.exr";
    unsigned long long pages = 0;
    std::ifstream("/proc/self/statm") >> pages;
    rlimit saved{};
    getrlimit(RLIMIT_AS, &saved);
    rlimit limited = saved;
    const unsigned long long wanted = pages * 4096ull + (768ull << 20);
    if (saved.rlim_cur == RLIM_INFINITY || saved.rlim_cur > wanted)
    {
      limited.rlim_cur = wanted;
    }
    Check(pages > 0 && setrlimit(RLIMIT_AS, &limited) == 0, "cannot limit the address space");
    vtkNew<vtkOpenEXRReader> reader;
    CheckReaderFails(reader,
      file,
      { "Cannot read OpenEXR file", file, "not enough memory", "'Radiance'", "1536 MiB" },
      "data window beyond the memory available");
    setrlimit(RLIMIT_AS, &saved);
  }

  // The writer.
  vtkSmartPointer<vtkImageData> image = MakeImage(16, 8);
  const std::string out = (folder / "out.exr").string();
  {
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetFileName(out.c_str());
    CheckWriterFails(writer, folder, "out.exr", { "No input" }, "writer without input");
  }
  {
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetInputData(image);
    CheckWriterFails(writer, folder, "out.exr", { "No FileName" }, "writer without file name");
  }
  {
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(out.c_str());
    writer->SetColorArrayName("Missing");
    CheckWriterFails(
      writer, folder, "out.exr", { out, "no point array 'Missing'" }, "missing colour array");
    writer->SetColorArrayName("Depth");
    CheckWriterFails(
      writer, folder, "out.exr", { out, "'Depth'", "1 components, not 3" }, "1-component colour");
    writer->SetColorArrayName("Radiance");
    writer->AddChannelArray("Radiance");
    CheckWriterFails(writer,
      folder,
      "out.exr",
      { out, "'Radiance'", "3 components, not 1" },
      "3-component extra channel");
    writer->RemoveAllChannelArrays();
    writer->AddChannelArray("Nothing");
    CheckWriterFails(
      writer, folder, "out.exr", { out, "no point array 'Nothing'" }, "missing extra channel");
    writer->RemoveAllChannelArrays();
    writer->AddChannelArray("Depth");
    writer->AddChannelArray("Depth");
    // Depth is written as OpenEXR's channel Z (vtkOpenEXRWriter.h).
    CheckWriterFails(
      writer, folder, "out.exr", { out, "'Z' is written twice" }, "the same extra channel twice");
    writer->RemoveAllChannelArrays();
    writer->AddChannelArray("Depth");
    writer->AddChannelArray("Z");
    vtkNew<vtkFloatArray> z;
    z->SetName("Z");
    z->SetNumberOfTuples(image->GetNumberOfPoints());
    z->Fill(1.0);
    image->GetPointData()->AddArray(z);
    CheckWriterFails(writer,
      folder,
      "out.exr",
      { out, "'Z' is written twice" },
      "an array Z next to Depth, which is written as the channel Z");
    image->GetPointData()->RemoveArray("Z");
  }
  {
    vtkNew<vtkImageData> bytesImage;
    bytesImage->SetExtent(0, 3, 0, 3, 0, 0);
    vtkNew<vtkUnsignedCharArray> rgb;
    rgb->SetName("RGB");
    rgb->SetNumberOfComponents(3);
    rgb->SetNumberOfTuples(16);
    rgb->FillValue(7);
    bytesImage->GetPointData()->AddArray(rgb);
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetInputData(bytesImage);
    writer->SetFileName(out.c_str());
    writer->SetColorArrayName("RGB");
    CheckWriterFails(writer,
      folder,
      "out.exr",
      { out, "unsigned char", "not float or double" },
      "unsigned char colour");
  }
  {
    vtkNew<vtkImageData> volume;
    volume->SetExtent(0, 3, 0, 3, 0, 2);
    vtkNew<vtkFloatArray> radiance;
    radiance->SetName("Radiance");
    radiance->SetNumberOfComponents(3);
    radiance->SetNumberOfTuples(volume->GetNumberOfPoints());
    radiance->Fill(1.0);
    volume->GetPointData()->AddArray(radiance);
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetInputData(volume);
    writer->SetFileName(out.c_str());
    CheckWriterFails(writer, folder, "out.exr", { out, "3-D" }, "3-D image");
  }
  {
    const std::string unwritable = (folder / "no_such_folder" / "out.exr").string();
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(unwritable.c_str());
    CheckWriterFails(writer, folder, "no_such_folder", { unwritable }, "unwritable folder");
  }

  // An aborted write leaves the existing file as it was and no temporary file.
  {
    const fs::path kept = folder / "kept.exr";
    WriteBytes(kept, "the previous content");
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetInputData(MakeImage(64, 200));
    writer->SetFileName(kept.string().c_str());
    vtkNew<vtkCallbackCommand> abortOnProgress;
    abortOnProgress->SetCallback([](vtkObject* caller, unsigned long, void*, void*)
      { static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1); });
    writer->AddObserver(vtkCommand::ProgressEvent, abortOnProgress);
    Check(writer->Write() == 0, "an aborted write returned success");
    Check(ReadBytes(kept) == "the previous content", "an aborted write changed the file");
    Check(FilesStartingWith(folder, "kept.exr") == 1, "an aborted write left a temporary file");
    // Without the abort the write replaces the file.
    writer->RemoveAllObservers();
    writer->SetAbortExecute(0);
    Check(writer->Write() == 1, "the write after the abort failed");
    vtkNew<vtkOpenEXRReader> reader;
    Check(reader->CanReadFile(kept.string().c_str()) == 3, "the file was not replaced");
    Check(FilesStartingWith(folder, "kept.exr") == 1, "a temporary file was left");
  }
  return TestFailures::ExitCode();
}
