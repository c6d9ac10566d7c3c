// SPDX-License-Identifier: BSD-3-Clause
#include "cover/CoverRefinement.h"

#include "cover/EnclosureSplit.h"
#include "cover/HemisphereGrid.h"
#include "cover/HiddenPartAnalysis.h"
#include "cover/HorizonSplit.h"
#include "cover/RBuffer.h"
#include "math/ByteBuffer.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <exception>
#include <memory>
#include <stdexcept>
#include <utility>

namespace sphcover
{
namespace
{
/// Receivers per ParallelFor call; progress and abort are checked between calls.
constexpr std::size_t BatchSize = 64;

/// One leaf's Step 1 verdict (EnclosureSplitter::Straddles), as the ranks join it.
struct EnclosureVerdict
{
  uint64_t Split = 0;
  uint64_t Probes = 0;
};

/// Runs body(k) for every k in [0, count), in batches of BatchSize items shared out by `run`;
/// after each batch afterBatch(items done so far) reports progress and may stop the loop by
/// returning false (then so does this).
template<class Body, class AfterBatch>
bool ForEachInBatches(std::size_t count,
  const ParallelFor& run,
  Body&& body,
  AfterBatch&& afterBatch)
{
  for (std::size_t first = 0; first < count; first += BatchSize)
  {
    const std::size_t batch = std::min(BatchSize, count - first);
    run(batch,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t k = first + begin; k < first + end; ++k)
        {
          body(k);
        }
      });
    if (!afterBatch(first + batch))
    {
      return false;
    }
  }
  return true;
}
}

std::string RefinementSettings::Problem() const
{
  if (this->MaxLevel < 0)
  {
    return "RefinementSettings: MaxLevel must be >= 0";
  }
  if (!(this->HiddenFraction > 0.0 && this->HiddenFraction < 1.0))
  {
    return "RefinementSettings: HiddenFraction must be in (0, 1)";
  }
  if (!(this->EnclosureMargin >= 0.0 && this->EnclosureMargin <= 4.0))
  {
    return "RefinementSettings: EnclosureMargin must be in [0, 4]";
  }
  if (!(this->HorizonReach > 0.0 && this->HorizonReach <= 8.0))
  {
    return "RefinementSettings: HorizonReach must be in (0, 8]";
  }
  if (this->ProbesPerSide < 2 || this->ProbesPerSide > 16)
  {
    return "RefinementSettings: ProbesPerSide must be in [2, 16]";
  }
  if (!(this->MinimumHiddenCells >= 0.0) || !(this->MinimumVisibleCells >= 0.0))
  {
    return "RefinementSettings: MinimumHiddenCells and MinimumVisibleCells must be >= 0";
  }
  try
  {
    HemisphereGrid grid(
      this->Cover.ThetaBins, this->Cover.PhiBins, this->Cover.SamplesTheta, this->Cover.SamplesPhi);
  }
  catch (const std::invalid_argument& error)
  {
    return std::string("RefinementSettings: ") + error.what();
  }
  return std::string();
}

CoverRefinement::CoverRefinement(const Scene& scene,
  std::vector<Patch> patches,
  const RefinementSettings& settings)
  : Environment(scene)
  , Settings(settings)
  , Nodes(std::move(patches))
{
  const std::string problem = settings.Problem();
  if (!problem.empty())
  {
    throw std::invalid_argument(problem);
  }
  for (const Patch& patch : this->Nodes)
  {
    if (patch.SurfaceIndex < 0 || static_cast<size_t>(patch.SurfaceIndex) >= scene.Surfaces.size())
    {
      throw std::invalid_argument("CoverRefinement: a patch's surface is not in the scene");
    }
  }
  this->Leaves.resize(this->Nodes.size());
  for (size_t k = 0; k < this->Nodes.size(); ++k)
  {
    this->Leaves[k] = static_cast<int>(k);
  }
  this->VisibleNodes.resize(this->Nodes.size());
  this->Analysed.assign(this->Nodes.size(), false);
  this->Stats.InputPatches = this->Nodes.size();
  this->Stats.OutputPatches = this->Nodes.size();
}

