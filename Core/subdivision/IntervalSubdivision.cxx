// SPDX-License-Identifier: BSD-3-Clause
#include "subdivision/IntervalSubdivision.h"

#include "geometry/BoundingBoxTree.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <climits>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace sphcover
{
namespace
{
Box BoxOf(const Patch& patch)
{
  // The control net's box encloses the patch (convex hull property): the interval box of §4.1.
  const IntervalVec3& bounds = patch.Geometry.Bounds();
  return { bounds.Lower(), bounds.Upper() };
}

/// Receivers per progress report / abort check.
constexpr std::size_t BatchSize = 64;

/// Bytes a patch of this geometry holds: the struct and its control and derivative nets.
std::size_t BytesOfPatch(const BezierPatch& geometry)
{
  const std::size_t nets = geometry.ControlPoints().size() + geometry.DerivativeNetU().size() +
    geometry.DerivativeNetV().size();
  return sizeof(Patch) + nets * sizeof(glm::dvec3);
}

/// The interval boxes of the leaves, in leaf order.
std::vector<Box> BoxesOf(const std::vector<Patch>& nodes, const std::vector<int>& leaves)
{
  std::vector<Box> boxes;
  boxes.reserve(leaves.size());
  for (int node : leaves)
  {
    boxes.push_back(BoxOf(nodes[static_cast<size_t>(node)]));
  }
  return boxes;
}

/// Pairs (receiver, source) with at least one new patch: a sweep's candidates.
double CandidatePairs(const std::vector<bool>& leafIsNew)
{
  const size_t count = leafIsNew.size();
  const size_t fresh = static_cast<size_t>(std::count(leafIsNew.begin(), leafIsNew.end(), true));
  return static_cast<double>(fresh) *
    (2.0 * static_cast<double>(count) - static_cast<double>(fresh));
}

/// One sweep's pair tests over the leaves (paper §4.3 Step 2): each receiver against the
/// sources the bounding-volume hierarchy does not cull, merging split requests by priority.
class SweepExamination
{
public:
  SweepExamination(std::vector<PatchView> views,
    const std::vector<Patch>& nodes,
    const std::vector<int>& leaves,
    const std::vector<bool>& leafIsNew,
    const SubdivisionSettings& settings,
    double minimumDiagonal,
    std::vector<std::atomic<int>>& requested)
    : Views(std::move(views))
    , Nodes(nodes)
    , Leaves(leaves)
    , LeafIsNew(leafIsNew)
    , Settings(settings)
    , CellAngle(settings.CellAngle())
    , MinimumDiagonal(minimumDiagonal)
    , Requested(requested)
    , Boxes(BoxesOf(nodes, leaves))
    , Tree(this->Boxes)
  {
    this->Tree.MarkItems(leafIsNew);
    // No request yet: the lowest (highest-priority) reason wins, so INT_MAX means none.
    for (auto& r : requested)
    {
      r.store(INT_MAX, std::memory_order_relaxed);
    }
  }

  /// Tests receiver i against every candidate source; safe to call from several threads.
  void ExamineReceiver(size_t i);

  std::size_t PairTests() const { return this->Pairs.load(); }
  std::size_t LimitedPairs() const { return this->Limited.load(); }

private:
  /// A split of patch k is allowed when it is not at MaxLevel, is larger than MinPatchSize and
  /// projects, from the point that asks, to more than about one cell (§4.3 note 2).
  bool CanSplit(size_t k, const glm::dvec3& from) const
  {
    if (this->Nodes[static_cast<size_t>(this->Leaves[k])].Level >= this->Settings.MaxLevel ||
      (this->MinimumDiagonal > 0.0 && this->Boxes[k].Diagonal() <= this->MinimumDiagonal))
    {
      return false;
    }
    const double distance = this->Boxes[k].DistanceTo(from);
    return distance <= 0.0 || this->Boxes[k].Diagonal() > this->CellAngle * distance;
  }

  /// Split requests: the highest-priority (lowest) reason per leaf, so that the merge does not
  /// depend on the order in which threads report.
  void Request(size_t k, SplitReason reason)
  {
    int current = this->Requested[k].load(std::memory_order_relaxed);
    const int value = static_cast<int>(reason);
    while (value < current &&
      !this->Requested[k].compare_exchange_weak(current, value, std::memory_order_relaxed))
    {
    }
  }

  const std::vector<PatchView> Views;
  const std::vector<Patch>& Nodes;
  const std::vector<int>& Leaves;
  const std::vector<bool>& LeafIsNew;
  const SubdivisionSettings& Settings;
  const double CellAngle;
  /// MinPatchSize times the diagonal of the scene's box.
  const double MinimumDiagonal;
  std::vector<std::atomic<int>>& Requested;
  std::vector<Box> Boxes;
  BoundingBoxTree Tree;
  std::atomic<size_t> Pairs{ 0 };
  std::atomic<size_t> Limited{ 0 };
};

void SweepExamination::ExamineReceiver(size_t i)
{
  const PatchView& receiver = this->Views[i];
  const bool receiverIsNew = this->LeafIsNew[i];
  size_t localPairs = 0;
  size_t localLimited = 0;
  this->Tree.Traverse(
    [&](const BoundingBoxTree::Node& node)
    {
      // Pairs of two old patches were settled in an earlier sweep.
      if (!receiverIsNew && !node.Flag)
      {
        return false;
      }
      // A group wholly below the tangent plane sends no light to P_i: classified at once.
      return node.Bounds.MaxHeightAbove(receiver.Point, receiver.Normal) > 0.0;
    },
    [&](int32_t item)
    {
      const size_t j = static_cast<size_t>(item);
      if (j == i || (!receiverIsNew && !this->LeafIsNew[j]))
      {
        return;
      }
      // The limits first: a pair whose patches may not be split either way cannot change Q.
      const bool sourceMaySplit = this->CanSplit(j, receiver.Point);
      const bool receiverMaySplit = this->CanSplit(i, this->Views[j].Point);
      if (!sourceMaySplit && !receiverMaySplit)
      {
        ++localLimited;
        return;
      }
      ++localPairs;
      const PairAssessment assessment =
        AssessPair(receiver, this->Views[j], this->Settings, sourceMaySplit, receiverMaySplit);
      if (assessment.SplitSource != SplitReason::None)
      {
        this->Request(j, assessment.SplitSource);
      }
      if (assessment.SplitReceiver != SplitReason::None)
      {
        this->Request(i, assessment.SplitReceiver);
      }
    });
  this->Pairs.fetch_add(localPairs, std::memory_order_relaxed);
  this->Limited.fetch_add(localLimited, std::memory_order_relaxed);
}
}

IntervalSubdivision::IntervalSubdivision(const Scene& scene, const SubdivisionSettings& settings)
  : Environment(scene)
  , Settings(settings)
{
  const std::string problem = settings.Problem();
  if (!problem.empty())
  {
    throw std::invalid_argument(problem);
  }
  // Step 0: Q = S, each surface one patch over its whole domain.
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    this->Nodes.emplace_back(static_cast<int>(s), UVRect::Unit(), 0, scene.Surfaces[s].Patch);
    this->Leaves.push_back(static_cast<int>(s));
    this->LeafIsNew.push_back(true);
    this->NodeBytes += BytesOfPatch(scene.Surfaces[s].Patch);
  }
  if (!scene.Surfaces.empty())
  {
    glm::dvec3 lower;
    glm::dvec3 upper;
    scene.Bounds(lower, upper);
    this->SceneDiagonal = glm::length(upper - lower);
  }
}

