// SPDX-License-Identifier: BSD-3-Clause
#include "SavedSolution.h"

#include "Options.h"
#include "Pipeline.h"
#include "ProgressBar.h"

#include "vtkSolutionPieces.h"
#include "vtkSphericalCoverArrayNames.h"

#include <vtkCompositeDataSet.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkMultiPieceDataSet.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace sphcover_cli
{
namespace
{
/// The first file a multiblock file refers to that is not there (its path as written in the
/// file, relative to the file's folder), or "" when all are. The XML reader would read a
/// missing piece as empty (or as the piece read before it) with no error.
std::string MissingPieceFile(const std::string& file)
{
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(file.c_str());
  if (!parser->Parse() || !parser->GetRootElement())
  {
    return std::string(); // the reader says what is wrong with it
  }
  const std::filesystem::path folder = std::filesystem::path(file).parent_path();
  std::vector<vtkXMLDataElement*> elements{ parser->GetRootElement() };
  while (!elements.empty())
  {
    vtkXMLDataElement* element = elements.back();
    elements.pop_back();
    const char* piece = element->GetAttribute("file");
    std::error_code error;
    if (piece && !std::filesystem::is_regular_file(folder / piece, error))
    {
      return piece;
    }
    for (int k = 0; k < element->GetNumberOfNestedElements(); ++k)
    {
      elements.push_back(element->GetNestedElement(k));
    }
  }
  return std::string();
}

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
  const std::string missing = MissingPieceFile(options.SolutionFile);
  if (!missing.empty())
  {
    throw std::runtime_error(named + ": its piece '" + missing + "' is missing");
  }
  this->Reader->SetFileName(options.SolutionFile.c_str());
  {
    ProgressBar bar(this->Reader, "read", options.Quiet);
    Run(this->Reader, errors);
    this->ReadSeconds = bar.Seconds();
  }
  auto* blocks = vtkMultiBlockDataSet::SafeDownCast(this->Reader->GetOutputDataObject(0));
  const unsigned count = blocks ? blocks->GetNumberOfBlocks() : 0;
  this->Patches = count == 2 || count == 3 ? blocks->GetBlock(0) : nullptr;
  this->Illumination =
    count == 2 || count == 3 ? vtkPolyData::SafeDownCast(blocks->GetBlock(1)) : nullptr;
  auto* pieces = count == 3 ? vtkMultiPieceDataSet::SafeDownCast(blocks->GetBlock(2)) : nullptr;
  if (!this->Patches || !this->Illumination || (count == 3 && !pieces))
  {
    throw std::runtime_error(named +
      ": not a solution of sphcover solve -o (two blocks, the patches and the illumination, "
      "and, written in pieces, the cover's shares)");
  }
  if (pieces)
  {
    // Written in pieces (solve -o under mpiexec): the ranks' shares of the cover and its
    // regions' radiance join into the whole solution.
    std::vector<vtkPolyData*> shares;
    for (unsigned k = 0; k < pieces->GetNumberOfPieces(); ++k)
    {
      auto* share = vtkPolyData::SafeDownCast(pieces->GetPiece(k));
      if (!share)
      {
        throw std::runtime_error(named + ": share " + std::to_string(k + 1) + " of " +
          std::to_string(pieces->GetNumberOfPieces()) + " of the cover is missing");
      }
      shares.push_back(share);
    }
    const std::string problem = vtkSolutionPieces::Join(this->Illumination, shares, this->Joined);
    if (!problem.empty())
    {
      throw std::runtime_error(named + ": " + problem);
    }
    this->Illumination = this->Joined;
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