bool CoverRefinement::Run(const ProgressCallback& progress, const ParallelFor& parallelFor)
{
  const ParallelFor& run = parallelFor ? parallelFor : ParallelFor(SequentialFor);
  // The receiver side costs a few rays and box tests per patch; the hemisphere analysis most
  // of the time.
  const double receiverShare = this->Settings.AnalyseHemispheres ? 0.05 : 1.0;
  const double probeShare = this->Settings.SplitHorizons ? 0.8 * receiverShare : receiverShare;
  // Steps 1 and 2's leaves and Step 3's hemispheres are shared among the ranks (RankShare.h),
  // joined every round.
  const bool completed = !this->Settings.SplitEnclosureBoundaries ||
    this->SplitAcrossEnclosures(progress, run, probeShare);
  if (!completed ||
    (this->Settings.SplitHorizons &&
      !this->SplitAcrossHorizons(
        progress, run, this->Settings.SplitEnclosureBoundaries ? probeShare : 0.0, receiverShare)))
  {
    return false;
  }
  const bool receiverSide = this->Settings.SplitEnclosureBoundaries || this->Settings.SplitHorizons;
  if (this->Settings.AnalyseHemispheres &&
    !this->AnalyseHemispheres(progress, run, receiverSide ? receiverShare : 0.0))
  {
    return false;
  }
  if (progress)
  {
    progress(1.0);
  }
  return true;
}

void CoverRefinement::SetProbeExtents(std::vector<UVRect> extents, std::vector<int> groups)
{
  if ((!extents.empty() && extents.size() != this->Environment.Surfaces.size()) ||
    (!groups.empty() && groups.size() != this->Environment.Surfaces.size()))
  {
    throw std::invalid_argument("CoverRefinement: one probe extent and group per surface");
  }
  this->Extents.Extents = std::move(extents);
  this->Extents.Groups = std::move(groups);
}

void CoverRefinement::SplitLeaves(const std::vector<char>& split)
{
  std::vector<int> nextLeaves;
  for (std::size_t k = 0; k < this->Leaves.size(); ++k)
  {
    if (!split[k])
    {
      nextLeaves.push_back(this->Leaves[k]);
      continue;
    }
    const Patch& leaf = this->Nodes[static_cast<std::size_t>(this->Leaves[k])];
    const BezierPatch& surface =
      this->Environment.Surfaces[static_cast<std::size_t>(leaf.SurfaceIndex)].Patch;
    for (Patch& piece : SplitInThree(leaf, surface, SplitReason::RBuffer))
    {
      nextLeaves.push_back(this->AddNode(std::move(piece)));
    }
  }
  this->Leaves = std::move(nextLeaves);
}

int CoverRefinement::AddNode(Patch piece)
{
  const int node = static_cast<int>(this->Nodes.size());
  this->Nodes.push_back(std::move(piece));
  this->VisibleNodes.emplace_back();
  this->Analysed.push_back(false);
  return node;
}

