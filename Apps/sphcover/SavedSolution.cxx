// SPDX-License-Identifier: BSD-3-Clause
#include "SavedSolution.h"

#include "Options.h"
#include "Pipeline.h"
#include "ProgressBar.h"

#include "vtkSphericalCoverArrayNames.h"

#include <vtkFieldData.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <filesystem>
#include <stdexcept>

namespace sphcover_cli
{
namespace
{
/// The one value of a data object's SceneFingerprint field array, or nullptr.
vtkStringArray* FingerprintOf(vtkDataObject* data)
{
  auto* fingerprint = vtkStringArray::SafeDownCast(
    data->GetFieldData()->GetAbstractArray(vtkSphericalCoverArrayNames::SceneFingerprint));
  return fingerprint && fingerprint->GetNumberOfValues() == 1 ? fingerprint : nullptr;
}
}

void SavedSolution::Read(const Options& options, ErrorCollector& errors)
{
  const std::string named =
    (this->Option.empty() ? std::string() : this->Option + " ") + "'" + options.SolutionFile + "'";
  if (!std::filesystem::is_regular_file(options.SolutionFile))
  {
    throw std::runtime_error(named + ": no such file");
  }
  this->Reader->SetFileName(options.SolutionFile.c_str());
  {
    ProgressBar bar(this->Reader, "read", options.Quiet);
    Run(this->Reader, errors);
    this->ReadSeconds = bar.Seconds();
  }
  auto* blocks = vtkMultiBlockDataSet::SafeDownCast(this->Reader->GetOutputDataObject(0));
  const bool two = blocks && blocks->GetNumberOfBlocks() == 2;
  this->Patches = two ? blocks->GetBlock(0) : nullptr;
  this->Illumination = two ? vtkPolyData::SafeDownCast(blocks->GetBlock(1)) : nullptr;
  if (!this->Patches || !this->Illumination)
  {
    throw std::runtime_error(named +
      ": not a solution of sphcover solve -o (two blocks, the patches and the illumination)");
  }
}

void SavedSolution::CheckFingerprint(const Options& options, vtkDataObject* scene) const
{
  vtkStringArray* stored = FingerprintOf(this->Illumination);
  if (!stored)
  {
    throw std::runtime_error("--solution '" + options.SolutionFile +
      "': has no scene fingerprint (not written by sphcover solve -o); solve the scene again");
  }
  vtkStringArray* own = FingerprintOf(scene);
  const std::string expected = own ? own->GetValue(0) : std::string();
  if (stored->GetValue(0) != expected)
  {
    throw std::runtime_error("--solution '" + options.SolutionFile +
      "': solved from another scene than '" + options.Scene +
      "' (or from an edited one: fingerprint " + stored->GetValue(0) + ", the scene's " + expected +
      "); solve the scene again");
  }
}
}
