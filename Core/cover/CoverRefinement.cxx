// SPDX-License-Identifier: BSD-3-Clause
#include "cover/CoverRefinement.h"

#include "math/Constants.h"

#include "cover/HemisphereGrid.h"
#include "cover/RBuffer.h"
#include "cover/RayCastFill.h"
#include "geometry/BoundingBoxTree.h"
#include "geometry/RayCaster.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>

namespace sphcover
{
namespace
{
/// Receivers per ParallelFor call; progress and abort are checked between calls.
constexpr std::size_t BatchSize = 64;

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

/// A source's tangent plane cuts a receiver's surface when points of it around the receiver
/// lie farther than this fraction of the receiver's size to both sides
/// (CoverRefinement::SeesHorizonAcross).
constexpr double HorizonTolerance = 0.02;
/// A surface whose control points lie within this fraction of its size from one plane is
/// planar (a horizon source).
constexpr double PlanarTolerance = 0.01;

/// Union-find over the samples of one hemisphere (path halving, union by index so that the
/// labelling does not depend on anything but the R-buffer).
struct SampleRegions
{
  std::vector<int32_t> Parent;

  void Reset(std::size_t count)
  {
    this->Parent.resize(count);
    for (std::size_t k = 0; k < count; ++k)
    {
      this->Parent[k] = static_cast<int32_t>(k);
    }
  }
  int32_t Find(int32_t x)
  {
    while (this->Parent[static_cast<size_t>(x)] != x)
    {
      const int32_t grand = this->Parent[static_cast<size_t>(this->Parent[static_cast<size_t>(x)])];
      this->Parent[static_cast<size_t>(x)] = grand;
      x = grand;
    }
    return x;
  }
  void Join(int32_t a, int32_t b)
  {
    a = this->Find(a);
    b = this->Find(b);
    if (a != b)
    {
      this->Parent[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
    }
  }
};

/// Per-thread scratch of the analysis: per-source sums (one slot per patch, left zero) and
/// the sample regions.
struct Scratch
{
  std::vector<double> VisibleMeasure;
  std::vector<uint32_t> VisibleSamples;
  std::vector<uint32_t> LargeRegions;
  std::vector<uint32_t> RegionSamples;
  SampleRegions Regions;
};
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

/// What the analysis of one hemisphere H_i found (sources as indices into the current list).
struct CoverRefinement::Analysis
{
  /// Sources visible in H_i (image of at least one sample), ascending.
  std::vector<uint32_t> Visible;
  /// Sources to split because substantially hidden, and (not already there) because their
  /// image is disconnected; both within the limits.
  std::vector<uint32_t> Hidden;
  std::vector<uint32_t> Disconnected;
  /// Sources that asked for a split the limits refused.
  std::size_t Limited = 0;
  /// Thread-local working arrays, shared by the receivers of one ParallelFor chunk.
  std::shared_ptr<Scratch> Work;
};

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
  // Which surfaces are planes (the only horizon sources, see SeesHorizonAcross): every control
  // point within PlanarTolerance of the net's size from the plane through their centroid
  // normal to the control net's normal (the Cornell red wall's 3.2 mm twist over 780 mm counts
  // as planar).
  for (const Surface& surface : scene.Surfaces)
  {
    const BezierPatch& patch = surface.Patch;
    const glm::dvec3 normal = patch.ControlNetNormal();
    bool planar = glm::length(normal) > 0.0;
    if (planar)
    {
      glm::dvec3 centroid(0.0);
      for (const glm::dvec3& point : patch.ControlPoints())
      {
        centroid += point;
      }
      centroid /= static_cast<double>(patch.ControlPoints().size());
      const glm::dvec3 unit = glm::normalize(normal);
      for (const glm::dvec3& point : patch.ControlPoints())
      {
        planar =
          planar && std::fabs(glm::dot(point - centroid, unit)) <= PlanarTolerance * patch.Size();
      }
    }
    this->PlanarSurfaces.push_back(planar ? 1 : 0);
  }
  this->Stats.InputPatches = this->Nodes.size();
  this->Stats.OutputPatches = this->Nodes.size();
}

void CoverRefinement::Analyse(std::size_t receiver,
  const std::vector<Patch>& current,
  const RBufferFiller& filler,
  RBuffer& buffer,
  Analysis& result) const
{
  filler.Fill(receiver, buffer, nullptr);
  const HemisphereGrid& grid = buffer.Grid();
  Scratch& work = *result.Work;
  const size_t count = current.size();
  if (work.VisibleMeasure.size() != count)
  {
    work.VisibleMeasure.assign(count, 0.0);
    work.VisibleSamples.assign(count, 0);
    work.LargeRegions.assign(count, 0);
  }
  const int rows = grid.SampleRows();
  const int columns = grid.SampleColumns();
  const int perCell = grid.SamplesPerCell();
  const int samplesTheta = grid.SamplesTheta();

  // The image of every source at sample resolution: measure, sample count, regions.
  work.Regions.Reset(grid.SampleCount());
  work.RegionSamples.assign(grid.SampleCount(), 0);
  std::vector<std::pair<int32_t, int32_t>> poleSamples; // (source, first sample of row 0)
  for (int r = 0; r < rows; ++r)
  {
    const double weight = grid.CellMeasure(r / samplesTheta) / perCell;
    for (int c = 0; c < columns; ++c)
    {
      const size_t s = grid.SampleIndex(r, c);
      const int32_t source = buffer.SampleSource(s);
      if (source < 0)
      {
        continue;
      }
      if (work.VisibleSamples[static_cast<size_t>(source)] == 0)
      {
        result.Visible.push_back(static_cast<uint32_t>(source));
      }
      ++work.VisibleSamples[static_cast<size_t>(source)];
      work.VisibleMeasure[static_cast<size_t>(source)] += weight;
      // 8-neighbours already visited: left (wrapping in phi) and the three above.
      const int32_t self = static_cast<int32_t>(s);
      auto join = [&](int rr, int cc)
      {
        const size_t t = grid.SampleIndex(rr, (cc + columns) % columns);
        if (buffer.SampleSource(t) == source)
        {
          work.Regions.Join(self, static_cast<int32_t>(t));
        }
      };
      join(r, c - 1);
      if (c == columns - 1)
      {
        join(r, 0);
      }
      if (r > 0)
      {
        join(r - 1, c - 1);
        join(r - 1, c);
        join(r - 1, c + 1);
      }
      else
      {
        // The first sample row is a small circle around the normal: all of it is adjacent.
        auto found = std::find_if(poleSamples.begin(),
          poleSamples.end(),
          [source](const std::pair<int32_t, int32_t>& p) { return p.first == source; });
        if (found == poleSamples.end())
        {
          poleSamples.emplace_back(source, self);
        }
        else
        {
          work.Regions.Join(self, found->second);
        }
      }
    }
  }
  std::sort(result.Visible.begin(), result.Visible.end());
  for (size_t s = 0; s < grid.SampleCount(); ++s)
  {
    if (buffer.SampleSource(s) >= 0)
    {
      ++work.RegionSamples[static_cast<size_t>(work.Regions.Find(static_cast<int32_t>(s)))];
    }
  }
  for (size_t s = 0; s < grid.SampleCount(); ++s)
  {
    const int32_t source = buffer.SampleSource(s);
    if (source >= 0 && work.Regions.Parent[s] == static_cast<int32_t>(s) &&
      work.RegionSamples[s] >= static_cast<uint32_t>(perCell))
    {
      ++work.LargeRegions[static_cast<size_t>(source)];
    }
  }

  // Step 3: compare each visible source's image with its unoccluded projection.
  const std::vector<std::pair<int32_t, float>>& unoccluded =
    buffer.UnoccludedProjectedSolidAngles();
  const Patch& receiverPatch = current[receiver];
  const double cellAngle = std::min(HalfPi / grid.ThetaBins(), TwoPi / grid.PhiBins());
  for (const uint32_t j : result.Visible)
  {
    const double visible = work.VisibleMeasure[j];
    const uint32_t samples = work.VisibleSamples[j];
    const uint32_t regions = work.LargeRegions[j];
    work.VisibleMeasure[j] = 0.0;
    work.VisibleSamples[j] = 0;
    work.LargeRegions[j] = 0;
    if (j == receiver || samples < this->Settings.MinimumVisibleCells * perCell)
    {
      continue; // a concave patch seeing itself; or (note 4) Q_j fully hidden from P_i
    }
    const auto found = std::lower_bound(unoccluded.begin(),
      unoccluded.end(),
      static_cast<int32_t>(j),
      [](const std::pair<int32_t, float>& p, int32_t source) { return p.first < source; });
    const double projection =
      found != unoccluded.end() && found->first == static_cast<int32_t>(j) ? found->second : 0.0;
    // The cell measure where Q_j is seen: its image's mean measure per sample, times a cell's.
    const double cellMeasure = visible / samples * perCell;
    const double hidden = projection - visible;
    const bool hiddenSubstantially = hidden > this->Settings.HiddenFraction * projection &&
      hidden > this->Settings.MinimumHiddenCells * cellMeasure;
    const bool disconnected = this->Settings.SplitDisconnected && regions >= 2;
    if (!hiddenSubstantially && !disconnected)
    {
      continue;
    }
    // The limits of §4.3 note 2, as in the subdivision.
    const Patch& source = current[j];
    const IntervalVec3& bounds = source.Geometry.Bounds();
    const Box box{ bounds.Lower(), bounds.Upper() };
    const double distance = box.DistanceTo(receiverPatch.Point);
    const bool maySplit = source.Level < this->Settings.MaxLevel &&
      (distance <= 0.0 || box.Diagonal() > cellAngle * distance);
    if (!maySplit)
    {
      ++result.Limited;
      continue;
    }
    (hiddenSubstantially ? result.Hidden : result.Disconnected).push_back(j);
  }
}

bool CoverRefinement::Run(const ProgressCallback& progress, const ParallelFor& parallelFor)
{
  const ParallelFor& run = parallelFor ? parallelFor : ParallelFor(SequentialFor);
  // The receiver side costs a few rays and box tests per patch; the hemisphere analysis most
  // of the time.
  const double receiverShare = this->Settings.AnalyseHemispheres ? 0.05 : 1.0;
  const double probeShare = this->Settings.SplitHorizons ? 0.8 * receiverShare : receiverShare;
  if (this->Settings.SplitEnclosureBoundaries &&
    !this->SplitAcrossEnclosures(progress, run, probeShare))
  {
    return false;
  }
  if (this->Settings.SplitHorizons &&
    !this->SplitAcrossHorizons(
      progress, run, this->Settings.SplitEnclosureBoundaries ? probeShare : 0.0, receiverShare))
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
  this->ProbeExtents = std::move(extents);
  this->ProbeGroups = std::move(groups);
}

UVRect CoverRefinement::ProbeExtent(int surface) const
{
  return this->ProbeExtents.empty() ? UVRect::Unit()
                                    : this->ProbeExtents[static_cast<size_t>(surface)];
}

int CoverRefinement::GroupOf(int surface) const
{
  return this->ProbeGroups.empty() ? surface : this->ProbeGroups[static_cast<size_t>(surface)];
}

bool CoverRefinement::SplitAcrossEnclosures(const ProgressCallback& progress,
  const ParallelFor& run,
  double progressShare)
{
  // The environment the probes see: the scene's whole surfaces (splitting changes no geometry).
  std::vector<RayCastPatch> environment;
  environment.reserve(this->Environment.Surfaces.size());
  Box bounds;
  for (size_t s = 0; s < this->Environment.Surfaces.size(); ++s)
  {
    environment.push_back(
      RayCastPatch{ &this->Environment.Surfaces[s].Patch, static_cast<int32_t>(s) });
    const IntervalVec3& box = this->Environment.Surfaces[s].Patch.Bounds();
    if (s == 0)
    {
      bounds = Box{ box.Lower(), box.Upper() };
    }
    else
    {
      bounds.Extend(Box{ box.Lower(), box.Upper() });
    }
  }
  if (environment.empty())
  {
    return true;
  }
  const RayCaster rays(std::move(environment), RayCastOptions(this->Settings.Cover.FillOptions));
  // Rays start on their own surface: skip the first 1e-7 of the scene's size (single-precision
  // rays; far below any gap that matters, such as the light's 0.5 mm in a 550 mm box), and hits
  // of the probe's own surface within its tessellation error.
  const double tNear = 1e-7 * bounds.Diagonal();
  const double ownTolerance = 2.0 * this->Settings.Cover.FillOptions.TessellationTolerance;
  const int m = this->Settings.ProbesPerSide;
  // The side of the first surface met along one ray: 1 back, 0 front or none, -1 undecided.
  auto backSideFirst = [&](const Patch& patch,
                         const glm::dvec3& origin,
                         const glm::dvec3& direction,
                         std::size_t& probes) -> int
  {
    double near = tNear;
    for (int attempt = 0; attempt < 8; ++attempt)
    {
      ++probes;
      std::size_t hit;
      double distance;
      bool front;
      if (!rays.FirstHit(origin, direction, near, hit, distance, front))
      {
        return 0;
      }
      if (this->GroupOf(static_cast<int>(hit)) == this->GroupOf(patch.SurfaceIndex) &&
        distance < ownTolerance * this->Environment.Surfaces[hit].Patch.Size())
      {
        near = distance * (1.0 + 1e-6) + tNear;
        continue;
      }
      return !front && !this->Environment.Surfaces[hit].TwoSided ? 1 : 0;
    }
    return -1;
  };
  // A point is enclosed when the first surface met is a back side along its normal and along
  // the four directions 45 degrees from it towards +-T and +-B: a point inside a closed solid
  // (or in a thin gap under a surface turned away) meets back sides all around, a point that
  // merely sees some back side through an opening (a teapot's lid gap) does not.
  auto enclosed = [&](const Patch& patch, double u, double v, std::size_t& probes) -> int
  {
    // On the whole surface at the patch's (u, v) mapped into its domain (the probes may lie
    // around the patch, within the surface).
    const BezierPatch& surface =
      this->Environment.Surfaces[static_cast<size_t>(patch.SurfaceIndex)].Patch;
    const UVRect extent = this->ProbeExtent(patch.SurfaceIndex);
    u = std::min(
      extent.U1, std::max(extent.U0, patch.Domain.U0 + u * (patch.Domain.U1 - patch.Domain.U0)));
    v = std::min(
      extent.V1, std::max(extent.V0, patch.Domain.V0 + v * (patch.Domain.V1 - patch.Domain.V0)));
    const glm::dvec3 normal = surface.UnnormalizedNormal(u, v);
    const double length = glm::length(normal);
    if (!(length > 0.0))
    {
      return -1; // no normal (a collapsed edge): no verdict
    }
    const glm::dvec3 origin = surface.Evaluate(u, v);
    const HemisphereFrame frame = HemisphereFrame::FromPartials(
      origin, normal / length, surface.PartialU(u, v), surface.PartialV(u, v));
    const glm::dvec3 directions[5] = { frame.Normal,
      glm::normalize(frame.Normal + frame.Tangent),
      glm::normalize(frame.Normal - frame.Tangent),
      glm::normalize(frame.Normal + frame.Bitangent),
      glm::normalize(frame.Normal - frame.Bitangent) };
    for (const glm::dvec3& direction : directions)
    {
      const int verdict = backSideFirst(patch, origin, direction, probes);
      if (verdict != 1)
      {
        return verdict;
      }
    }
    return 1;
  };
  // Whether a patch straddles an enclosure boundary: some probes enclosed, some not.
  // The probes cover the patch and a margin of EnclosureMargin patch widths around it (within
  // the surface): a patch is split when an enclosure boundary crosses it or passes that near,
  // which grades the pieces towards the boundary (see the file comment).
  const double margin = this->Settings.EnclosureMargin;
  const int n = m + 2 * static_cast<int>(std::ceil(margin * m));
  auto straddles = [&](const Patch& patch, std::size_t& probes)
  {
    bool in = false;
    bool out = false;
    for (int b = 0; b < n; ++b)
    {
      for (int a = 0; a < n; ++a)
      {
        const int verdict = enclosed(patch,
          -margin + (1.0 + 2.0 * margin) * (a + 0.5) / n,
          -margin + (1.0 + 2.0 * margin) * (b + 0.5) / n,
          probes);
        in = in || verdict == 1;
        out = out || verdict == 0;
        if (in && out)
        {
          return true;
        }
      }
    }
    return false;
  };

  // Every leaf independently (its pieces split recursively), merged in leaf order.
  const size_t count = this->Leaves.size();
  std::vector<std::vector<Patch>> pieces(count);
  std::vector<std::size_t> splits(count, 0);
  std::vector<std::size_t> probes(count, 0);
  const bool finished = ForEachInBatches(
    count,
    run,
    [&](size_t k)
    {
      const Patch& leaf = this->Nodes[static_cast<size_t>(this->Leaves[k])];
      if (leaf.Level >= this->Settings.MaxLevel || !straddles(leaf, probes[k]))
      {
        return;
      }
      const BezierPatch& surface =
        this->Environment.Surfaces[static_cast<size_t>(leaf.SurfaceIndex)].Patch;
      std::vector<Patch> stack{ leaf };
      while (!stack.empty())
      {
        const Patch patch = std::move(stack.back());
        stack.pop_back();
        if (patch.Level >= this->Settings.MaxLevel ||
          (splits[k] > 0 && !straddles(patch, probes[k])))
        {
          pieces[k].push_back(patch);
          continue;
        }
        ++splits[k];
        std::array<Patch, 3> three = SplitInThree(patch, surface, SplitReason::RBuffer);
        for (int t = 2; t >= 0; --t)
        {
          stack.push_back(std::move(three[static_cast<size_t>(t)]));
        }
      }
    },
    [&](size_t done) { return !progress || progress(progressShare * double(done) / count); });
  if (!finished)
  {
    return false;
  }
  std::vector<int> nextLeaves;
  for (size_t k = 0; k < count; ++k)
  {
    this->Stats.Probes += probes[k];
    if (pieces[k].empty())
    {
      nextLeaves.push_back(this->Leaves[k]);
      continue;
    }
    this->Stats.Splits += splits[k];
    this->Stats.EnclosureSplits += splits[k];
    for (Patch& piece : pieces[k])
    {
      nextLeaves.push_back(static_cast<int>(this->Nodes.size()));
      this->Nodes.push_back(std::move(piece));
      this->VisibleNodes.emplace_back();
      this->Analysed.push_back(false);
    }
  }
  this->Leaves = std::move(nextLeaves);
  this->Stats.OutputPatches = this->Leaves.size();
  return true;
}

bool CoverRefinement::SeesHorizonAcross(std::size_t k) const
{
  const Patch& receiver = this->Nodes[static_cast<size_t>(this->Leaves[k])];
  const double size = receiver.Geometry.Size();
  const double reach = this->Settings.HorizonReach * size;
  // A plane "cuts" the surface when points of it lie on both sides by more than this: a
  // surface meeting it along an edge (a wall on the floor) does not cut it.
  const double tolerance = HorizonTolerance * size;
  // The surface over the patch and EnclosureMargin patch widths around it (within the surface,
  // as the enclosure probes): a plane cutting it there puts a kink into the patch's
  // neighbourhood, and the pieces shrink towards it as towards an enclosure boundary.
  const BezierPatch& surface =
    this->Environment.Surfaces[static_cast<size_t>(receiver.SurfaceIndex)].Patch;
  const UVRect extent = this->ProbeExtent(receiver.SurfaceIndex);
  const double margin = this->Settings.EnclosureMargin;
  const double steps[5] = { -margin, 0.0, 0.5, 1.0, 1.0 + margin };
  std::array<glm::dvec3, 25> points;
  for (int b = 0; b < 5; ++b)
  {
    for (int a = 0; a < 5; ++a)
    {
      const UVRect& d = receiver.Domain;
      const double u = std::min(extent.U1, std::max(extent.U0, d.U0 + steps[a] * (d.U1 - d.U0)));
      const double v = std::min(extent.V1, std::max(extent.V0, d.V0 + steps[b] * (d.V1 - d.V0)));
      points[static_cast<size_t>(5 * b + a)] = surface.Evaluate(u, v);
    }
  }
  const int group = this->GroupOf(receiver.SurfaceIndex);
  for (const int leaf : this->Leaves)
  {
    const Patch& source = this->Nodes[static_cast<size_t>(leaf)];
    if (this->GroupOf(source.SurfaceIndex) == group ||
      !this->PlanarSurfaces[static_cast<size_t>(source.SurfaceIndex)])
    {
      continue;
    }
    const IntervalVec3& bounds = source.Geometry.Bounds();
    if (Box{ bounds.Lower(), bounds.Upper() }.DistanceTo(receiver.Point) >= reach)
    {
      continue;
    }
    // In front of the receiver (seen from its characteristic point)...
    if (glm::dot(source.Point - receiver.Point, receiver.Normal) <= tolerance)
    {
      continue;
    }
    // ... and its tangent plane cuts the receiver's neighbourhood: part of it sees the
    // source's front, part of it does not.
    double below = 0.0;
    double above = 0.0;
    for (const glm::dvec3& point : points)
    {
      const double height = glm::dot(point - source.Point, source.Normal);
      below = std::min(below, height);
      above = std::max(above, height);
    }
    if (below < -tolerance && above > tolerance)
    {
      return true;
    }
  }
  return false;
}

bool CoverRefinement::SplitAcrossHorizons(const ProgressCallback& progress,
  const ParallelFor& run,
  double progressStart,
  double progressEnd)
{
  // Rounds: every leaf is tested against the current list; the leaves that see a horizon
  // across them are split, and their pieces tested again in the next round (each round deepens
  // by one level, so there are at most MaxLevel + 1 rounds).
  for (int round = 0; round <= this->Settings.MaxLevel; ++round)
  {
    const size_t count = this->Leaves.size();
    std::vector<char> split(count, 0);
    const bool finished = ForEachInBatches(
      count,
      run,
      [&](size_t k)
      {
        const Patch& leaf = this->Nodes[static_cast<size_t>(this->Leaves[k])];
        split[k] = leaf.Level < this->Settings.MaxLevel && this->SeesHorizonAcross(k);
      },
      [&](size_t done)
      {
        const double share = (round + double(done) / count) / (this->Settings.MaxLevel + 1);
        return !progress || progress(progressStart + (progressEnd - progressStart) * share);
      });
    if (!finished)
    {
      return false;
    }
    std::vector<int> nextLeaves;
    size_t splits = 0;
    for (size_t k = 0; k < count; ++k)
    {
      if (!split[k])
      {
        nextLeaves.push_back(this->Leaves[k]);
        continue;
      }
      ++splits;
      const Patch& leaf = this->Nodes[static_cast<size_t>(this->Leaves[k])];
      const BezierPatch& surface =
        this->Environment.Surfaces[static_cast<size_t>(leaf.SurfaceIndex)].Patch;
      std::array<Patch, 3> three = SplitInThree(leaf, surface, SplitReason::RBuffer);
      for (Patch& piece : three)
      {
        nextLeaves.push_back(static_cast<int>(this->Nodes.size()));
        this->Nodes.push_back(std::move(piece));
        this->VisibleNodes.emplace_back();
        this->Analysed.push_back(false);
      }
    }
    this->Leaves = std::move(nextLeaves);
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

bool CoverRefinement::AnalyseHemispheres(const ProgressCallback& progress,
  const ParallelFor& run,
  double progressStart)
{
  const SphericalCoverOptions& options = this->Settings.Cover;
  const HemisphereGrid grid(
    options.ThetaBins, options.PhiBins, options.SamplesTheta, options.SamplesPhi);
  // Each round deepens by at most one level.
  const double expectedRounds = this->Settings.MaxLevel + 1.0;
  while (true)
  {
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
      RBufferFiller::Create(RBufferFill::Projection, current, grid, options.FillOptions);

    // Step 3 for every hemisphere that may have changed; requests merged in receiver order.
    std::vector<char> hidden(count, 0);
    std::vector<char> disconnected(count, 0);
    std::vector<Analysis> results;
    for (size_t first = 0; first < receivers.size(); first += BatchSize)
    {
      const size_t batch = std::min(BatchSize, receivers.size() - first);
      results.assign(batch, Analysis());
      run(batch,
        [&](size_t begin, size_t end)
        {
          RBuffer buffer(grid);
          const std::shared_ptr<Scratch> work = std::make_shared<Scratch>();
          for (size_t k = begin; k < end; ++k)
          {
            results[k].Work = work;
            this->Analyse(receivers[first + k], current, *filler, buffer, results[k]);
            results[k].Work.reset();
          }
        });
      for (size_t k = 0; k < batch; ++k)
      {
        const Analysis& analysis = results[k];
        const size_t node = static_cast<size_t>(this->Leaves[receivers[first + k]]);
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
        this->Stats.LimitedRequests += analysis.Limited;
      }
      this->Stats.RowsAnalysed += batch;
      if (progress &&
        !progress(progressStart +
          (1.0 - progressStart) *
            std::min(1.0,
              (this->Stats.Rounds + double(first + batch) / receivers.size()) / expectedRounds)))
      {
        return false;
      }
    }
    ++this->Stats.Rounds;

    // Step 5: every split patch is replaced by its three pieces, in its place.
    std::vector<int> nextLeaves;
    std::vector<char> splitNode(this->Nodes.size(), 0);
    for (size_t k = 0; k < count; ++k)
    {
      const int node = this->Leaves[k];
      if (!hidden[k] && !disconnected[k])
      {
        nextLeaves.push_back(node);
        continue;
      }
      splitNode[static_cast<size_t>(node)] = 1;
      ++this->Stats.Splits;
      if (!hidden[k])
      {
        ++this->Stats.DisconnectedSplits;
      }
      const Patch& parent = this->Nodes[static_cast<size_t>(node)];
      const BezierPatch& surface =
        this->Environment.Surfaces[static_cast<size_t>(parent.SurfaceIndex)].Patch;
      for (Patch& piece : SplitInThree(parent, surface, SplitReason::RBuffer))
      {
        nextLeaves.push_back(static_cast<int>(this->Nodes.size()));
        this->Nodes.push_back(std::move(piece));
        this->VisibleNodes.emplace_back();
        this->Analysed.push_back(false);
      }
      this->VisibleNodes[static_cast<size_t>(node)].clear();
    }
    if (nextLeaves.size() == count)
    {
      break;
    }
    // A hemisphere in which a split patch was visible must be analysed again (its pieces may
    // be hidden differently); one in which it was hidden keeps its verdicts.
    for (int node : nextLeaves)
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
    this->Leaves = std::move(nextLeaves);
    this->Stats.OutputPatches = this->Leaves.size();
  }
  return true;
}

std::vector<Patch> CoverRefinement::Patches() const
{
  return CollectPatches(this->Nodes, this->Leaves);
}

} // namespace sphcover
