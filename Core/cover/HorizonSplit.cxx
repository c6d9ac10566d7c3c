// SPDX-License-Identifier: BSD-3-Clause
#include "cover/HorizonSplit.h"

#include "geometry/BoundingBoxTree.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace sphcover
{
namespace
{
/// A source's tangent plane cuts a receiver's surface when points of it around the receiver
/// lie farther than this fraction of the receiver's size to both sides.
constexpr double HorizonTolerance = 0.02;
}

HorizonTest::HorizonTest(const Scene& scene,
  const ProbeExtents& extents,
  const RefinementSettings& settings)
  : Environment(scene)
  , Extents(extents)
  , Settings(settings)
{
  // Which surfaces are planes (the only horizon sources): NearlyPlanar, every control point
  // within 1% of the net's size from one plane.
  for (const Surface& surface : scene.Surfaces)
  {
    const BezierPatch& patch = surface.Patch;
    const bool planar = NearlyPlanar(patch.ControlPoints(), patch.ControlNetNormal(), patch.Size());
    this->PlanarSurfaces.push_back(planar ? 1 : 0);
  }
}

bool HorizonTest::Across(const Patch& receiver,
  const std::vector<Patch>& nodes,
  const std::vector<int>& leaves) const
{
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
  const UVRect extent = this->Extents.Extent(receiver.SurfaceIndex);
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
  const int group = this->Extents.Group(receiver.SurfaceIndex);
  for (const int leaf : leaves)
  {
    const Patch& source = nodes[static_cast<size_t>(leaf)];
    if (this->Extents.Group(source.SurfaceIndex) == group ||
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

} // namespace sphcover
