// SPDX-License-Identifier: BSD-3-Clause
#include "cover/RayCastFill.h"

#include "cover/HemisphereInterpolation.h"

#include "geometry/RayPatchIntersection.h"
#include "subdivision/Patch.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sphcover
{

namespace
{
/// Per-sample hit parameters of one receiver, reused by each thread.
struct HitScratch
{
  std::vector<double> U;
  std::vector<double> V;
  std::vector<float> T;
  /// Adaptive sampling: per cell, the group shown by its centre sample (-1: empty).
  std::vector<int32_t> CellKey;
  /// FillFromDonors: per cell the patch the donors agree on (NoSource: nothing), or Unknown,
  /// and its depth; per donor cell whether it lies inside a region of one surface.
  std::vector<int32_t> PredictedSource;
  std::vector<float> PredictedDepth;
  /// FillFromDonors: per pair of donors its interpolated cells' sources and R.
  std::vector<int32_t> DonorSources;
  std::vector<float> DonorDepths;
};

/// A cell FillFromDonors leaves to the rays.
constexpr int32_t Unknown = -2;

HitScratch& ThreadScratch()
{
  thread_local HitScratch scratch;
  return scratch;
}

/// What the hit filter needs to know of the receiver (RBuffer.h's visibility semantics).
struct ReceiverFilter
{
  std::size_t Receiver;
  float SelfExclusion;
  bool CountSelf;
  bool BackFacesOcclude;
  /// Per patch whether the rays pass its back side (RayCastFiller::PassedBack); may be empty.
  const std::vector<char>* PassedBack;
};

/// The filter of the rays from `receiver`'s point under the fill's options.
ReceiverFilter FilterFor(std::size_t receiver,
  const Patch& patch,
  const RBufferFillOptions& options,
  const std::vector<char>& passedBack)
{
  return { receiver,
    static_cast<float>(options.SelfExclusionFraction * patch.Geometry.Size()),
    options.CountSelfVisibility,
    options.BackFacesOcclude,
    &passedBack };
}

bool AcceptForReceiver(const void* context, std::size_t patch, float distance, bool front)
{
  const ReceiverFilter& receiver = *static_cast<const ReceiverFilter*>(context);
  // The back side of a pane or of a two-sided surface is its reversed copy's front, which the
  // ray meets at the same place.
  const bool passedBack = !front && !receiver.PassedBack->empty() && (*receiver.PassedBack)[patch];
  if (!front && (!receiver.BackFacesOcclude || passedBack))
  {
    return false; // a back side the rays pass through
  }
  // The point of such a patch lies on its reversed copy too (the same place, the other side): a
  // hit on such a patch that near is that copy, not something the point sees.
  if (distance < receiver.SelfExclusion && !receiver.PassedBack->empty() &&
    (*receiver.PassedBack)[receiver.Receiver] && (*receiver.PassedBack)[patch])
  {
    return false;
  }
  // The receiver's own patch: P_i itself, or all of it when its self-visibility is not counted.
  return !(
    patch == receiver.Receiver && (!receiver.CountSelf || distance < receiver.SelfExclusion));
}

/// Whether every hit nearer than the self-exclusion distance of the rays from `origin`, the
/// receiver's point, is P_i itself, which AcceptForReceiver rejects: no patch but the
/// receiver's own comes within twice that distance (a pane's reversed copy lies there too).
/// Then RayFilter::RejectsAllNearer is that distance, else 0.
float ReceiverRejectsAllNearer(const ReceiverFilter& receiver,
  const RayCaster& rays,
  const glm::dvec3& origin)
{
  std::vector<std::size_t> near;
  rays.PatchesNear(origin, 2.0 * receiver.SelfExclusion, near);
  return std::all_of(
           near.begin(), near.end(), [&](std::size_t p) { return p == receiver.Receiver; })
    ? receiver.SelfExclusion
    : 0.0f;
}

/// The unit normal of a patch whose control points all lie in one plane (to 1e-12 of its
/// Size()), zero for any other patch.
glm::dvec3 PlaneNormal(const BezierPatch& geometry)
{
  glm::dvec3 q;
  glm::dvec3 qu;
  glm::dvec3 qv;
  EvaluatePointAndPartials(geometry, 0.5, 0.5, q, qu, qv);
  const glm::dvec3 cross = glm::cross(qu, qv);
  const double length = glm::length(cross);
  if (!(length > 0.0))
  {
    return glm::dvec3(0.0);
  }
  const glm::dvec3 normal = cross / length;
  const double tolerance = 1e-12 * geometry.Size();
  for (const glm::dvec3& point : geometry.ControlPoints())
  {
    if (!(std::fabs(glm::dot(point - q, normal)) <= tolerance))
    {
      return glm::dvec3(0.0);
    }
  }
  return normal;
}
}

std::vector<RayCastPatch> RayCastPatches(const std::vector<Patch>& patches)
{
  std::vector<RayCastPatch> result;
  result.reserve(patches.size());
  for (const Patch& patch : patches)
  {
    result.push_back(RayCastPatch{ &patch.Geometry, patch.SurfaceIndex });
  }
  return result;
}

RayCasterOptions RayCastOptions(const RBufferFillOptions& options)
{
  RayCasterOptions result;
  result.TessellationTolerance = options.TessellationTolerance;
  result.RefineHits = options.RefineHits;
  return result;
}

RayCastFiller::RayCastFiller(const std::vector<Patch>& patches,
  const HemisphereGrid& grid,
  const RBufferFillOptions& options,
  std::shared_ptr<const RayCaster> rays)
  : Patches(patches)
  , Grid(grid)
  , Options(options)
  , Rays(rays ? std::move(rays)
              : std::make_shared<const RayCaster>(RayCastPatches(patches), RayCastOptions(options)))
{
  if (this->Rays->PatchCount() != patches.size())
  {
    throw std::invalid_argument("RayCastFiller: the given ray caster has " +
      std::to_string(this->Rays->PatchCount()) + " patches, not the environment's " +
      std::to_string(patches.size()));
  }
  const std::vector<bool>& panes = options.PaneSurfaces;
  const std::vector<bool>& twoSided = options.TwoSidedSurfaces;
  bool anyPane = false;
  bool anyPassed = false;
  for (const Patch& patch : patches)
  {
    this->SurfaceOfPatch.push_back(patch.SurfaceIndex);
    this->PlaneNormals.push_back(PlaneNormal(patch.Geometry));
    this->PlaneOffsets.push_back(
      glm::dot(this->PlaneNormals.back(), patch.Geometry.Evaluate(0.5, 0.5)));
    const std::size_t surface = static_cast<std::size_t>(patch.SurfaceIndex);
    this->PanePatch.push_back(surface < panes.size() && panes[surface] ? 1 : 0);
    anyPane = anyPane || this->PanePatch.back() != 0;
    const bool passed =
      this->PanePatch.back() != 0 || (surface < twoSided.size() && twoSided[surface]);
    this->PassedBack.push_back(passed ? 1 : 0);
    anyPassed = anyPassed || passed;
  }
  if (!anyPane)
  {
    this->PanePatch.clear();
  }
  if (!anyPassed)
  {
    this->PassedBack.clear();
  }
  for (std::size_t i = 0; i < patches.size(); ++i)
  {
    this->RejectsAllNearer.push_back(
      ReceiverRejectsAllNearer(FilterFor(i, patches[i], options, this->PassedBack),
        *this->Rays,
        HemisphereFrame::OfPatch(patches[i]).Origin));
  }
}

std::uint64_t RayCastFiller::RaysCast() const
{
  return this->RayCount.load();
}

RayCastFiller::~RayCastFiller() = default;

std::size_t RayCastFiller::EnvironmentBytes() const
{
  // Vertices and indices, 12 bytes each per vertex / triangle, plus Embree's high-quality BVH,
  // about 40 bytes per triangle (its reference figures: node and triangle storage of the
  // 4-wide BVH with spatial splits).
  return this->Rays->VertexCount() * 12 + this->Rays->TriangleCount() * (12 + 40);
}

bool RayCastFiller::IsGrazing(const TriangleHit& hit, const glm::dvec3& direction) const
{
  const double threshold = this->Options.GrazingCosine;
  // A planar patch's exact normal is its plane's everywhere: the evaluation below would give
  // the same cosine up to rounding, so it is needed only within a rounding margin of the
  // threshold (profile: the evaluation per hit was 6 % of the ray fill on the Cornell box).
  const glm::dvec3& plane = this->PlaneNormals[hit.Patch];
  if (plane != glm::dvec3(0.0))
  {
    constexpr double margin = 1e-6;
    const double cosine = std::fabs(glm::dot(plane, direction));
    if (std::fabs(cosine - threshold) > margin)
    {
      return cosine < threshold;
    }
  }
  // The exact normal at the hit's parameters decides grazing (a triangle's normal can be off
  // by several degrees on a curved patch).
  glm::dvec3 q;
  glm::dvec3 qu;
  glm::dvec3 qv;
  EvaluatePointAndPartials(this->Patches[hit.Patch].Geometry, hit.U, hit.V, q, qu, qv);
  glm::dvec3 normal = glm::cross(qu, qv);
  if (!(glm::length(normal) > 0.0))
  {
    normal = hit.TriangleNormal;
  }
  const double cosine =
    std::fabs(glm::dot(normal, direction)) / std::max(glm::length(normal), 1e-300);
  return cosine < threshold;
}

int32_t RayCastFiller::CastSample(const SampleCast& cast, int row, int column) const
{
  const glm::dvec3 direction = cast.Frame.ToWorld(this->Grid.SampleDirection(row, column));
  TriangleHit hit;
  // Rays from one point in neighbouring directions: coherent.
  if (!this->Rays->Intersect(cast.Frame.Origin, direction, 0.0f, cast.Filter, true, hit))
  {
    return RBuffer::NoSource;
  }
  if (!hit.FrontSide)
  {
    return RBuffer::NoSource; // a back side: it hides what is behind it, the sample stays empty
  }
  this->StoreHit(cast, this->Grid.SampleIndex(row, column), hit, direction);
  return static_cast<int32_t>(hit.Patch);
}

void RayCastFiller::StoreHit(const SampleCast& cast,
  std::size_t sample,
  const TriangleHit& hit,
  const glm::dvec3& direction) const
{
  cast.U[sample] = hit.U;
  cast.V[sample] = hit.V;
  cast.T[sample] = hit.Distance;
  // With refinement the exact R is computed for the cells' representative samples only
  // (in Classify); the other samples' R is never used.
  cast.Buffer.SetSample(sample,
    static_cast<int32_t>(hit.Patch),
    this->Options.RefineHits ? std::numeric_limits<float>::quiet_NaN() : hit.Distance,
    this->IsGrazing(hit, direction));
}

std::size_t RayCastFiller::CastSamples(std::size_t receiver,
  const HemisphereFrame& frame,
  RBuffer& buffer,
  const Prediction* prediction) const
{
  const HemisphereGrid& grid = this->Grid;
  const ReceiverFilter receiverFilter =
    FilterFor(receiver, this->Patches[receiver], this->Options, this->PassedBack);

  HitScratch& scratch = ThreadScratch();
  scratch.U.resize(grid.SampleCount());
  scratch.V.resize(grid.SampleCount());
  scratch.T.resize(grid.SampleCount());
  const SampleCast cast{ frame,
    RayFilter{ AcceptForReceiver, &receiverFilter, this->RejectsAllNearer[receiver] },
    buffer,
    scratch.U.data(),
    scratch.V.data(),
    scratch.T.data() };

  if (!this->Options.AdaptiveSampling)
  {
    for (int row = 0; row < grid.SampleRows(); ++row)
    {
      for (int column = 0; column < grid.SampleColumns(); ++column)
      {
        this->CastSample(cast, row, column);
      }
    }
    return grid.SampleCount();
  }

  // Adaptive sampling (RBufferFillOptions::AdaptiveSampling): first the centre sample of every
  // cell, cells in row-major order; the group of what it shows (the surface of a front side
  // met, or -1 when the sample is empty) is the cell's key.
  const int samplesTheta = grid.SamplesTheta();
  const int samplesPhi = grid.SamplesPhi();
  const int rows = grid.ThetaBins();
  const int columns = grid.PhiBins();
  const int centre = grid.SamplesFromCentre()[0];
  const int centreA = centre / samplesPhi;
  const int centreB = centre % samplesPhi;
  std::vector<int32_t>& key = scratch.CellKey;
  key.resize(static_cast<size_t>(grid.CellCount()));
  PendingRays pending;
  // A predicted cell (FillFromDonors) gets its centre sample from the donors, without a ray.
  auto predicted = [prediction](int cell)
  { return prediction ? prediction->Source[static_cast<size_t>(cell)] : Unknown; };
  std::size_t castCount = 0;
  for (int row = 0; row < rows; ++row)
  {
    for (int column = 0; column < columns; ++column)
    {
      const int32_t source = predicted(grid.CellIndex(row, column));
      if (source == Unknown)
      {
        this->Queue(cast, pending, row * samplesTheta + centreA, column * samplesPhi + centreB);
        ++castCount;
      }
      else if (source != RBuffer::NoSource)
      {
        buffer.SetSample(
          grid.SampleIndex(row * samplesTheta + centreA, column * samplesPhi + centreB),
          source,
          prediction->Depth[static_cast<size_t>(grid.CellIndex(row, column))],
          false);
      }
    }
  }
  this->Flush(cast, pending);
  for (int row = 0; row < rows; ++row)
  {
    for (int column = 0; column < columns; ++column)
    {
      const int32_t source = buffer.SampleSource(
        grid.SampleIndex(row * samplesTheta + centreA, column * samplesPhi + centreB));
      key[static_cast<size_t>(grid.CellIndex(row, column))] =
        source == RBuffer::NoSource ? -1 : this->SurfaceOfPatch[static_cast<size_t>(source)];
    }
  }
  // Then, cell by cell in row-major order, the other samples: copied from the centre where the
  // cell and its 8 neighbours (phi wraps around; rows 0 and last have no row beyond) agree,
  // cast where they do not. A predicted cell is copied from its centre; so is every cell of a
  // prediction that does not sample its boundary cells.
  const bool sampleBoundaries = !prediction || prediction->SampleBoundaryCells;
  for (int row = 0; row < rows; ++row)
  {
    for (int column = 0; column < columns; ++column)
    {
      const int32_t own = key[static_cast<size_t>(grid.CellIndex(row, column))];
      const bool known = predicted(grid.CellIndex(row, column)) != Unknown;
      const bool decided = known || !sampleBoundaries;
      bool uniform = true;
      for (int r = std::max(0, row - 1); !decided && uniform && r <= std::min(rows - 1, row + 1);
           ++r)
      {
        for (int dc = -1; dc <= 1; ++dc)
        {
          const int c = (column + dc + columns) % columns;
          if (key[static_cast<size_t>(grid.CellIndex(r, c))] != own)
          {
            uniform = false;
            break;
          }
        }
      }
      const std::size_t centreSample =
        grid.SampleIndex(row * samplesTheta + centreA, column * samplesPhi + centreB);
      const int32_t centreSource = buffer.SampleSource(centreSample);
      for (int a = 0; a < samplesTheta; ++a)
      {
        for (int b = 0; b < samplesPhi; ++b)
        {
          if (a == centreA && b == centreB)
          {
            continue;
          }
          const int sampleRow = row * samplesTheta + a;
          const int sampleColumn = column * samplesPhi + b;
          if (!uniform)
          {
            this->Queue(cast, pending, sampleRow, sampleColumn);
            ++castCount;
            continue;
          }
          if (centreSource == RBuffer::NoSource)
          {
            continue; // stays empty, as Reset left it
          }
          // The centre's source and grazing flag; R unknown (NaN), to be refined on demand from
          // the centre's hit as a first guess (never needed: a uniform cell's representative is
          // its centre sample; a predicted centre has its R).
          const std::size_t sample = grid.SampleIndex(sampleRow, sampleColumn);
          scratch.U[sample] = scratch.U[centreSample];
          scratch.V[sample] = scratch.V[centreSample];
          scratch.T[sample] = scratch.T[centreSample];
          buffer.SetSample(sample,
            centreSource,
            known ? buffer.SampleDepth(centreSample) : std::numeric_limits<float>::quiet_NaN(),
            buffer.SampleGrazing(centreSample));
        }
      }
    }
  }
  this->Flush(cast, pending);
  return castCount;
}

void RayCastFiller::Queue(const SampleCast& cast, PendingRays& pending, int row, int column) const
{
  if (!this->Options.RayPackets)
  {
    this->CastSample(cast, row, column);
    return;
  }
  pending.Row[pending.Count] = row;
  pending.Column[pending.Count] = column;
  pending.Direction[pending.Count] = cast.Frame.ToWorld(this->Grid.SampleDirection(row, column));
  if (++pending.Count == RayCaster::PacketSize)
  {
    this->Flush(cast, pending);
  }
}

void RayCastFiller::Flush(const SampleCast& cast, PendingRays& pending) const
{
  if (pending.Count == 0)
  {
    return;
  }
  TriangleHit hits[RayCaster::PacketSize];
  bool found[RayCaster::PacketSize];
  this->Rays->IntersectPacket(
    cast.Frame.Origin, pending.Direction, pending.Count, 0.0f, cast.Filter, hits, found);
  for (int k = 0; k < pending.Count; ++k)
  {
    // A back side hides what is behind it: the sample stays empty.
    if (found[k] && hits[k].FrontSide)
    {
      this->StoreHit(cast,
        this->Grid.SampleIndex(pending.Row[k], pending.Column[k]),
        hits[k],
        pending.Direction[k]);
    }
  }
  pending.Count = 0;
}

void RayCastFiller::Fill(std::size_t receiver, RBuffer& buffer, CullingStatistics*) const
{
  const HemisphereFrame frame = HemisphereFrame::OfPatch(this->Patches[receiver]);
  buffer.Reset(receiver);
  const std::size_t rays = this->CastSamples(receiver, frame, buffer, nullptr);
  this->RayCount.fetch_add(rays, std::memory_order_relaxed);
  this->ClassifyCells(frame, buffer);
}

void RayCastFiller::FillFromDonors(std::size_t receiver,
  const std::vector<DonorPair>& pairs,
  double maxDifference,
  bool sampleBoundaryCells,
  RBuffer& buffer) const
{
  const HemisphereGrid& grid = this->Grid;
  const HemisphereFrame frame = HemisphereFrame::OfPatch(this->Patches[receiver]);
  buffer.Reset(receiver);
  HitScratch& scratch = ThreadScratch();
  const size_t cells = static_cast<size_t>(grid.CellCount());
  // The pairs whose hemispheres lie on the receiver's grid (the same frame but for the origin;
  // paper §3.4 interpolates in one (theta, phi) space).
  auto sameFrame = [&frame](const HemisphereFrame& f)
  {
    return glm::length(f.Normal - frame.Normal) < 1e-6 &&
      glm::length(f.Tangent - frame.Tangent) < 1e-6;
  };
  // And whose donors are alike: the measure of the cells where they show different surfaces
  // (or one of them nothing) at most maxDifference of the hemisphere's (paper §3.4: "the
  // neighbours of H_i are likely to be very similar"; where they are not, e.g. one donor under
  // a block and the other beside it, their interpolation means nothing).
  auto groupOf = [this](int32_t source)
  { return source < 0 ? -1 : this->SurfaceOfPatch[static_cast<size_t>(source)]; };
  std::vector<const DonorPair*> usable;
  for (const DonorPair& pair : pairs)
  {
    if (!sameFrame(HemisphereFrame::OfPatch(this->Patches[pair.A.Patch])) ||
      !sameFrame(HemisphereFrame::OfPatch(this->Patches[pair.B.Patch])))
    {
      continue;
    }
    double different = 0.0;
    for (int cell = 0; cell < grid.CellCount(); ++cell)
    {
      if (groupOf(pair.A.CellSources[cell]) != groupOf(pair.B.CellSources[cell]))
      {
        different += grid.CellMeasureOfCell(cell);
      }
    }
    if (different <= maxDifference * grid.TotalMeasure())
    {
      usable.push_back(&pair);
    }
  }
  if (usable.empty())
  {
    this->Fill(receiver, buffer, nullptr);
    return;
  }
  std::vector<int32_t>& interpolated = scratch.DonorSources;
  std::vector<float>& interpolatedDepth = scratch.DonorDepths;
  interpolated.resize(cells * usable.size());
  interpolatedDepth.resize(cells * usable.size());
  for (size_t k = 0; k < usable.size(); ++k)
  {
    const DonorPair& pair = *usable[k];
    InterpolateHemispheres(grid.ThetaBins(),
      grid.PhiBins(),
      pair.A.CellSources,
      pair.A.CellDepths,
      pair.B.CellSources,
      pair.B.CellDepths,
      pair.T,
      interpolated.data() + k * cells,
      interpolatedDepth.data() + k * cells);
  }
  // A cell is known where the pairs agree (or there is one pair); the receiver never sees its
  // own patch through its donors' eyes.
  Prediction prediction{ scratch.PredictedSource, scratch.PredictedDepth, sampleBoundaryCells };
  prediction.Source.assign(cells, Unknown);
  prediction.Depth.assign(cells, 0.0f);
  for (size_t c = 0; c < cells; ++c)
  {
    const int32_t source = interpolated[c];
    double depth = interpolatedDepth[c];
    bool agreed = source != static_cast<int32_t>(receiver);
    for (size_t k = 1; agreed && k < usable.size(); ++k)
    {
      const int32_t other = interpolated[k * cells + c];
      agreed = other == source;
      depth += interpolatedDepth[k * cells + c];
    }
    if (agreed)
    {
      prediction.Source[c] = source;
      prediction.Depth[c] = static_cast<float>(depth / static_cast<double>(usable.size()));
    }
  }
  const std::size_t rays = this->CastSamples(receiver, frame, buffer, &prediction);
  this->RayCount.fetch_add(rays, std::memory_order_relaxed);
  this->ClassifyCells(frame, buffer);
}

void RayCastFiller::ClassifyCells(const HemisphereFrame& frame, RBuffer& buffer) const
{
  const HemisphereGrid& grid = this->Grid;
  const HitScratch& scratch = ThreadScratch();
  buffer.Classify(
    [&](std::size_t sample, int32_t source) -> float
    {
      const int row = static_cast<int>(sample / static_cast<size_t>(grid.SampleColumns()));
      const int column = static_cast<int>(sample % static_cast<size_t>(grid.SampleColumns()));
      const glm::dvec3 direction = frame.ToWorld(grid.SampleDirection(row, column));
      // A planar patch's exact distance is its plane's (the closed form of what Newton's
      // method converges to, at a tenth of its cost: the refinement was a tenth of the rows).
      const glm::dvec3& plane = this->PlaneNormals[static_cast<size_t>(source)];
      const double facing = glm::dot(plane, direction);
      if (plane != glm::dvec3(0.0) && std::fabs(facing) > 1e-12)
      {
        const double t =
          (this->PlaneOffsets[static_cast<size_t>(source)] - glm::dot(plane, frame.Origin)) /
          facing;
        if (t > 0.0)
        {
          return static_cast<float>(t);
        }
      }
      double u = scratch.U[sample];
      double v = scratch.V[sample];
      double t = scratch.T[sample];
      // The tessellation's distance stays where Newton's method leaves the patch.
      this->Rays->Refine(static_cast<size_t>(source), frame.Origin, direction, u, v, t);
      return static_cast<float>(t);
    },
    &this->SurfaceOfPatch,
    this->Options.DiffuseRounding);
}

void RayCastFiller::FillBehindPanes(std::size_t receiver,
  const RBuffer& front,
  int layer,
  RBuffer& behind) const
{
  const HemisphereGrid& grid = this->Grid;
  const HemisphereFrame frame = HemisphereFrame::OfPatch(this->Patches[receiver]);
  const ReceiverFilter receiverFilter =
    FilterFor(receiver, this->Patches[receiver], this->Options, this->PassedBack);
  const RayFilter filter =
    RayFilter{ AcceptForReceiver, &receiverFilter, this->RejectsAllNearer[receiver] };
  behind.Reset(receiver);
  const int samplesTheta = grid.SamplesTheta();
  const int samplesPhi = grid.SamplesPhi();
  const std::vector<int>& order = grid.SamplesFromCentre();
  std::vector<char> through(order.size());
  std::size_t rays = 0;
  for (int row = 0; row < grid.ThetaBins(); ++row)
  {
    for (int column = 0; column < grid.PhiBins(); ++column)
    {
      const int32_t shown = front.CellSource(grid.CellIndex(row, column));
      if (shown == RBuffer::NoSource || !this->IsPane(static_cast<std::size_t>(shown)))
      {
        continue;
      }
      auto sampleOf = [&](int k)
      {
        return grid.SampleIndex(
          row * samplesTheta + k / samplesPhi, column * samplesPhi + k % samplesPhi);
      };
      int first = -1;
      for (int k = 0; k < static_cast<int>(order.size()); ++k)
      {
        through[static_cast<std::size_t>(k)] = 0;
        const int a = row * samplesTheta + k / samplesPhi;
        const int b = column * samplesPhi + k % samplesPhi;
        const glm::dvec3 direction = frame.ToWorld(grid.SampleDirection(a, b));
        // The ray's own path: from each pane met on, cast again just beyond it (Embree's filter
        // sees hits out of order, so "the next hit" is a new ray, not a callback).
        float nearest = 0.0f;
        TriangleHit hit;
        int passed = 0;
        bool found = false;
        for (;;)
        {
          ++rays;
          found = this->Rays->Intersect(frame.Origin, direction, nearest, filter, true, hit) &&
            hit.FrontSide;
          if (!found || passed == layer || !this->IsPane(hit.Patch))
          {
            break;
          }
          ++passed;
          nearest = RayCaster::Beyond(hit.Distance);
        }
        // Through `layer` panes the ray meets a front side or nothing (an open scene's sky):
        // both are what the cell shows behind them.
        if (passed == layer)
        {
          through[static_cast<std::size_t>(k)] = 1;
          if (found)
          {
            behind.SetSample(sampleOf(k),
              static_cast<int32_t>(hit.Patch),
              hit.Distance,
              this->IsGrazing(hit, direction));
          }
        }
      }
      for (const int k : order)
      {
        if (through[static_cast<std::size_t>(k)] && first < 0)
        {
          first = k;
        }
      }
      if (first < 0)
      {
        continue;
      }
      const std::size_t copied = sampleOf(first);
      for (int k = 0; k < static_cast<int>(order.size()); ++k)
      {
        if (!through[static_cast<std::size_t>(k)])
        {
          behind.SetSample(sampleOf(k),
            behind.SampleSource(copied),
            behind.SampleDepth(copied),
            behind.SampleGrazing(copied));
        }
      }
    }
  }
  this->RayCount.fetch_add(rays, std::memory_order_relaxed);
  behind.Classify(nullptr, &this->SurfaceOfPatch, this->Options.DiffuseRounding);
}

double VisibleProjectedSolidAngle(const RayCaster& caster,
  const glm::dvec3& origin,
  const glm::dvec3& normal,
  const RayFilter& filter,
  std::size_t source,
  const Patch& target,
  int minimumSide)
{
  return VisibleProjectedSolidAngleThroughPanes(
    caster, origin, normal, filter, source, target, minimumSide, nullptr)
    .x;
}

glm::dvec3 VisibleProjectedSolidAngleThroughPanes(const RayCaster& caster,
  const glm::dvec3& origin,
  const glm::dvec3& normal,
  const RayFilter& filter,
  std::size_t source,
  const Patch& target,
  int minimumSide,
  const std::vector<glm::vec3>* transmittanceOfPatch,
  uint64_t* paneLimitRays)
{
  const double distance = glm::length(target.Point - origin);
  const double size = target.Geometry.Size();
  const int n = distance > 0.0
    ? static_cast<int>(std::clamp(
        std::ceil(4.0 * size / distance), static_cast<double>(std::max(1, minimumSide)), 32.0))
    : 32;
  const double step = 1.0 / n;
  glm::dvec3 sum(0.0);
  for (int a = 0; a < n; ++a)
  {
    for (int b = 0; b < n; ++b)
    {
      const double u = (a + 0.5) * step;
      const double v = (b + 0.5) * step;
      const glm::dvec3 q = target.Geometry.Evaluate(u, v);
      // |dQ/du x dQ/dv| du dv, oriented along the front normal.
      const glm::dvec3 area = target.Geometry.UnnormalizedNormal(u, v) * (step * step);
      const glm::dvec3 toward = q - origin;
      const double r2 = glm::dot(toward, toward);
      if (!(r2 > 0.0))
      {
        continue;
      }
      const double r = std::sqrt(r2);
      const glm::dvec3 direction = toward / r;
      const double cosReceiver = glm::dot(direction, normal);
      const double projectedArea = -glm::dot(direction, area); // cos(theta_j) dA
      if (!(cosReceiver > 0.0) || !(projectedArea > 0.0))
      {
        continue;
      }
      // The node is seen when the ray's first front side is the source's, or when it is
      // reached through panes' front sides, scaled by their transmittances.
      glm::dvec3 seen(1.0);
      float nearest = 0.0f;
      TriangleHit hit;
      bool found = false;
      for (int pane = 0; pane <= MaxPanesPerRay; ++pane)
      {
        if (!caster.Intersect(origin, direction, nearest, filter, false, hit) || !hit.FrontSide)
        {
          break;
        }
        if (hit.Patch == source)
        {
          found = true;
          break;
        }
        const glm::dvec3 t =
          transmittanceOfPatch ? glm::dvec3((*transmittanceOfPatch)[hit.Patch]) : glm::dvec3(0.0);
        if (t == glm::dvec3(0.0))
        {
          break;
        }
        seen *= t;
        nearest = RayCaster::Beyond(hit.Distance);
        if (pane == MaxPanesPerRay && paneLimitRays)
        {
          ++*paneLimitRays;
        }
      }
      if (found)
      {
        sum += seen * (cosReceiver * projectedArea / r2);
      }
    }
  }
  return sum;
}

double RayCastFiller::VisibleProjectedSolidAngle(std::size_t receiver,
  std::size_t source,
  int minimumSide) const
{
  const Patch& self = this->Patches[receiver];
  const HemisphereFrame frame = HemisphereFrame::OfPatch(self);
  const ReceiverFilter receiverFilter = FilterFor(receiver, self, this->Options, this->PassedBack);
  const RayFilter filter =
    RayFilter{ AcceptForReceiver, &receiverFilter, this->RejectsAllNearer[receiver] };
  return sphcover::VisibleProjectedSolidAngle(
    *this->Rays, frame.Origin, frame.Normal, filter, source, this->Patches[source], minimumSide);
}

} // namespace sphcover
