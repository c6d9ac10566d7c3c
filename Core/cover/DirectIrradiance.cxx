// SPDX-License-Identifier: BSD-3-Clause
#include "cover/DirectIrradiance.h"

#include "cover/RayCastFill.h"
#include "geometry/RayCaster.h"
#include "math/Constants.h"
#include "math/PatternShift.h"
#include "subdivision/Patch.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

namespace sphcover
{

namespace
{

/// The rays' filter at a node: a hit on the node's own surface nearer than SelfExclusion is
/// the node itself (its surface's tessellation around the exact point).
struct NodeFilter
{
  const std::vector<int32_t>* SurfaceOfPatch;
  int32_t Surface;
  float SelfExclusion;
  bool BackFacesOcclude;
  /// Per patch 1 when the rays pass its back side (a pane's side or a two-sided surface's, its
  /// reversed copy's front; empty: none), and whether the node is on one.
  const std::vector<char>* PassedBack;
  bool OnPassedBack;
};

bool AcceptForNode(const void* context, std::size_t patch, float distance, bool front)
{
  const NodeFilter& node = *static_cast<const NodeFilter*>(context);
  const bool passed = !node.PassedBack->empty() && (*node.PassedBack)[patch];
  // A pane's (or a two-sided surface's) back side is its reversed copy's front; a node on such a
  // patch lies on that copy too.
  if (!front && (!node.BackFacesOcclude || passed))
  {
    return false;
  }
  if (distance < node.SelfExclusion && passed && node.OnPassedBack)
  {
    return false;
  }
  return !(distance < node.SelfExclusion && (*node.SurfaceOfPatch)[patch] == node.Surface);
}

/// Where the rays of node (s, t) of a patch start: the surface point moved a hair (1e-4 of the
/// patch's parameters and of its Size()) toward the patch's centre and off its front. A node on
/// an edge where surfaces meet then lies on one side of the other surface: a ray into that
/// surface's front meets it (the floor, from the foot of a block's face), a ray leaving it
/// does not (the lamp, from the foot of a wall), and at a convex edge (a block's top) the side
/// face lies wholly behind the node.
glm::dvec3 RayOrigin(const Patch& patch, double s, double t, glm::dvec3& normal)
{
  const double inward = 1e-4;
  const double si = s + (0.5 - s) * inward;
  const double ti = t + (0.5 - t) * inward;
  normal = patch.Geometry.Normal(si, ti);
  return patch.Geometry.Evaluate(si, ti) + normal * (inward * patch.Geometry.Size());
}

/// A node's rays: their origin, the surface's normal there and their filter.
struct NodeRays
{
  NodeFilter Filter;
  glm::dvec3 Origin;
  glm::dvec3 Normal;
};

/// One lamp piece: its patch, its emission and its quadrature's least side.
struct LampPiece
{
  std::size_t Patch;
  glm::dvec3 Emission;
  int MinimumSide;
};

/// Runs `body` on nodes 0 .. count - 1 in batches through the ParallelFor, progress from
/// `from` to `to` and abort between batches; false when aborted. Every node is written by one
/// task, so the result does not depend on the threads.
template<typename Body>
bool ForEachNode(const std::vector<std::size_t>& items,
  const Body& body,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  double from,
  double to)
{
  const std::size_t count = items.size();
  const std::size_t batch = std::max<std::size_t>(256, count / 50);
  for (std::size_t first = 0; first < count; first += batch)
  {
    const std::size_t last = std::min(count, first + batch);
    parallelFor(last - first,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t k = begin; k < end; ++k)
        {
          body(items[first + k]);
        }
      });
    if (progress &&
      !progress(from + (to - from) * static_cast<double>(last) / static_cast<double>(count)))
    {
      return false;
    }
  }
  return true;
}

} // namespace

glm::dvec3 DirectIrradianceNodes::At(std::size_t patch, double s, double t) const
{
  const int n = this->NodesPerSide;
  const double x = std::clamp(s, 0.0, 1.0) * (n - 1);
  const double y = std::clamp(t, 0.0, 1.0) * (n - 1);
  const int i = std::min(static_cast<int>(x), n - 2);
  const int j = std::min(static_cast<int>(y), n - 2);
  const double fx = x - i;
  const double fy = y - j;
  auto node = [&](int a, int b)
  {
    const float* value = &this->Values[((patch * static_cast<size_t>(n) + static_cast<size_t>(b)) *
                                           static_cast<size_t>(n) +
                                         static_cast<size_t>(a)) *
      3];
    return glm::dvec3(value[0], value[1], value[2]);
  };
  return (1.0 - fy) * ((1.0 - fx) * node(i, j) + fx * node(i + 1, j)) +
    fy * ((1.0 - fx) * node(i, j + 1) + fx * node(i + 1, j + 1));
}