bool CoverRefinement::SplitAcrossEnclosures(const ProgressCallback& progress,
  const ParallelFor& run,
  double progressShare)
{
  // Built on every rank; the ranks agree that it was before they share its probes, so that a
  // rank whose build failed leaves no other waiting in a round's join.
  std::unique_ptr<const EnclosureSplitter> splitter;
  std::exception_ptr failure;
  try
  {
    splitter =
      std::make_unique<const EnclosureSplitter>(this->Environment, this->Extents, this->Settings);
  }
  catch (...)
  {
    failure = std::current_exception();
  }
  if (!this->Share.EveryRankOk(!failure) && !failure)
  {
    throw RankShare::PeerFailure();
  }
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  if (splitter->Empty())
  {
    return true;
  }
  // Rounds, as Step 2's: the leaves not yet probed are probed (each rank its share, the
  // verdicts joined in leaf order), those straddling a boundary are split in three in place and
  // their pieces probed in the next round. A patch's verdict depends on the patch alone, so a
  // probed leaf keeps it: the leaves come out as splitting each leaf recursively, depth first,
  // gives them. Each round deepens by one level: at most MaxLevel + 1 rounds.
  const double expectedRounds = this->Settings.MaxLevel + 1.0;
  // The leaves not yet probed: nodes from this index on (pieces of the last round's splits).
  std::size_t firstUnprobed = 0;
  for (int round = 0;; ++round)
  {
    std::vector<std::size_t> untested;
    for (std::size_t k = 0; k < this->Leaves.size(); ++k)
    {
      if (static_cast<std::size_t>(this->Leaves[k]) >= firstUnprobed)
      {
        untested.push_back(k);
      }
    }
    if (untested.empty())
    {
      break;
    }
    std::vector<EnclosureVerdict> verdicts(untested.size());
    const bool finished = ShareItems(this->Share,
      untested.size(),
      verdicts,
      [&](const std::vector<std::size_t>& mine)
      {
        return ForEachInBatches(
          mine.size(),
          run,
          [&](std::size_t n)
          {
            const Patch& leaf =
              this->Nodes[static_cast<std::size_t>(this->Leaves[untested[mine[n]]])];
            std::size_t probes = 0;
            EnclosureVerdict& verdict = verdicts[mine[n]];
            verdict.Split =
              leaf.Level < this->Settings.MaxLevel && splitter->Straddles(leaf, probes) ? 1 : 0;
            verdict.Probes = probes;
          },
          [&](std::size_t done)
          {
            const double share = std::min(1.0,
              (round + double(done) / double(std::max<std::size_t>(1, mine.size()))) /
                expectedRounds);
            return !progress || progress(progressShare * share);
          });
      });
    if (!finished)
    {
      return false;
    }
    std::vector<char> split(this->Leaves.size(), 0);
    std::size_t splits = 0;
    for (std::size_t u = 0; u < untested.size(); ++u)
    {
      split[untested[u]] = verdicts[u].Split != 0 ? 1 : 0;
      splits += split[untested[u]];
      this->Stats.Probes += static_cast<std::size_t>(verdicts[u].Probes);
    }
    firstUnprobed = this->Nodes.size();
    this->SplitLeaves(split);
    this->Stats.Splits += splits;
    this->Stats.EnclosureSplits += splits;
  }
  this->Stats.OutputPatches = this->Leaves.size();
  return true;
}

bool CoverRefinement::SplitAcrossHorizons(const ProgressCallback& progress,
  const ParallelFor& run,
  double progressStart,
  double progressEnd)
{
  const HorizonTest horizons(this->Environment, this->Extents, this->Settings);
  // Rounds: every leaf is tested against the current list; the leaves that see a horizon
  // across them are split, and their pieces tested again in the next round (each round deepens
  // by one level, so there are at most MaxLevel + 1 rounds).
  for (int round = 0; round <= this->Settings.MaxLevel; ++round)
  {
    // Each rank tests its share of the leaves; the verdicts are joined in leaf order.
    const size_t count = this->Leaves.size();
    std::vector<char> split(count, 0);
    const bool finished = ShareItems(this->Share,
      count,
      split,
      [&](const std::vector<std::size_t>& mine)
      {
        return ForEachInBatches(
          mine.size(),
          run,
          [&](size_t n)
          {
            const Patch& leaf = this->Nodes[static_cast<size_t>(this->Leaves[mine[n]])];
            split[mine[n]] = leaf.Level < this->Settings.MaxLevel &&
              horizons.Across(leaf, this->Nodes, this->Leaves);
          },
          [&](size_t done)
          {
            const double share =
              (round + double(done) / double(std::max<std::size_t>(1, mine.size()))) /
              (this->Settings.MaxLevel + 1);
            return !progress || progress(progressStart + (progressEnd - progressStart) * share);
          });
      });
    if (!finished)
    {
      return false;
    }
    const std::size_t splits =
      static_cast<std::size_t>(std::count_if(split.begin(), split.end(), [](char s) { return s; }));
    this->SplitLeaves(split);
    this->Stats.Splits += splits;
    this->Stats.HorizonSplits += splits;
    this->Stats.OutputPatches = this->Leaves.size();
    if (splits == 0)
    {
      break;
    }
  }
  return true;
}