PatchView IntervalSubdivision::ViewOfPatch(const Patch& patch) const
{
  const Surface& surface = this->Environment.Surfaces[static_cast<size_t>(patch.SurfaceIndex)];
  const Material& material =
    this->Environment.Materials[static_cast<size_t>(surface.MaterialIndex)];
  return ViewOf(patch, material.Type == MaterialType::Diffuse);
}

void IntervalSubdivision::Split(int node, SplitReason reason)
{
  const Patch& parent = this->Nodes[static_cast<size_t>(node)];
  const BezierPatch& whole =
    this->Environment.Surfaces[static_cast<size_t>(parent.SurfaceIndex)].Patch;
  // SplitInThree returns copies, so appending to Nodes cannot invalidate `parent` mid-split.
  for (Patch& piece : SplitInThree(parent, whole, reason))
  {
    this->Nodes.push_back(std::move(piece));
  }
}

bool IntervalSubdivision::Run(const ProgressCallback& progress, const ParallelFor& parallelFor)
{
  // The pair tests of the last sweep per pair it could have tested (those with a new patch):
  // what the bounding-volume culling and the limits leave, to predict the next sweep's cost.
  // 1 before the first sweep (an upper bound: every pair).
  double testedShare = 1.0;
  // The surfaces' own patches against the budget first: a scene of more patches than it allows
  // is refused before the first sweep's pair tests, not after them.
  this->CheckBudget({});
  while (true)
  {
    // No leaf below MaxLevel: no pair can split anything, and a sweep would only count them as
    // limited, O(N^2) pair visits for nothing (20,000 tiles at max_level 0: 4 s).
    if (std::all_of(this->Leaves.begin(),
          this->Leaves.end(),
          [this](int node)
          { return this->Nodes[static_cast<size_t>(node)].Level >= this->Settings.MaxLevel; }))
    {
      break;
    }
    const size_t count = this->Leaves.size();
    const double candidates = CandidatePairs(this->LeafIsNew);
    this->CheckCost(testedShare * candidates, "would make about");

    std::vector<std::atomic<int>> requested(count);
    std::size_t pairTests = 0;
    std::size_t limited = 0;
    if (!this->ExaminePairs(requested, pairTests, limited, progress, parallelFor))
    {
      return false;
    }
    this->Stats.PairTests += pairTests;
    testedShare = candidates > 0.0 ? static_cast<double>(pairTests) / candidates : 1.0;
    this->Stats.LimitedPairs += limited;
    ++this->Stats.Sweeps;

    this->CheckBudget(requested);
    if (!this->ApplySplits(requested))
    {
      break;
    }
  }
  if (progress)
  {
    progress(1.0);
  }
  return true;
}

