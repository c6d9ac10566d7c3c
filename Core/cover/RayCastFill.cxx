// SPDX-License-Identifier: BSD-3-Clause
#include "cover/RayCastFill.h"

#include "geometry/RayPatchIntersection.h"
#include "subdivision/Patch.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

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
};

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
};

bool AcceptForReceiver(const void* context, std::size_t patch, float distance, bool front)
{
  const ReceiverFilter& receiver = *static_cast<const ReceiverFilter*>(context);
  if (!front && !receiver.BackFacesOcclude)
  {
    return false; // a back side the rays pass through
  }
  // The receiver's own patch: P_i itself, or all of it when its self-visibility is not counted.
  return !(
    patch == receiver.Receiver && (!receiver.CountSelf || distance < receiver.SelfExclusion));
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
  const RBufferFillOptions& options)
  : Patches(patches)
  , Grid(grid)
  , Options(options)
  , Rays(RayCastPatches(patches), RayCastOptions(options))
{
  for (const Patch& patch : patches)
  {
    this->SurfaceOfPatch.push_back(patch.SurfaceIndex);
  }
}

RayCastFiller::~RayCastFiller() = default;

std::size_t RayCastFiller::EnvironmentBytes() const
{
  // Vertices and indices (12 bytes each per vertex / triangle, about one vertex per two
  // triangles) plus Embree's high-quality BVH, about 40 bytes per triangle (its reference
  // figures: node and triangle storage of the 4-wide BVH with spatial splits).
  return this->Rays.TriangleCount() * (6 + 12 + 40);
}

void RayCastFiller::CastSamples(std::size_t receiver,
  const HemisphereFrame& frame,
  RBuffer& buffer) const
{
  const HemisphereGrid& grid = this->Grid;
  const Patch& patch = this->Patches[receiver];
  const ReceiverFilter receiverFilter{ receiver,
    static_cast<float>(this->Options.SelfExclusionFraction * patch.Geometry.Size()),
    this->Options.CountSelfVisibility,
    this->Options.BackFacesOcclude };
  const RayFilter filter{ AcceptForReceiver, &receiverFilter };

  HitScratch& scratch = ThreadScratch();
  scratch.U.resize(grid.SampleCount());
  scratch.V.resize(grid.SampleCount());
  scratch.T.resize(grid.SampleCount());

  for (int row = 0; row < grid.SampleRows(); ++row)
  {
    for (int column = 0; column < grid.SampleColumns(); ++column)
    {
      const glm::dvec3 direction = frame.ToWorld(grid.SampleDirection(row, column));
      TriangleHit hit;
      // Rays from one point in neighbouring directions: coherent.
      if (!this->Rays.Intersect(frame.Origin, direction, 0.0f, filter, true, hit))
      {
        continue;
      }
      if (!hit.FrontSide)
      {
        continue; // a back side: it hides what is behind it, the sample stays empty
      }
      const BezierPatch& geometry = this->Patches[hit.Patch].Geometry;
      const std::size_t sample = grid.SampleIndex(row, column);
      // The exact normal at the hit's parameters decides grazing (a triangle's normal can be
      // off by several degrees on a curved patch).
      glm::dvec3 q;
      glm::dvec3 qu;
      glm::dvec3 qv;
      EvaluatePointAndPartials(geometry, hit.U, hit.V, q, qu, qv);
      glm::dvec3 normal = glm::cross(qu, qv);
      if (!(glm::length(normal) > 0.0))
      {
        normal = hit.TriangleNormal;
      }
      const double cosine =
        std::fabs(glm::dot(normal, direction)) / std::max(glm::length(normal), 1e-300);
      scratch.U[sample] = hit.U;
      scratch.V[sample] = hit.V;
      scratch.T[sample] = hit.Distance;
      // With refinement the exact R is computed for the cells' representative samples only
      // (in Classify); the other samples' R is never used.
      buffer.SetSample(sample,
        static_cast<int32_t>(hit.Patch),
        this->Options.RefineHits ? std::numeric_limits<float>::quiet_NaN() : hit.Distance,
        cosine < this->Options.GrazingCosine);
    }
  }
}

void RayCastFiller::Fill(std::size_t receiver, RBuffer& buffer, CullingStatistics*) const
{
  const HemisphereGrid& grid = this->Grid;
  const HemisphereFrame frame = HemisphereFrame::OfPatch(this->Patches[receiver]);
  buffer.Reset(receiver);
  this->CastSamples(receiver, frame, buffer);
  const HitScratch& scratch = ThreadScratch();
  buffer.Classify(
    [&](std::size_t sample, int32_t source) -> float
    {
      const int row = static_cast<int>(sample / static_cast<size_t>(grid.SampleColumns()));
      const int column = static_cast<int>(sample % static_cast<size_t>(grid.SampleColumns()));
      const glm::dvec3 direction = frame.ToWorld(grid.SampleDirection(row, column));
      double u = scratch.U[sample];
      double v = scratch.V[sample];
      double t = scratch.T[sample];
      // The tessellation's distance stays where Newton's method leaves the patch.
      this->Rays.Refine(static_cast<size_t>(source), frame.Origin, direction, u, v, t);
      return static_cast<float>(t);
    },
    &this->SurfaceOfPatch,
    this->Options.DiffuseRounding);
}

} // namespace sphcover