bool CoverRefinement::AnalyseRound(const HemisphereGrid& grid,
  const ProgressCallback& progress,
  const ParallelFor& run,
  double progressStart,
  std::vector<char>& hidden,
  std::vector<char>& disconnected)
{
  // Each round deepens by at most one level.
  const double expectedRounds = this->Settings.MaxLevel + 1.0;
  const size_t count = this->Leaves.size();
  std::vector<Patch> current;
  current.reserve(count);
  for (int node : this->Leaves)
  {
    current.push_back(this->Nodes[static_cast<size_t>(node)]);
  }
  std::vector<size_t> receivers;
  for (size_t k = 0; k < count; ++k)
  {
    if (!this->Analysed[static_cast<size_t>(this->Leaves[k])])
    {
      receivers.push_back(k);
    }
  }
  const std::unique_ptr<RBufferFiller> filler =
    RBufferFiller::Create(RBufferFill::Projection, current, grid, this->Settings.Cover.FillOptions);

  // Step 3 for every hemisphere that may have changed. The merge of one hemisphere's verdicts
  // does not depend on the others' (flags are or-ed, the visible lists are per node), so the
  // order of the merge does not matter. Under MPI each rank analyses its share of the
  // hemispheres and the verdicts are joined (RankShare.h).
  hidden.assign(count, 0);
  disconnected.assign(count, 0);
  const std::vector<size_t> mine = this->Share.MyItems(receivers.size());
  std::vector<char> myVerdicts; // under MPI: node, visible nodes, per analysed hemisphere
  ByteWriter verdicts(myVerdicts);
  std::size_t limited = 0;
  auto merge = [&](const HemisphereAnalysis& analysis, size_t receiver)
  {
    const size_t node = static_cast<size_t>(this->Leaves[receiver]);
    this->Analysed[node] = true;
    std::vector<int>& visible = this->VisibleNodes[node];
    visible.clear();
    for (uint32_t j : analysis.Visible)
    {
      visible.push_back(this->Leaves[j]);
    }
    std::sort(visible.begin(), visible.end());
    for (uint32_t j : analysis.Hidden)
    {
      hidden[j] = 1;
    }
    for (uint32_t j : analysis.Disconnected)
    {
      disconnected[j] = 1;
    }
    limited += analysis.Limited;
    if (this->Share.Distributed())
    {
      verdicts.Value(static_cast<uint64_t>(node));
      verdicts.Array(visible);
    }
  };
  bool completed = true;
  std::exception_ptr failure;
  try
  {
    std::vector<HemisphereAnalysis> results;
    for (size_t first = 0; first < mine.size() && completed; first += BatchSize)
    {
      const size_t batch = std::min(BatchSize, mine.size() - first);
      results.assign(batch, HemisphereAnalysis());
      run(batch,
        [&](size_t begin, size_t end)
        {
          RBuffer buffer(grid);
          HiddenPartAnalyser analyser(this->Settings);
          for (size_t k = begin; k < end; ++k)
          {
            analyser.Analyse(receivers[mine[first + k]], current, *filler, buffer, results[k]);
          }
        });
      for (size_t k = 0; k < batch; ++k)
      {
        merge(results[k], receivers[mine[first + k]]);
      }
      completed = !progress ||
        progress(progressStart +
          (1.0 - progressStart) *
            std::min(
              1.0, (this->Stats.Rounds + double(first + batch) / mine.size()) / expectedRounds));
    }
  }
  catch (...)
  {
    failure = std::current_exception();
  }
  if (this->Share.Distributed())
  {
    this->JoinVerdicts(myVerdicts, completed && !failure, hidden, disconnected, limited);
  }
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  if (!completed)
  {
    return false;
  }
  this->Stats.RowsAnalysed += receivers.size();
  this->Stats.LimitedRequests += limited;
  return true;
}