bool ComputeDirectIrradiance(const std::vector<Patch>& patches,
  const RayCaster& caster,
  const std::vector<bool>& lamps,
  const std::vector<glm::dvec3>& emission,
  const std::vector<glm::dvec3>& diffuse,
  const DirectIrradianceOptions& options,
  DirectIrradianceNodes& result,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  const RankShare& share)
{
  const bool bounce = options.BounceRaysPerSide > 0;
  if (emission.size() != patches.size() || caster.PatchCount() != patches.size() ||
    (bounce && diffuse.size() != patches.size()))
  {
    throw std::invalid_argument("ComputeDirectIrradiance: " + std::to_string(patches.size()) +
      " patches, the emission of " + std::to_string(emission.size()) + ", the reflectance of " +
      std::to_string(diffuse.size()) + " and a caster of " + std::to_string(caster.PatchCount()));
  }
  if (options.BounceRaysPerSide < 0 || options.BounceRaysPerSide > 256)
  {
    throw std::invalid_argument("ComputeDirectIrradiance: BounceRaysPerSide " +
      std::to_string(options.BounceRaysPerSide) + " is not in [0, 256]");
  }
  const int n = options.NodesPerSide;
  if (n < 3 || n > 33 || n % 2 == 0)
  {
    throw std::invalid_argument("ComputeDirectIrradiance: NodesPerSide " + std::to_string(n) +
      " is not an odd number from 3 to 33");
  }
  result = DirectIrradianceNodes();
  if (!options.Transmittance.empty() && options.Transmittance.size() != patches.size())
  {
    throw std::invalid_argument(
      "ComputeDirectIrradiance: " + std::to_string(options.Transmittance.size()) +
      " transmittances for " + std::to_string(patches.size()) + " patches");
  }
  // Panes (see DirectIrradianceOptions::Transmittance): per patch whether it is one.
  std::vector<char> panePatch;
  for (const glm::vec3& t : options.Transmittance)
  {
    panePatch.push_back(t != glm::vec3(0.0f) ? 1 : 0);
  }
  if (std::find(panePatch.begin(), panePatch.end(), 1) == panePatch.end())
  {
    panePatch.clear();
  }
  const std::vector<glm::vec3>* panes = panePatch.empty() ? nullptr : &options.Transmittance;
  // The patches whose back side the rays pass: the panes' and the two-sided surfaces' sides.
  std::vector<char> passedBack;
  for (std::size_t k = 0; k < patches.size(); ++k)
  {
    const std::size_t surface = static_cast<std::size_t>(patches[k].SurfaceIndex);
    const bool twoSided =
      surface < options.TwoSidedSurfaces.size() && options.TwoSidedSurfaces[surface];
    passedBack.push_back(twoSided || (!panePatch.empty() && panePatch[k]) ? 1 : 0);
  }
  if (std::find(passedBack.begin(), passedBack.end(), 1) == passedBack.end())
  {
    passedBack.clear();
  }

  std::vector<std::size_t> piecesOfSurface(lamps.size(), 0);
  std::vector<int32_t> surfaceOfPatch(patches.size());
  for (std::size_t k = 0; k < patches.size(); ++k)
  {
    surfaceOfPatch[k] = patches[k].SurfaceIndex;
    const std::size_t surface = static_cast<std::size_t>(patches[k].SurfaceIndex);
    if (surface < lamps.size() && lamps[surface])
    {
      ++piecesOfSurface[surface];
    }
  }
  std::vector<LampPiece> pieces;
  for (std::size_t k = 0; k < patches.size(); ++k)
  {
    const std::size_t surface = static_cast<std::size_t>(patches[k].SurfaceIndex);
    if (surface < lamps.size() && lamps[surface])
    {
      // The lamp's pieces together get at least LampNodesPerSide^2 quadrature nodes, finer
      // where a piece is near (VisibleProjectedSolidAngle).
      const int side = std::max(1,
        static_cast<int>(std::ceil(
          options.LampNodesPerSide / std::sqrt(static_cast<double>(piecesOfSurface[surface])))));
      pieces.push_back({ k, emission[k], side });
    }
  }
  if (pieces.empty())
  {
    return true;
  }

  // A node on a border between patches of one surface belongs to each of them (3 x 3 nodes per
  // patch are about 4 distinct ones on a uniform layout): each distinct (surface, u, v) is
  // computed once, from the first patch that has it.
  const std::size_t nodesPerPatch = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  std::vector<std::size_t> nodeOf(patches.size() * nodesPerPatch);
  std::vector<std::size_t> firstPatch;
  std::vector<int> firstIndex; // j * n + i in that patch
  {
    std::map<std::tuple<int, long long, long long>, std::size_t> distinct;
    const double quantum = 1e9; // rectangles of a ternary subdivision are exact to far better
    for (std::size_t p = 0; p < patches.size(); ++p)
    {
      const UVRect& domain = patches[p].Domain;
      for (int j = 0; j < n; ++j)
      {
        for (int i = 0; i < n; ++i)
        {
          const double u = domain.U0 + (domain.U1 - domain.U0) * i / (n - 1);
          const double v = domain.V0 + (domain.V1 - domain.V0) * j / (n - 1);
          const auto key = std::make_tuple(
            patches[p].SurfaceIndex, std::llround(u * quantum), std::llround(v * quantum));
          const auto found = distinct.emplace(key, firstPatch.size());
          if (found.second)
          {
            firstPatch.push_back(p);
            firstIndex.push_back(j * n + i);
          }
          nodeOf[p * nodesPerPatch + static_cast<std::size_t>(j * n + i)] = found.first->second;
        }
      }
    }
  }

  // Where a distinct node's rays start and what stops them (RayOrigin, NodeFilter).
  auto raysOf = [&](std::size_t node)
  {
    const Patch& patch = patches[firstPatch[node]];
    NodeRays rays;
    rays.Filter = { &surfaceOfPatch,
      patch.SurfaceIndex,
      static_cast<float>(options.SelfExclusionFraction * patch.Geometry.Size()),
      options.BackFacesOcclude,
      &passedBack,
      !passedBack.empty() && passedBack[firstPatch[node]] != 0 };
    rays.Origin = RayOrigin(patch,
      static_cast<double>(firstIndex[node] % n) / (n - 1),
      static_cast<double>(firstIndex[node] / n) / (n - 1),
      rays.Normal);
    return rays;
  };

  std::vector<glm::dvec3> irradianceOfNode(firstPatch.size(), glm::dvec3(0.0));
  auto computeNode = [&](std::size_t node)
  {
    const std::size_t p = firstPatch[node];
    const Patch& patch = patches[p];
    const NodeRays rays = raysOf(node);
    const RayFilter filter{ AcceptForNode, &rays.Filter };
    const glm::dvec3& origin = rays.Origin;
    const glm::dvec3& normal = rays.Normal;
    glm::dvec3 irradiance(0.0);
    for (const LampPiece& piece : pieces)
    {
      if (patches[piece.Patch].SurfaceIndex == patch.SurfaceIndex)
      {
        continue; // the lamp's own light is not direct light on it
      }
      irradiance += piece.Emission *
        VisibleProjectedSolidAngleThroughPanes(caster,
          origin,
          normal,
          filter,
          piece.Patch,
          patches[piece.Patch],
          piece.MinimumSide,
          panes);
    }
    irradianceOfNode[node] = irradiance;
  };

  const std::size_t count = firstPatch.size();
  const double directShare = bounce ? 0.25 : 1.0;
  // The nodes are independent: under MPI each rank computes its share and the values are
  // joined (RankShare.h), the same on every rank whatever K.
  if (!ShareItems(share,
        count,
        irradianceOfNode,
        [&](const std::vector<std::size_t>& items)
        { return ForEachNode(items, computeNode, parallelFor, progress, 0.0, directShare); }))
  {
    return false;
  }
  DirectIrradianceNodes direct;
  direct.NodesPerSide = n;
  direct.Values.assign(patches.size() * nodesPerPatch * 3, 0.0f);
  auto store = [&](const std::vector<glm::dvec3>& ofNode, std::vector<float>& values)
  {
    for (std::size_t k = 0; k < nodeOf.size(); ++k)
    {
      const glm::dvec3& irradiance = ofNode[nodeOf[k]];
      values[3 * k + 0] = static_cast<float>(irradiance.x);
      values[3 * k + 1] = static_cast<float>(irradiance.y);
      values[3 * k + 2] = static_cast<float>(irradiance.z);
    }
  };
  store(irradianceOfNode, direct.Values);

  if (bounce)
  {
    // The first bounce of the direct light: at every node, g x g cosine-weighted rays, each
    // meeting a front side y whose Lambertian radiance rho(y) / pi E_direct(y) comes from the
    // direct light just computed at y's patch's nodes; E = pi x their mean.
    const int g = options.BounceRaysPerSide;
    // The directions of g x g strata of (sin^2 theta, phi) in a node's frame, one per stratum
    // at the place that the node's shift (a Cranley-Patterson rotation hashed from the node's
    // index) gives. With one pattern for every node, neighbouring nodes err alike and the
    // errors make patch-sized blotches; shifted, they vary from node to node and average out
    // over an area.
    auto strataOf = [g](std::size_t node, std::vector<glm::dvec3>& local)
    {
      double shiftTheta = 0.0;
      double shiftPhi = 0.0;
      PatternShift(static_cast<uint64_t>(node), shiftTheta, shiftPhi);
      local.resize(static_cast<std::size_t>(g) * static_cast<std::size_t>(g));
      for (int a = 0; a < g; ++a)
      {
        for (int b = 0; b < g; ++b)
        {
          const double sin2 = (a + shiftTheta) / g;
          const double phi = 2.0 * Pi * (b + shiftPhi) / g;
          local[static_cast<std::size_t>(a * g + b)] = glm::dvec3(std::sqrt(sin2) * std::cos(phi),
            std::sqrt(sin2) * std::sin(phi),
            std::sqrt(1.0 - sin2));
        }
      }
    };
    std::vector<glm::dvec3> bounced(count, glm::dvec3(0.0));
    auto gatherNode = [&](std::size_t node)
    {
      thread_local std::vector<glm::dvec3> local;
      strataOf(node, local);
      const NodeRays rays = raysOf(node);
      const RayFilter filter{ AcceptForNode, &rays.Filter };
      const glm::dvec3& origin = rays.Origin;
      const glm::dvec3& normal = rays.Normal;
      // Any tangent frame: the strata are the same in every one.
      const glm::dvec3 helper =
        std::fabs(normal.x) < 0.6 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
      const glm::dvec3 tangent = glm::normalize(glm::cross(helper, normal));
      const glm::dvec3 bitangent = glm::cross(normal, tangent);
      // The rays share their origin and neighbours in phi are near: packets of them.
      glm::dvec3 sum(0.0);
      glm::dvec3 directions[RayCaster::PacketSize];
      TriangleHit hits[RayCaster::PacketSize];
      bool found[RayCaster::PacketSize];
      for (std::size_t first = 0; first < local.size(); first += RayCaster::PacketSize)
      {
        const int packet =
          static_cast<int>(std::min<std::size_t>(RayCaster::PacketSize, local.size() - first));
        for (int k = 0; k < packet; ++k)
        {
          const glm::dvec3& d = local[first + static_cast<std::size_t>(k)];
          directions[k] = d.x * tangent + d.y * bitangent + d.z * normal;
        }
        caster.IntersectPacket(origin, directions, packet, 0.0f, filter, hits, found);
        for (int k = 0; k < packet; ++k)
        {
          // Through panes: each pane's own Lambertian radiance, then T times what is behind.
          TriangleHit hit = hits[k];
          bool met = found[k];
          glm::dvec3 throughput(1.0);
          for (int pane = 0; met && hit.FrontSide && pane <= MaxPanesPerRay; ++pane)
          {
            sum += throughput * diffuse[hit.Patch] * direct.At(hit.Patch, hit.U, hit.V);
            if (panePatch.empty() || !panePatch[hit.Patch])
            {
              break;
            }
            throughput *= glm::dvec3(options.Transmittance[hit.Patch]);
            met = caster.Intersect(
              origin, directions[k], RayCaster::Beyond(hit.Distance), filter, false, hit);
          }
        }
      }
      bounced[node] = sum / static_cast<double>(local.size());
    };
    if (!ShareItems(share,
          count,
          bounced,
          [&](const std::vector<std::size_t>& items)
          { return ForEachNode(items, gatherNode, parallelFor, progress, directShare, 1.0); }))
    {
      return false;
    }
    std::vector<float> values(direct.Values.size());
    store(bounced, values);
    for (std::size_t k = 0; k < values.size(); ++k)
    {
      direct.Values[k] += values[k];
    }
  }
  result = std::move(direct);
  return true;
}
} // namespace sphcover