bool IntervalSubdivision::ExaminePairs(std::vector<std::atomic<int>>& requested,
  std::size_t& pairTests,
  std::size_t& limited,
  const ProgressCallback& progress,
  const ParallelFor& parallelFor) const
{
  const size_t count = this->Leaves.size();
  // Sweeps needed is unknown in advance; every sweep deepens by at most one level.
  const double expectedSweeps = this->Settings.MaxLevel + 1.0;
  std::vector<PatchView> views;
  views.reserve(count);
  for (int node : this->Leaves)
  {
    views.push_back(this->ViewOfPatch(this->Nodes[static_cast<size_t>(node)]));
  }
  SweepExamination sweep(std::move(views),
    this->Nodes,
    this->Leaves,
    this->LeafIsNew,
    this->Settings,
    this->Settings.MinPatchSize * this->SceneDiagonal,
    requested);

  // Receivers in batches, so progress is reported (and abort honoured) from this thread.
  for (size_t first = 0; first < count; first += BatchSize)
  {
    const size_t batch = std::min(BatchSize, count - first);
    parallelFor(batch,
      [&](size_t begin, size_t end)
      {
        for (size_t k = begin; k < end; ++k)
        {
          sweep.ExamineReceiver(first + k);
        }
      });
    // The prediction can be low: the budget also holds while the sweep runs.
    this->CheckCost(static_cast<double>(sweep.PairTests()), "has made");
    if (progress &&
      !progress(
        std::min(1.0, (this->Stats.Sweeps + double(first + batch) / count) / expectedSweeps)))
    {
      return false;
    }
  }
  pairTests = sweep.PairTests();
  limited = sweep.LimitedPairs();
  return true;
}