void CoverRefinement::JoinVerdicts(std::vector<char>& myVerdicts,
  bool ok,
  std::vector<char>& hidden,
  std::vector<char>& disconnected,
  std::size_t& limited)
{
  // Every rank's verdicts: its hidden and disconnected flags, its limited requests and the
  // visible nodes of the hemispheres it analysed.
  std::vector<char> mine;
  ByteWriter out(mine);
  out.Array(hidden);
  out.Array(disconnected);
  out.Value(static_cast<uint64_t>(limited));
  out.Values(myVerdicts.data(), myVerdicts.size());
  myVerdicts = std::vector<char>();
  std::vector<std::vector<char>> all;
  const bool everyRankOk = this->Share.Join(mine, ok, all);
  if (!ok)
  {
    return; // this rank's own failure is reported by the caller
  }
  if (!everyRankOk)
  {
    throw RankShare::PeerFailure();
  }
  limited = 0;
  std::vector<char> flags[2];
  for (size_t r = 0; r < all.size(); ++r)
  {
    ByteReader in(all[r]);
    uint64_t rankLimited = 0;
    bool read = in.Array(flags[0]) && in.Array(flags[1]) && in.Value(rankLimited) &&
      flags[0].size() == hidden.size() && flags[1].size() == disconnected.size();
    for (size_t k = 0; read && k < hidden.size(); ++k)
    {
      hidden[k] = static_cast<char>(hidden[k] | flags[0][k]);
      disconnected[k] = static_cast<char>(disconnected[k] | flags[1][k]);
    }
    limited += static_cast<size_t>(rankLimited);
    while (read && !in.AtEnd())
    {
      uint64_t node = 0;
      std::vector<int> visible;
      read = in.Value(node) && node < this->Nodes.size() && in.Array(visible);
      if (read)
      {
        this->Analysed[static_cast<size_t>(node)] = true;
        this->VisibleNodes[static_cast<size_t>(node)] = std::move(visible);
      }
    }
    if (!read)
    {
      throw std::runtime_error(
        "CoverRefinement: rank " + std::to_string(r) + "'s verdicts are damaged");
    }
  }
}

bool CoverRefinement::ReplaceSplitPatches(const std::vector<char>& hidden,
  const std::vector<char>& disconnected)
{
  // Every split patch is replaced by its three pieces, in its place.
  const size_t count = this->Leaves.size();
  std::vector<char> split(count, 0);
  std::vector<char> splitNode(this->Nodes.size(), 0);
  for (size_t k = 0; k < count; ++k)
  {
    if (!hidden[k] && !disconnected[k])
    {
      continue;
    }
    const int node = this->Leaves[k];
    split[k] = 1;
    splitNode[static_cast<size_t>(node)] = 1;
    ++this->Stats.Splits;
    if (!hidden[k])
    {
      ++this->Stats.DisconnectedSplits;
    }
    this->VisibleNodes[static_cast<size_t>(node)].clear();
  }
  this->SplitLeaves(split);
  if (this->Leaves.size() == count)
  {
    return false;
  }
  // A hemisphere in which a split patch was visible must be analysed again (its pieces may
  // be hidden differently); one in which it was hidden keeps its verdicts.
  for (int node : this->Leaves)
  {
    const std::vector<int>& visible = this->VisibleNodes[static_cast<size_t>(node)];
    if (this->Analysed[static_cast<size_t>(node)] &&
      std::any_of(visible.begin(),
        visible.end(),
        [&](int j) { return splitNode[static_cast<size_t>(j)] != 0; }))
    {
      this->Analysed[static_cast<size_t>(node)] = false;
    }
  }
  this->Stats.OutputPatches = this->Leaves.size();
  return true;
}

bool CoverRefinement::AnalyseHemispheres(const ProgressCallback& progress,
  const ParallelFor& run,
  double progressStart)
{
  const SphericalCoverOptions& options = this->Settings.Cover;
  const HemisphereGrid grid(
    options.ThetaBins, options.PhiBins, options.SamplesTheta, options.SamplesPhi);
  std::vector<char> hidden;
  std::vector<char> disconnected;
  do
  {
    // Step 3, then Step 5 ("Modify Q by suitably replacing all subdivided patches which are
    // not completely hidden"), until no patch asks to be split.
    if (!this->AnalyseRound(grid, progress, run, progressStart, hidden, disconnected))
    {
      return false;
    }
    ++this->Stats.Rounds;
  } while (this->ReplaceSplitPatches(hidden, disconnected));
  return true;
}

std::vector<Patch> CoverRefinement::Patches() const
{
  return CollectPatches(this->Nodes, this->Leaves);
}

} // namespace sphcover
