// SPDX-License-Identifier: BSD-3-Clause
#include "cover/EnclosureSplit.h"

#include "cover/HemisphereGrid.h"
#include "cover/RayCastFill.h"
#include "geometry/BoundingBoxTree.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace sphcover
{

EnclosureSplitter::EnclosureSplitter(const Scene& scene,
  const ProbeExtents& extents,
  const RefinementSettings& settings)
  : Environment(scene)
  , Extents(extents)
  , Settings(settings)
{
  // The environment the probes see: the scene's whole surfaces (splitting changes no geometry).
  std::vector<RayCastPatch> environment;
  environment.reserve(scene.Surfaces.size());
  Box bounds;
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    environment.push_back(RayCastPatch{ &scene.Surfaces[s].Patch, static_cast<int32_t>(s) });
    const IntervalVec3& box = scene.Surfaces[s].Patch.Bounds();
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
    return;
  }
  this->Rays =
    std::make_unique<RayCaster>(std::move(environment), RayCastOptions(settings.Cover.FillOptions));
  // Rays start on their own surface: skip the first 1e-7 of the scene's size (single-precision
  // rays; far below any gap that matters, such as the light's 0.5 mm in a 550 mm box), and hits
  // of the probe's own surface within its tessellation error.
  this->TNear = 1e-7 * bounds.Diagonal();
  this->OwnTolerance = 2.0 * settings.Cover.FillOptions.TessellationTolerance;
}

int EnclosureSplitter::BackSideFirst(const Patch& patch,
  const glm::dvec3& origin,
  const glm::dvec3& direction,
  std::size_t& probes) const
{
  double near = this->TNear;
  for (int attempt = 0; attempt < 8; ++attempt)
  {
    ++probes;
    std::size_t hit;
    double distance;
    bool front;
    if (!this->Rays->FirstHit(origin, direction, near, hit, distance, front))
    {
      return 0;
    }
    if (this->Extents.Group(static_cast<int>(hit)) == this->Extents.Group(patch.SurfaceIndex) &&
      distance < this->OwnTolerance * this->Environment.Surfaces[hit].Patch.Size())
    {
      near = distance * (1.0 + 1e-6) + this->TNear;
      continue;
    }
    return !front && !this->Environment.Surfaces[hit].TwoSided ? 1 : 0;
  }
  return -1;
}

int EnclosureSplitter::Enclosed(const Patch& patch, double u, double v, std::size_t& probes) const
{
  // On the whole surface at the patch's (u, v) mapped into its domain (the probes may lie
  // around the patch, within the surface).
  const BezierPatch& surface =
    this->Environment.Surfaces[static_cast<size_t>(patch.SurfaceIndex)].Patch;
  const UVRect extent = this->Extents.Extent(patch.SurfaceIndex);
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
  // Along the normal and the four directions 45 degrees from it towards +-T and +-B: a point
  // inside a closed solid (or in a thin gap under a surface turned away) meets back sides all
  // around, a point that merely sees some back side through an opening (a teapot's lid gap)
  // does not.
  const glm::dvec3 directions[5] = { frame.Normal,
    glm::normalize(frame.Normal + frame.Tangent),
    glm::normalize(frame.Normal - frame.Tangent),
    glm::normalize(frame.Normal + frame.Bitangent),
    glm::normalize(frame.Normal - frame.Bitangent) };
  for (const glm::dvec3& direction : directions)
  {
    const int verdict = this->BackSideFirst(patch, origin, direction, probes);
    if (verdict != 1)
    {
      return verdict;
    }
  }
  return 1;
}

bool EnclosureSplitter::Straddles(const Patch& patch, std::size_t& probes) const
{
  // The probes cover the patch and a margin of EnclosureMargin patch widths around it (within
  // the surface): a patch is split when an enclosure boundary crosses it or passes that near.
  const int m = this->Settings.ProbesPerSide;
  const double margin = this->Settings.EnclosureMargin;
  const int n = m + 2 * static_cast<int>(std::ceil(margin * m));
  bool in = false;
  bool out = false;
  for (int b = 0; b < n; ++b)
  {
    for (int a = 0; a < n; ++a)
    {
      const int verdict = this->Enclosed(patch,
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
}

} // namespace sphcover
