// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPSphericalCoverFilter.h"

#include "vtkCoverDistribution.h"
#include "vtkHeldMessages.h"
#include "vtkNamedArrays.h"
#include "vtkSMPParallelFor.h"
#include "vtkScenePieces.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"
#include "vtkSphericalCoverSteps.h"
#include "vtkStageProgress.h"

#include "cover/SphericalCover.h"
#include "distributed/RowBlockBytes.h"
#include "distributed/RowShares.h"
#include "math/RankShare.h"

#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiProcessController.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <functional>
#include <string>
#include <vector>

namespace names = vtkSphericalCoverArrayNames;
using namespace vtkSphericalCoverSteps;

namespace
{
/// How many chunks of rows each rank builds (BuildRowChunks).
constexpr std::size_t RowChunksPerRank = 32;

/**
 * This rank's rows of the cover, under MPI, into `bytes` (PackRowBlock of its share) and their
 * count into `receivers`; progress from the cover's start to 0.9. The receivers are cut into
 * K x RowChunksPerRank consecutive chunks of about equal estimated cost
 * (RowShares::EstimateRowCosts) and rank r builds the rows of chunks r, r + K, ...
 * (share.MyItems) into one share: consecutive receivers lie on one surface and cost alike, so
 * dealing the chunks round the ranks evens out what the estimate misses, as the direct light's
 * interleaved nodes do. False, with a warning, when aborted; throws what BuildRowsOf throws.
 */
bool BuildRowChunks(vtkPSphericalCoverFilter* self,
  const CoverInput& prepared,
  const sphcover::RankShare& share,
  std::vector<char>& bytes,
  double& receivers)
{
  const std::size_t chunks = static_cast<std::size_t>(share.Ranks()) * RowChunksPerRank;
  const std::vector<std::size_t> bounds = sphcover::RowShares::PartitionRows(
    sphcover::RowShares::EstimateRowCosts(prepared.Patches, prepared.Options), chunks);
  const std::vector<std::size_t> mine =
    sphcover::RowShares::ReceiversOfRanges(bounds, share.MyItems(chunks));
  receivers = static_cast<double>(mine.size());
  vtkStageProgress progress(self, "Spherical Cover: cover", prepared.CoverStart, 0.9);
  bytes.clear();
  sphcover::SphericalCover rows;
  if (!sphcover::RowShares::BuildRowsOf(
        rows,
        prepared.Patches,
        prepared.Options,
        mine,
        vtkSMPParallelFor::Make(),
        [&progress](double fraction) { return progress(fraction); },
        prepared.Rays))
  {
    vtkWarningWithObjectMacro(self, "Spherical cover aborted.");
    return false;
  }
  const sphcover::CullingStatistics culling = rows.Culling();
  bytes = sphcover::PackRowBlock(std::move(rows).ExportArrays(), culling);
  return true;
}

/**
 * GatherRows off: this rank's rows, those of receivers r, r + K, ... (share.MyItems, the light
 * propagation's share), built into `rows` and kept; their count into `receivers`; progress from
 * the cover's start to 0.9. One by one round the ranks, every rank gets a K-th of every surface:
 * no estimate of the rows' costs is needed to even the work out. False, with a warning, when
 * aborted; throws what BuildRowsOf throws.
 */
bool BuildOwnRows(vtkPSphericalCoverFilter* self,
  const CoverInput& prepared,
  const sphcover::RankShare& share,
  sphcover::SphericalCover& rows,
  double& receivers)
{
  const std::vector<std::size_t> mine = share.MyItems(prepared.Patches.size());
  receivers = static_cast<double>(mine.size());
  vtkStageProgress progress(self, "Spherical Cover: cover", prepared.CoverStart, 0.9);
  if (!sphcover::RowShares::BuildRowsOf(
        rows,
        prepared.Patches,
        prepared.Options,
        mine,
        vtkSMPParallelFor::Make(),
        [&progress](double fraction) { return progress(fraction); },
        prepared.Rays))
  {
    vtkWarningWithObjectMacro(self, "Spherical cover aborted.");
    return false;
  }
  return true;
}

/**
 * The cover on the controller's K ranks (vtkCoverDistribution.h): every rank prepares the same
 * patches (rank 0's input broadcast when the other ranks hold empty pieces, as under pvbatch),
 * builds the rows of its range of receivers, balanced by Core's cost estimate, and the row
 * blocks are joined in receiver order: the serial cover bit for bit. The ranks that hold the
 * whole scene write the outputs (with CoverRankFigures); those that hold an empty piece keep
 * empty outputs (vtkScenePieces.h). Every rank agrees on success before each collective step,
 * so a failure anywhere is one error on every rank and no rank waits forever.
 */
int BuildDistributed(vtkPSphericalCoverFilter* self,
  vtkMultiProcessController* controller,
  vtkDataSet* input,
  vtkScenePieces::Role role,
  vtkInformationVector* outputVector,
  vtkPolyData* pointsOut,
  vtkTable* stripsOut)
{
  pointsOut->Initialize();
  stripsOut->Initialize();
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  const bool whole = role == vtkScenePieces::Role::WholeScene;
  const bool everyRankWhole = vtkCoverDistribution::Count(controller, whole) == ranks;
  std::string problem;
  if (role == vtkScenePieces::Role::PartialScene)
  {
    problem = "Cannot build a spherical cover of this input: " +
      vtkScenePieces::PartialSceneError(outputVector) + ".";
  }
  else if (rank == 0 && !whole)
  {
    problem = "Cannot build a spherical cover: rank 0 must hold the whole scene (piece 0).";
  }
  std::string agreed = vtkCoverDistribution::Agree(controller, problem);
  if (!agreed.empty())
  {
    vtkErrorWithObjectMacro(self, << agreed);
    return 0;
  }
  vtkSmartPointer<vtkDataSet> scene = input;
  if (!everyRankWhole)
  {
    scene = vtkSmartPointer<vtkDataSet>::Take(input->NewInstance());
    if (rank == 0)
    {
      scene->ShallowCopy(input);
    }
    vtkCoverDistribution::BroadcastFromFirst(controller, scene);
  }

  CoverInput prepared;
  sphcover::DirectIrradianceNodes direct;
  // GatherRows on: this rank's row blocks, as bytes to gather; off: its rows, kept.
  const bool keepRows = !self->GetGatherRows();
  std::vector<char> bytes;
  sphcover::SphericalCover ownRows;
  vtkCoverDistribution::RankFigures mine;
  const sphcover::RankShare share = vtkCoverDistribution::ShareOf(controller);
  // Each step's messages are held until the ranks agree on them (vtkHeldMessages); an exception
  // is the step's error.
  auto step = [self](const std::function<bool()>& body)
  {
    vtkHeldMessages held(self);
    bool done = false;
    try
    {
      done = body();
    }
    catch (const std::exception& e)
    {
      vtkErrorWithObjectMacro(self, << "Spherical cover failed: " << e.what());
    }
    return done ? std::string() : held.First("Spherical cover aborted.");
  };
  // Every rank prepares the same patches; the refinement's hemispheres, the rows and the direct
  // light's nodes are then shared among the ranks, each step collective, with an Agree after
  // it (the refinement and the direct light join inside too, RankShare.h).
  agreed = vtkCoverDistribution::Agree(
    controller, step([&] { return PrepareCover(self, scene, prepared); }));
  if (agreed.empty())
  {
    agreed = vtkCoverDistribution::Agree(
      controller, step([&] { return RefineCover(self, share, prepared); }));
  }
  if (agreed.empty())
  {
    problem = step(
      [&]
      {
        if (!MemoryFits(self, prepared.Patches, prepared.Options, prepared.Budget, prepared.Rays))
        {
          return false;
        }
        const auto start = std::chrono::steady_clock::now();
        if (keepRows ? !BuildOwnRows(self, prepared, share, ownRows, mine.Receivers)
                     : !BuildRowChunks(self, prepared, share, bytes, mine.Receivers))
        {
          return false;
        }
        mine.Seconds = SecondsSince(start);
        self->RecordStageSeconds(1, mine.Seconds);
        mine.Bytes = static_cast<double>(keepRows ? ownRows.MemoryBytes() : bytes.size());
        return true;
      });
    agreed = vtkCoverDistribution::Agree(controller, problem);
  }
  if (agreed.empty())
  {
    agreed = vtkCoverDistribution::Agree(
      controller, step([&] { return ComputeDirectIrradianceOf(self, share, prepared, direct); }));
  }
  prepared.Rays.reset();
  if (!agreed.empty())
  {
    vtkErrorWithObjectMacro(self, << agreed);
    return 0;
  }

  const std::vector<vtkCoverDistribution::RankFigures> figures =
    vtkCoverDistribution::GatherFigures(controller, mine);
  auto rankFigures = vtkNamedArrays::Double(names::CoverRankFigures, 3, ranks);
  for (vtkIdType r = 0; r < ranks; ++r)
  {
    const vtkCoverDistribution::RankFigures& f = figures[static_cast<size_t>(r)];
    const double tuple[3] = { f.Receivers, f.Seconds, f.Bytes };
    rankFigures->SetTuple(r, tuple);
  }
  if (keepRows)
  {
    // Every rank writes its share: every point, its own rows. The entries carry measures of
    // their own on every rank or on none, as the whole cover's (SphericalCover::BuildRowsOf).
    if (vtkCoverDistribution::Count(controller, ownRows.HasMeasures()) > 0)
    {
      sphcover::RowShares::KeepCellMeasures(ownRows);
    }
    // Of a share each rank knows its own rows' coverage only: each point's from its owner.
    PointCoverage coverage = CoverageOf(ownRows);
    coverage.Covered = sphcover::JoinOwnedItems(share, coverage.Covered);
    coverage.Visible = sphcover::JoinOwnedItems(share, coverage.Visible);
    WriteOutputs(self, scene, prepared, ownRows, coverage, direct, pointsOut, stripsOut);
    pointsOut->GetFieldData()->AddArray(rankFigures);
    vtkSphericalCoverArrays::MarkShare(pointsOut, rank, ranks);
    self->UpdateProgress(1.0);
    return 1;
  }
  // Every rank is ready: the row blocks move, to every rank that writes the cover.
  std::vector<std::vector<char>> received =
    vtkCoverDistribution::GatherBytes(controller, std::move(bytes), everyRankWhole);
  if (!whole)
  {
    return 1; // an empty piece (vtkScenePieces.h)
  }
  // Every rank's share of the rows (BuildRowChunks), joined.
  std::vector<sphcover::SphericalCover::Arrays> shares(received.size());
  sphcover::CullingStatistics culling;
  for (size_t r = 0; r < received.size(); ++r)
  {
    sphcover::CullingStatistics counts;
    problem = sphcover::UnpackRowBlock(received[r].data(), received[r].size(), shares[r], counts);
    if (!problem.empty())
    {
      vtkErrorWithObjectMacro(
        self, << "Spherical cover failed: the rows of rank " << r << ": " << problem);
      return 0;
    }
    received[r] = std::vector<char>();
    culling += counts;
  }
  sphcover::SphericalCover cover;
  problem = sphcover::RowShares::JoinRows(cover, std::move(shares), prepared.Options, culling);
  if (!problem.empty())
  {
    vtkErrorWithObjectMacro(self, << "Spherical cover failed: the gathered rows: " << problem);
    return 0;
  }
  WriteOutputs(self, scene, prepared, cover, CoverageOf(cover), direct, pointsOut, stripsOut);
  pointsOut->GetFieldData()->AddArray(rankFigures);
  self->UpdateProgress(1.0);
  return 1;
}
}

vtkStandardNewMacro(vtkPSphericalCoverFilter);

vtkPSphericalCoverFilter::vtkPSphericalCoverFilter()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPSphericalCoverFilter::~vtkPSphericalCoverFilter()
{
  this->SetController(nullptr);
}

vtkCxxSetObjectMacro(vtkPSphericalCoverFilter, Controller, vtkMultiProcessController);

int vtkPSphericalCoverFilter::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (!this->Controller || this->Controller->GetNumberOfProcesses() <= 1)
  {
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  return BuildDistributed(this,
    this->Controller,
    input,
    vtkScenePieces::Classify(outputVector, input),
    outputVector,
    vtkPolyData::GetData(outputVector, 0),
    vtkTable::GetData(outputVector, 1));
}

void vtkPSphericalCoverFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GatherRows: " << this->GatherRows << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
