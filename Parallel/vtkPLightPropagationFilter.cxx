// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPLightPropagationFilter.h"

#include "vtkCoverDistribution.h"
#include "vtkHeldMessages.h"
#include "vtkLightPropagationSteps.h"
#include "vtkScenePieces.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"

#include "cover/SphericalCover.h"
#include "distributed/RowBlockBytes.h"
#include "distributed/RowShares.h"
#include "distributed/SharedPropagation.h"
#include "math/ByteBuffer.h"
#include "math/RankShare.h"
#include "propagation/LightPropagation.h"
#include "propagation/SolutionFigures.h"
#include "scene/Material.h"

#include <vtkAbstractArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkTable.h>

#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace names = vtkSphericalCoverArrayNames;
using namespace vtkLightPropagationSteps;

namespace
{
/// Under MPI: the ranks that propagate together, this rank's receivers, and whether every rank
/// writes the solution (else rank 0 alone, and the results are gathered there).
struct PropagationRanks
{
  vtkMultiProcessController* Controller = nullptr;
  bool EveryRankWrites = true;
  /// The solution kept in pieces (GatherSolution off): each rank keeps its own rows' regions.
  bool KeepsOwnRegions = false;
  sphcover::RankShare Share;
};

/**
 * The whole cover into `whole` on rank 0, joined from the ranks' shares (CoverHeld::Shares:
 * each rank's `rows`, let go as they are sent); nothing on the other ranks. Collective; what
 * rank 0 finds wrong in the shares ("" when nothing), for the ranks to agree on.
 */
std::string GatherShares(vtkMultiProcessController* controller,
  sphcover::SphericalCover rows,
  sphcover::SphericalCover& whole)
{
  const sphcover::SphericalCoverOptions options = rows.Options();
  std::vector<std::vector<char>> all = vtkCoverDistribution::GatherBytes(
    controller, sphcover::PackRowBlock(std::move(rows).ExportArrays(), {}), false);
  std::string problem;
  if (all.empty())
  {
    return problem; // rank 0 joins
  }
  std::vector<sphcover::SphericalCover::Arrays> shares(all.size());
  for (std::size_t r = 0; r < all.size() && problem.empty(); ++r)
  {
    sphcover::CullingStatistics culling;
    problem = sphcover::UnpackRowBlock(all[r].data(), all[r].size(), shares[r], culling);
    if (!problem.empty())
    {
      problem = "rank " + std::to_string(r) + "'s share of the cover: " + problem;
    }
    all[r] = std::vector<char>();
  }
  if (problem.empty())
  {
    problem = sphcover::RowShares::JoinRows(whole, std::move(shares), options, {});
    if (!problem.empty())
    {
      problem = "the ranks' shares of the cover: " + problem;
    }
  }
  return problem;
}

/**
 * The cover's part of the figures on rank 0 when no rank holds the whole cover (a solution
 * kept in pieces of shares): each rank's rows' form-factor sums (SphericalCover::
 * FormFactorSums) and strip counts, joined in receiver order, give the whole cover's figures
 * bit for bit. Collective; "" or the problem, on the rank that meets it.
 */
std::string JoinCoverFigures(const sphcover::RankShare& share,
  const sphcover::SphericalCover& rows,
  const sphcover::PointIllumination& surfaces,
  sphcover::CoverFigures& figures)
{
  using GroupSum = sphcover::SphericalCover::GroupSum;
  std::vector<uint64_t> counts;
  std::vector<GroupSum> sums;
  std::string problem;
  try
  {
    std::vector<std::vector<GroupSum>> rowSums =
      rows.FormFactorSums(surfaces.SurfaceOfPoint, surfaces.SurfaceCount);
    for (const std::size_t i : share.MyItems(rows.PatchCount()))
    {
      counts.push_back(rowSums[i].size());
      sums.insert(sums.end(), rowSums[i].begin(), rowSums[i].end());
    }
  }
  catch (const std::exception& e)
  {
    problem = e.what();
  }
  const uint64_t strips = rows.StripCount();
  std::vector<char> bytes;
  sphcover::ByteWriter writer(bytes);
  writer.Value(strips);
  writer.Array(counts);
  writer.Array(sums);
  std::vector<std::vector<char>> all;
  if (!share.Join(bytes, problem.empty(), all))
  {
    return problem.empty() ? "another rank could not sum up its rows' form factors" : problem;
  }
  if (share.Rank() != 0)
  {
    return problem;
  }
  // Every receiver's sums from its rank, in receiver order.
  const std::size_t count = rows.PatchCount();
  std::vector<std::vector<GroupSum>> rowSums(count);
  figures.Strips = 0;
  for (std::size_t r = 0; r < all.size(); ++r)
  {
    sphcover::ByteReader reader(all[r]);
    uint64_t rankStrips = 0;
    const std::size_t items = r < count ? (count - r + all.size() - 1) / all.size() : 0;
    if (!reader.Value(rankStrips) || !reader.Array(counts) || !reader.Array(sums) ||
      counts.size() != items)
    {
      return "rank " + std::to_string(r) + "'s form-factor sums are malformed";
    }
    figures.Strips += static_cast<std::size_t>(rankStrips);
    std::size_t next = 0;
    std::size_t k = 0;
    for (std::size_t i = r; i < count; i += all.size(), ++k)
    {
      if (counts[k] > sums.size() - next)
      {
        return "rank " + std::to_string(r) + "'s form-factor sums are malformed";
      }
      rowSums[i].assign(sums.begin() + static_cast<std::ptrdiff_t>(next),
        sums.begin() + static_cast<std::ptrdiff_t>(next + counts[k]));
      next += counts[k];
    }
  }
  std::vector<double> areas(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    areas[i] = rows.PatchArea(i);
  }
  try
  {
    figures.FormFactors = sphcover::SumSurfaceFormFactors(
      rowSums, surfaces.SurfaceOfPoint, surfaces.SurfaceCount, areas);
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  figures.CharacteristicPoints = count;
  return std::string();
}

/// Rank `rank`'s (of `ranks`) rows of `cover`: those of its receivers rank, rank + K, ...
/// (RankShare::MyItems, as LightPropagation::SetRankShare takes them).
sphcover::SphericalCover RowsOfRank(const sphcover::SphericalCover& cover, int rank, int ranks)
{
  return sphcover::RowShares::RowsOf(
    cover, sphcover::RankShare::ItemsOf(rank, ranks, cover.PatchCount()));
}

/**
 * Rank 0 holds the whole `cover`, keeps its own rows and deals every other rank its rows
 * (vtkCoverDistribution::DealFromFirst), one rank at a time; the other ranks hold none and
 * receive theirs. Collective; throws what the bytes' reading finds wrong.
 */
sphcover::SphericalCover DealRows(vtkMultiProcessController* controller,
  const sphcover::SphericalCover& cover)
{
  const bool dealer = controller->GetLocalProcessId() == 0;
  const int ranks = controller->GetNumberOfProcesses();
  const std::vector<char> bytes = vtkCoverDistribution::DealFromFirst(controller,
    [&](int rank)
    {
      // One copy of the rank's rows at a time beside the cover (they are a K-th of it).
      sphcover::SphericalCover::Arrays arrays = RowsOfRank(cover, rank, ranks).ExportArrays();
      return sphcover::PackRowBlock(arrays, {});
    });
  if (dealer)
  {
    return RowsOfRank(cover, 0, ranks);
  }
  sphcover::SphericalCover mine;
  sphcover::SphericalCover::Arrays arrays;
  sphcover::CullingStatistics culling;
  std::string problem = sphcover::UnpackRowBlock(bytes.data(), bytes.size(), arrays, culling);
  if (problem.empty())
  {
    problem = mine.ImportArrays(std::move(arrays));
  }
  if (!problem.empty())
  {
    throw std::runtime_error("the rows dealt to this rank are damaged: " + problem);
  }
  return mine;
}

/// The results of every patch and region: this rank's own alone, or under MPI (collective)
/// each rank's patches and rows put back in patch order (the ranks' own patches are dealt
/// round them: RankShare::MyItems), on every rank or on rank 0 alone.
PropagationResults JoinResults(const PropagationRanks& ranks, OwnResults own)
{
  const bool everyRank = ranks.EveryRankWrites || !ranks.Controller;
  const bool writer = everyRank || ranks.Controller->GetLocalProcessId() == 0;
  // Every rank's values of its own patches, item k's lengths[k] of them, in patch order on the
  // ranks that write (empty on the others).
  const auto join = [&ranks, everyRank, writer](
                      const auto& values, const std::vector<std::size_t>& lengths)
  {
    using Value = typename std::decay_t<decltype(values)>::value_type;
    std::vector<char> bytes;
    sphcover::ByteWriter(bytes).Values(values.data(), values.size());
    std::vector<std::vector<char>> all;
    if (everyRank)
    {
      if (!ranks.Share.Join(bytes, true, all))
      {
        throw sphcover::RankShare::PeerFailure();
      }
    }
    else
    {
      all = vtkCoverDistribution::GatherBytes(ranks.Controller, std::move(bytes), false);
    }
    return writer ? sphcover::ItemsFromRanks<Value>(all, lengths) : std::vector<Value>();
  };
  PropagationResults results;
  results.Energy = own.Energy;
  const std::vector<uint64_t> rowLengths =
    join(own.RowLengths, std::vector<std::size_t>(own.Count, 1));
  const std::vector<glm::dvec3> perPatch =
    join(own.PerPatch, std::vector<std::size_t>(own.Count, 4));
  own.PerPatch = std::vector<glm::dvec3>();
  if (ranks.KeepsOwnRegions)
  {
    results.Incident = std::move(own.Incident);
  }
  else
  {
    results.Incident =
      join(own.Incident, std::vector<std::size_t>(rowLengths.begin(), rowLengths.end()));
    own.Incident = std::vector<glm::dvec3>();
  }
  if (!writer)
  {
    return results; // rank 0 writes the solution
  }
  SplitPerPatch(perPatch, own.Count, own.Lamps, results);
  return results;
}
}

vtkStandardNewMacro(vtkPLightPropagationFilter);

vtkPLightPropagationFilter::vtkPLightPropagationFilter()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPLightPropagationFilter::~vtkPLightPropagationFilter()
{
  this->SetController(nullptr);
}

vtkCxxSetObjectMacro(vtkPLightPropagationFilter, Controller, vtkMultiProcessController);

int vtkPLightPropagationFilter::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  this->RankFigures.clear();
  this->RankCount = 1;
  vtkMultiProcessController* controller = this->Controller;
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  // FixedOrder runs on each process alone (see the header).
  if (ranks <= 1 || this->ShootingOrder != BRIGHTEST_FIRST)
  {
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }
  vtkDataSet* inputData = vtkDataSet::GetData(inputVector[0], 0);
  vtkPolyData* input = vtkPolyData::SafeDownCast(inputData);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkTable* history = vtkTable::GetData(outputVector, 1);
  this->Shots = 0;
  // The counts are collective, so they come before any rank returns.
  const vtkScenePieces::Role role = vtkScenePieces::Classify(outputVector, inputData);
  const std::pair<int, int> rowShare = RowShareOf(inputData);
  const int rank = controller->GetLocalProcessId();
  if (vtkCoverDistribution::Count(controller, rowShare.first != -1) > 0)
  {
    // The cover kept on the ranks (vtkSphericalCoverFilter's GatherRows off): each must hold
    // its own share.
    std::string problem;
    if (rowShare.first != rank || rowShare.second != ranks)
    {
      problem = "this rank's input holds " + ShareName(rowShare) + " of the cover's rows, not " +
        ShareName({ rank, ranks }) + ": build the cover on these ranks, or gather its rows " +
        "(vtkSphericalCoverFilter's GatherRows)";
    }
    problem = vtkCoverDistribution::Agree(controller, problem);
    if (!problem.empty())
    {
      output->Initialize();
      history->Initialize();
      vtkErrorMacro(<< "Cannot propagate light: " << problem << ".");
      return 0;
    }
    return this->PropagateOnRanks(controller, input, output, history, CoverHeld::Shares);
  }
  const bool whole = role == vtkScenePieces::Role::WholeScene;
  if (vtkCoverDistribution::Count(controller, whole) == ranks)
  {
    return this->PropagateOnRanks(controller, input, output, history);
  }
  return this->PropagateFromFirst(
    controller, static_cast<int>(role), outputVector, input, output, history);
}