bool IntervalSubdivision::ApplySplits(const std::vector<std::atomic<int>>& requested)
{
  const size_t count = this->Leaves.size();
  std::vector<int> nextLeaves;
  std::vector<bool> nextIsNew;
  for (size_t k = 0; k < count; ++k)
  {
    const int reason = requested[k].load();
    if (reason == INT_MAX)
    {
      nextLeaves.push_back(this->Leaves[k]);
      nextIsNew.push_back(false);
      continue;
    }
    const int firstChild = static_cast<int>(this->Nodes.size());
    this->Split(this->Leaves[k], static_cast<SplitReason>(reason));
    this->NodeBytes += 3 * BytesOfPatch(this->Nodes.back().Geometry);
    ++this->Stats.Splits[static_cast<size_t>(reason)];
    for (int c = 0; c < 3; ++c)
    {
      nextLeaves.push_back(firstChild + c);
      nextIsNew.push_back(true);
    }
  }
  const bool splitAny = nextLeaves.size() != count;
  this->Leaves = std::move(nextLeaves);
  this->LeafIsNew = std::move(nextIsNew);
  return splitAny;
}

void IntervalSubdivision::CheckCost(double sweepPairTests, const char* verb) const
{
  // The pair tests are the subdivision's time (about 0.7 to 1.7 million per second on two
  // threads in the Cornell box and the teapot room): a budget on them bounds the run.
  const double total = static_cast<double>(this->Stats.PairTests) + sweepPairTests;
  if (total > static_cast<double>(this->Settings.MaximumPairTests))
  {
    std::ostringstream problem;
    problem.precision(3);
    problem << "sweep " << this->Stats.Sweeps << " of " << this->Leaves.size() << " patches "
            << verb << " " << total << " pair tests in all, more than the budget of "
            << static_cast<double>(this->Settings.MaximumPairTests)
            << " (minutes to hours); raise the tolerance or lower MaxLevel";
    throw std::length_error(problem.str());
  }
}

void IntervalSubdivision::CheckBudget(const std::vector<std::atomic<int>>& requested) const
{
  // Checked before splitting, so the budget is never exceeded: a tolerance so small that every
  // pair splits, with a deep MaxLevel, would otherwise triple the patch list sweep after sweep.
  std::size_t leaves = this->Leaves.size();
  std::size_t bytes = this->NodeBytes;
  for (size_t k = 0; k < requested.size(); ++k)
  {
    if (requested[k].load() != INT_MAX)
    {
      const Patch& parent = this->Nodes[static_cast<size_t>(this->Leaves[k])];
      leaves += 2;
      bytes += 3 * BytesOfPatch(parent.Geometry);
    }
  }
  if (leaves > this->Settings.MaximumPatches || bytes > this->Settings.MemoryLimitBytes)
  {
    std::ostringstream problem;
    problem.precision(3);
    problem << "sweep " << this->Stats.Sweeps << " would make " << leaves << " patches ("
            << static_cast<double>(bytes) / (1024.0 * 1024.0) << " MiB), more than the budget of "
            << this->Settings.MaximumPatches << " patches and "
            << static_cast<double>(this->Settings.MemoryLimitBytes) / (1024.0 * 1024.0)
            << " MiB; raise the tolerance or lower MaxLevel";
    throw std::length_error(problem.str());
  }
}

std::vector<Patch> IntervalSubdivision::Patches() const
{
  return CollectPatches(this->Nodes, this->Leaves);
}

} // namespace sphcover
