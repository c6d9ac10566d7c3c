// SPDX-License-Identifier: BSD-3-Clause
// Every malformed input of Testing/Data/bad (listed with its expected message fragments in
// expected.json) makes the readers fail the request with exactly one error from the reader
// that names the file, the location and the problem, and leave the output empty: nothing
// partial, no crash. A missing file and an unset file name fail the same way.
#include "FailureExpectation.h"
#include "vtkBPTReader.h"
#include "vtkPatchSceneReader.h"

#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
/// Runs the reader on `file`; returns the number of failed checks.
int CheckFails(vtkPatchSceneReader* reader,
  const std::string& file,
  const std::vector<std::string>& fragments)
{
  reader->SetFileName(file.c_str());
  const int failed = FailureExpectation::Check(
    reader, fragments, std::string(reader->GetClassName()) + " on " + file);
  vtkUnstructuredGrid* output = reader->GetOutput();
  if (output->GetNumberOfCells() != 0 || output->GetNumberOfPoints() != 0)
  {
    std::cerr << "FAILED: " << reader->GetClassName() << " on " << file
              << ": the output is not empty\n";
    return failed + 1;
  }
  return failed;
}
}

int TestReaderBadInput(int, char*[])
{
  const std::string folder = SPHCOVER_TEST_DATA_DIR "/bad/";
  std::ifstream in(folder + "expected.json");
  const nlohmann::json expected = nlohmann::json::parse(in);
  int failures = 0;
  int cases = 0;
  for (auto it = expected.begin(); it != expected.end(); ++it)
  {
    const std::string name = it.key();
    const std::string ext = name.substr(name.find_last_of('.') + 1);
    const std::vector<std::string> fragments = it.value().get<std::vector<std::string>>();
    if (ext == "scene" || ext == "bpt")
    {
      vtkNew<vtkPatchSceneReader> sceneReader;
      failures += CheckFails(sceneReader, folder + name, fragments);
      ++cases;
    }
    if (ext == "bpt")
    {
      vtkNew<vtkBPTReader> bptReader;
      failures += CheckFails(bptReader, folder + name, fragments);
      ++cases;
    }
  }
  if (cases < 20)
  {
    std::cerr << "FAILED: only " << cases << " bad-input cases ran\n";
    ++failures;
  }

  // The corpus files are each one change away from these valid files: they must read.
  for (const char* valid : { "support/base.scene", "support/base.bpt" })
  {
    vtkNew<vtkPatchSceneReader> reader;
    reader->SetFileName((folder + valid).c_str());
    if (reader->GetExecutive()->Update() != 1 || reader->GetOutput()->GetNumberOfCells() == 0)
    {
      std::cerr << "FAILED: the valid base file " << valid << " does not read\n";
      ++failures;
    }
  }

  vtkNew<vtkPatchSceneReader> missing;
  failures += CheckFails(
    missing, folder + "no_such_file.scene", { "no_such_file.scene", "cannot open file" });
  vtkNew<vtkPatchSceneReader> unset;
  failures += CheckFails(unset, "", { "No FileName" });
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