int vtkPLightPropagationFilter::PropagateFromFirst(vtkMultiProcessController* controller,
  int role,
  vtkInformationVector* outputVector,
  vtkPolyData* input,
  vtkPolyData* output,
  vtkTable* history)
{
  // pvbatch and pvserver: rank 0 holds the cover (piece 0), the others empty pieces. Every rank
  // gets rank 0's points without the cover (their materials, frames and lamps: small), rank 0
  // deals each rank its rows, the ranks propagate together and rank 0 writes the solution; the
  // others keep empty outputs (vtkScenePieces.h) and never hold the whole cover.
  output->Initialize();
  history->Initialize();
  const int rank = controller->GetLocalProcessId();
  const auto pieceRole = static_cast<vtkScenePieces::Role>(role);
  std::string problem;
  if (pieceRole == vtkScenePieces::Role::PartialScene)
  {
    problem = vtkScenePieces::PartialSceneError(outputVector);
  }
  else if (rank == 0 && pieceRole != vtkScenePieces::Role::WholeScene)
  {
    problem = "rank 0 must hold the whole cover (piece 0)";
  }
  else if (rank != 0 && pieceRole == vtkScenePieces::Role::WholeScene)
  {
    problem = "some ranks other than rank 0 hold piece 0, but not all";
  }
  else if (rank == 0 && !input)
  {
    problem = "the input is not the cover points (vtkPolyData) of vtkSphericalCoverFilter";
  }
  problem = vtkCoverDistribution::Agree(controller, problem);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot propagate light: " << problem << ".");
    return 0;
  }
  vtkNew<vtkPolyData> points;
  if (rank == 0)
  {
    points->ShallowCopy(input);
    vtkNew<vtkFieldData> withoutCover;
    vtkFieldData* fd = input->GetFieldData();
    for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* array = fd->GetAbstractArray(a);
      if (!vtkSphericalCoverArrays::IsCoverArray(array->GetName()))
      {
        withoutCover->AddArray(array);
      }
    }
    points->SetFieldData(withoutCover);
  }
  vtkCoverDistribution::BroadcastFromFirst(controller, points);
  return this->PropagateOnRanks(
    controller, rank == 0 ? input : points.Get(), output, history, CoverHeld::FirstRank);
}

