// SPDX-License-Identifier: BSD-3-Clause
#include "SavedSolution.h"

#include "Options.h"
#include "Pipeline.h"
#include "ProgressBar.h"

#include "ErrorCollector.h"
#include "vtkCoverDistribution.h"
#include "vtkSolutionPieces.h"
#include "vtkSphericalCoverArrayNames.h"

#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkMultiPieceDataSet.h>
#include <vtkMultiProcessController.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLGenericDataObjectReader.h>

#include <chrono>
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

/// The files of a solution's blocks as its .vtm names them (relative to its folder): the
/// patches, the illumination and, written in pieces, the shares in rank order.
struct SolutionFiles
{
  std::string Patches;
  std::string Illumination;
  std::vector<std::string> Shares;
};

SolutionFiles FilesOf(const std::string& file)
{
  SolutionFiles files;
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(file.c_str());
  vtkXMLDataElement* root = parser->Parse() ? parser->GetRootElement() : nullptr;
  vtkXMLDataElement* blocks =
    root ? root->FindNestedElementWithName("vtkMultiBlockDataSet") : nullptr;
  for (int k = 0; blocks && k < blocks->GetNumberOfNestedElements(); ++k)
  {
    vtkXMLDataElement* block = blocks->GetNestedElement(k);
    const char* index = block->GetAttribute("index");
    const char* name = block->GetAttribute("file");
    const char* label = block->GetAttribute("name");
    if (index && name && std::string(index) == "0")
    {
      files.Patches = name;
    }
    else if (index && name && std::string(index) == "1")
    {
      files.Illumination = name;
    }
    else if (label && std::string(label) == "CoverShares")
    {
      for (int s = 0; s < block->GetNumberOfNestedElements(); ++s)
      {
        const char* share = block->GetNestedElement(s)->GetAttribute("file");
        files.Shares.push_back(share ? share : "");
      }
    }
  }
  return files;
}

/// The dataset of one XML file (any VTK XML dataset type); throws the reader's first error.
vtkSmartPointer<vtkDataObject> ReadDataset(const std::filesystem::path& file)
{
  vtkNew<vtkXMLGenericDataObjectReader> reader;
  ErrorCollector errors;
  errors.Watch(reader);
  reader->SetFileName(file.string().c_str());
  reader->Update();
  vtkDataObject* output = reader->GetOutputDataObject(0);
  if (!output || reader->GetErrorCode() != 0)
  {
    throw std::runtime_error(file.string() + ": " + errors.First());
  }
  return output;
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

bool SavedSolution::ReadPiece(const Options& options,
  vtkMultiProcessController* controller,
  const std::string& problem)
{
  const SolutionFiles files = FilesOf(options.SolutionFile);
  const int ranks = controller->GetNumberOfProcesses();
  const int rank = controller->GetLocalProcessId();
  if (ranks < 2 || files.Shares.size() != static_cast<std::size_t>(ranks))
  {
    return false;
  }
  std::string found = problem;
  const auto start = std::chrono::steady_clock::now();
  if (found.empty())
  {
    try
    {
      const std::string missing = MissingPieceFile(options.SolutionFile);
      if (!missing.empty())
      {
        throw std::runtime_error("its piece '" + missing + "' is missing");
      }
      const std::filesystem::path folder =
        std::filesystem::path(options.SolutionFile).parent_path();
      this->PiecePatches = ReadDataset(folder / files.Patches);
      vtkSmartPointer<vtkDataObject> points = ReadDataset(folder / files.Illumination);
      vtkSmartPointer<vtkDataObject> share =
        ReadDataset(folder / files.Shares[static_cast<std::size_t>(rank)]);
      auto* pointsData = vtkPolyData::SafeDownCast(points);
      auto* shareData = vtkPolyData::SafeDownCast(share);
      vtkDataArray* marker = shareData
        ? shareData->GetFieldData()->GetArray(vtkSphericalCoverArrayNames::CoverRowShare)
        : nullptr;
      if (!vtkDataSet::SafeDownCast(this->PiecePatches) || !pointsData || !marker ||
        marker->GetNumberOfTuples() != 1 || marker->GetNumberOfComponents() != 2 ||
        marker->GetComponent(0, 0) != rank || marker->GetComponent(0, 1) != ranks)
      {
        throw std::runtime_error("share " + std::to_string(rank + 1) + " of " +
          std::to_string(ranks) + " is not rank " + std::to_string(rank) +
          "'s share of the cover (not a solution of sphcover solve -o)");
      }
      vtkSolutionPieces::Merge(pointsData, shareData, this->Joined);
      this->Patches = this->PiecePatches;
      this->Illumination = this->Joined;
      this->ReadSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    catch (const std::exception& e)
    {
      found = (this->Option.empty() ? std::string() : this->Option + " ") + "'" +
        options.SolutionFile + "': " + e.what();
    }
  }
  found = vtkCoverDistribution::Agree(controller, found);
  if (!found.empty())
  {
    throw std::runtime_error(found);
  }
  return true;
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