int vtkPLightPropagationFilter::PropagateOnRanks(vtkMultiProcessController* controller,
  vtkPolyData* input,
  vtkPolyData* output,
  vtkTable* history,
  CoverHeld held)
{
  // One process, or the ranks together (see the header): every rank reads the same cover (or,
  // FirstRank, rank 0 reads it and the others its points; or, Shares, every rank its share) and
  // agrees on each step before the next collective one, so that a failure is one error on
  // every rank and none waits for ever (vtkCoverDistribution.h).
  auto agree = [controller](const std::string& problem)
  { return controller ? vtkCoverDistribution::Agree(controller, problem) : problem; };
  const bool first = !controller || controller->GetLocalProcessId() == 0;
  // Whether this rank reads a cover from its input, whether that cover is the whole one, and
  // whether this rank writes the solution.
  const bool readsCover = held != CoverHeld::FirstRank || first;
  const bool wholeCover = readsCover && held != CoverHeld::Shares;
  // GatherSolution off: every rank keeps its piece of the solution (its rows and their regions).
  const bool pieces = controller && !this->GatherSolution;
  const bool writer = pieces || held == CoverHeld::EveryRank || first;
  std::string problem;
  if (!input)
  {
    problem = "the input is not the cover points (vtkPolyData) of vtkSphericalCoverFilter.";
  }
  sphcover::SphericalCover cover;
  std::vector<sphcover::Material> materials;
  bool named = false;
  sphcover::PointIllumination surfaces;
  sphcover::CoverFigures figures;
  if (problem.empty())
  {
    // Under MPI a rank propagates its rows: their state must fit, checked when they are known.
    problem = ReadPropagationInput(input,
      readsCover,
      held == CoverHeld::Shares,
      controller ? std::numeric_limits<double>::infinity() : this->MemoryLimit,
      cover,
      materials,
      named,
      surfaces);
  }
  double watts = 1.0;
  if (problem.empty())
  {
    SquareMetresPerUnit(input->GetFieldData(), watts, problem);
  }
  if (!problem.empty())
  {
    problem = "Cannot propagate light: " + problem;
  }
  else if (wholeCover && named)
  {
    // The cover's part of the figures now: under MPI the cover is let go before the
    // propagation (below). Of shares, on rank 0 once it has gathered them.
    problem = CoverFiguresOf(cover, surfaces, figures);
    if (!problem.empty())
    {
      problem = "Cannot sum up the solution: " + problem;
    }
  }
  problem = agree(problem);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  if (wholeCover)
  {
    WarnOfOpaquePanes(this, cover.HasPanes(), materials);
  }

  PropagationRanks ranks;
  sphcover::SphericalCover rows;
  // Shares: the whole cover's arrays, gathered on rank 0 for the solution.
  vtkNew<vtkPolyData> gatheredCover;
  std::vector<bool> lampPatch;
  bool firstBounce = false;
  PropagationResults results;
  try
  {
    // A step the user can abort (its warning held under MPI): the ranks agree on whether some
    // rank stopped, so that all stop together with its message as the error. True: go on.
    // The agreed error goes out after the held messages are let go (they would hold it too).
    auto completedOnEveryRank = [this, controller, &agree](const std::function<bool()>& step)
    {
      std::string stopped;
      {
        vtkHeldMessages held(controller ? this : nullptr);
        stopped = step() ? std::string() : held.First("Light propagation aborted.");
      }
      stopped = agree(stopped);
      if (!stopped.empty() && controller)
      {
        vtkErrorMacro(<< stopped);
      }
      return stopped.empty();
    };
    if (!controller)
    {
      rows = std::move(cover);
    }
    else
    {
      // Rank r shoots into the rows of its receivers. A rank keeps (or is dealt) its rows and
      // the whole cover goes before the balance and the propagation's state exist: the memory
      // that falls with the ranks. Its state must fit MemoryLimit, not the whole cover's.
      ranks.Share = vtkCoverDistribution::ShareOf(controller);
      ranks.Controller = controller;
      ranks.EveryRankWrites = held == CoverHeld::EveryRank || pieces;
      ranks.KeepsOwnRegions = pieces;
      if (held == CoverHeld::Shares)
      {
        rows = std::move(cover);
        const std::size_t foreign = sphcover::RowShares::FirstForeignRow(rows, ranks.Share);
        if (foreign < rows.PatchCount())
        {
          problem = "this rank's share of the cover holds the row of receiver " +
            std::to_string(foreign) + ", which another rank owns";
        }
      }
      else
      {
        rows = held == CoverHeld::FirstRank
          ? DealRows(controller, cover)
          : RowsOfRank(cover, controller->GetLocalProcessId(), controller->GetNumberOfProcesses());
      }
      cover = sphcover::SphericalCover();
      // A rank's rows' state; the figures are rank 0's, summed before (the whole cover's) or
      // joined after the propagation (shares), and not counted here.
      problem =
        agree(problem.empty() ? MemoryProblem(rows, materials, 0, this->MemoryLimit) : problem);
      if (!problem.empty())
      {
        vtkErrorMacro(<< "Cannot propagate light: " << problem);
        return 0;
      }
    }
    // Under MPI the ranks balance the exchange together, each its own rows.
    std::vector<double> factors;
    if (this->BalanceExchanges &&
      !completedOnEveryRank([&] { return BalanceFactors(this, rows, ranks.Share, factors); }))
    {
      return 0;
    }
    LampPatchesOf(input, rows, materials, lampPatch, firstBounce);
    auto propagation = std::make_unique<sphcover::LightPropagation>(rows, materials);
    if (!completedOnEveryRank(
          [&]
          {
            return Propagate(this,
              input,
              factors,
              *propagation,
              [&ranks](sphcover::LightPropagation& shared)
              { sphcover::SharePropagation(shared, ranks.Share); });
          }))
    {
      return 0;
    }
    OwnResults own = OwnResultsOf(*propagation, rows, lampPatch, firstBounce);
    const std::vector<sphcover::ShotRecord>& shots = propagation->History();
    if (controller)
    {
      // What each rank held and did (GetRankFigures), gathered in rank order.
      const double done[4] = { static_cast<double>(own.RowLengths.size()),
        static_cast<double>(rows.EntryCount()),
        static_cast<double>(sphcover::LightPropagation::EstimateBytes(rows, materials)),
        shots.empty() ? 0.0 : shots.back().Seconds };
      this->RankFigures = sphcover::JoinValues(ranks.Share, done, 4, true);
      this->RankCount = controller->GetNumberOfProcesses();
    }
    this->Shots = static_cast<int>(shots.size());
    if (writer)
    {
      WriteShotHistory(shots, watts, history);
    }
    // The propagation's state goes before the ranks' results are joined: the join holds every
    // rank's regions, and beside the state it was each rank's peak memory.
    propagation.reset();
    factors = std::vector<double>();
    if (held == CoverHeld::Shares && !pieces)
    {
      // The solution holds the whole cover: rank 0 gathers the shares (the ranks' rows) now,
      // holding neither the propagation's state nor the joined results, then sums up its
      // figures and keeps its arrays alone (the whole cover goes before the results come).
      problem = GatherShares(controller, std::move(rows), cover);
      if (first && problem.empty() && named)
      {
        problem = CoverFiguresOf(cover, surfaces, figures);
        if (!problem.empty())
        {
          problem = "Cannot sum up the solution: " + problem;
        }
      }
      else if (!problem.empty())
      {
        problem = "Light propagation failed: " + problem;
      }
      problem = agree(problem);
      if (!problem.empty())
      {
        history->Initialize();
        vtkErrorMacro(<< problem);
        return 0;
      }
      if (first)
      {
        WarnOfOpaquePanes(this, cover.HasPanes(), materials);
        vtkSphericalCoverArrays::Store(std::move(cover).ExportArrays(), gatheredCover);
      }
    }
    else if (held == CoverHeld::Shares)
    {
      // Kept in pieces: no rank holds the whole cover; rank 0 sums up the figures from the
      // ranks' rows.
      problem = named ? JoinCoverFigures(ranks.Share, rows, surfaces, figures) : "";
      problem = agree(problem.empty() ? problem : "Cannot sum up the solution: " + problem);
      if (!problem.empty())
      {
        history->Initialize();
        vtkErrorMacro(<< problem);
        return 0;
      }
      const bool seesPanes = vtkCoverDistribution::Count(controller, rows.HasPanes()) > 0;
      if (first)
      {
        WarnOfOpaquePanes(this, seesPanes, materials);
      }
    }
    if (!pieces)
    {
      rows = sphcover::SphericalCover(); // sent and let go already when shares
    }
    results = JoinResults(ranks, std::move(own));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Light propagation failed: " << e.what());
    return 0;
  }
  if (!writer)
  {
    return 1; // rank 0 writes the solution
  }
  output->ShallowCopy(input);
  if (pieces && held != CoverHeld::Shares)
  {
    // This rank's rows in place of the cover it was given (a share's arrays are its rows
    // already), marked as its share.
    vtkFieldData* fd = output->GetFieldData();
    for (int a = fd->GetNumberOfArrays() - 1; a >= 0; --a)
    {
      if (vtkSphericalCoverArrays::IsCoverArray(fd->GetAbstractArray(a)->GetName()))
      {
        fd->RemoveArray(a);
      }
    }
    vtkSphericalCoverArrays::Store(std::move(rows).ExportArrays(), output);
    rows = sphcover::SphericalCover();
    vtkSphericalCoverArrays::MarkShare(output, ranks.Share.Rank(), ranks.Share.Ranks());
  }
  else if (held == CoverHeld::Shares && !pieces)
  {
    // The whole cover's arrays in place of this rank's share (referenced, not copied).
    vtkFieldData* fd = gatheredCover->GetFieldData();
    for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
    {
      output->GetFieldData()->AddArray(fd->GetAbstractArray(a));
    }
    output->GetFieldData()->RemoveArray(names::CoverRowShare);
  }
  // The figures sum up the whole: of a cover in shares, rank 0 alone sums them up.
  const bool sumsUp = named && (wholeCover || first);
  if (!WriteSolution(this,
        results,
        this->Shots,
        watts,
        sumsUp ? &figures : nullptr,
        std::move(surfaces),
        output))
  {
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPLightPropagationFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GatherSolution: " << (this->GatherSolution ? "On" : "Off") << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
