// SPDX-License-Identifier: BSD-3-Clause
#include "cover/DirectIrradiance.h"

#include "cover/RayCastFill.h"
#include "geometry/RayCaster.h"
#include "math/Constants.h"
#include "math/PatternShift.h"
#include "subdivision/Patch.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
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
  /// RayFilter::RejectsAllNearer: the self-exclusion distance when only the node's own surface
  /// comes within twice it of the origin (then AcceptForNode rejects every hit nearer), else 0.
  float RejectsAllNearer = 0.0f;

  RayFilter Predicate() const { return { AcceptForNode, &this->Filter, this->RejectsAllNearer }; }
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

/// The bilinear interpolation of the corner values a00 (0, 0), a10 (1, 0), a01 and a11 at
/// (fx, fy) in [0, 1]^2.
glm::dvec3 Bilinear(const glm::dvec3& a00,
  const glm::dvec3& a10,
  const glm::dvec3& a01,
  const glm::dvec3& a11,
  double fx,
  double fy)
{
  return (1.0 - fy) * ((1.0 - fx) * a00 + fx * a10) + fy * ((1.0 - fx) * a01 + fx * a11);
}

/// The brightest band of a value.
double Brightest(const glm::dvec3& value)
{
  return std::max(value.x, std::max(value.y, value.z));
}

/**
 * Per patch whether its nodes beyond the coarse 3 x 3 are computed (file comment of
 * DirectIrradiance.h, DirectIrradianceOptions::RefinementTolerance): where some coarse node
 * departs from the bilinear interpolation of the patch's four corners by more than `tolerance`
 * times the larger of the patch's brightest coarse node and the scene's mean (the area-weighted
 * mean of the patches' coarse nodes), so that a dark patch is held to the scene's scale and not
 * to its own. `coarse(p, ci, cj)` is the value at patch p's coarse node (ci, cj) in {0, 1, 2}^2
 * whose departure counts, `brightness(p, ci, cj)` the light there it is measured against.
 */
template<typename Coarse, typename Brightness>
std::vector<char> RefineWhere(const std::vector<Patch>& patches,
  const Coarse& coarse,
  const Brightness& brightness,
  double tolerance)
{
  double weighted = 0.0;
  double area = 0.0;
  for (std::size_t p = 0; p < patches.size(); ++p)
  {
    const double size = patches[p].Geometry.Size();
    double mean = 0.0;
    for (int cj = 0; cj < 3; ++cj)
    {
      for (int ci = 0; ci < 3; ++ci)
      {
        mean += Brightest(brightness(p, ci, cj)) / 9.0;
      }
    }
    weighted += size * size * mean;
    area += size * size;
  }
  const double scene = area > 0.0 ? weighted / area : 0.0;
  std::vector<char> refine(patches.size(), 0);
  for (std::size_t p = 0; p < patches.size(); ++p)
  {
    double brightest = 0.0;
    double deviation = 0.0;
    for (int cj = 0; cj < 3; ++cj)
    {
      for (int ci = 0; ci < 3; ++ci)
      {
        const double fx = 0.5 * ci;
        const double fy = 0.5 * cj;
        const glm::dvec3 bilinear =
          Bilinear(coarse(p, 0, 0), coarse(p, 2, 0), coarse(p, 0, 2), coarse(p, 2, 2), fx, fy);
        const glm::dvec3 value = coarse(p, ci, cj);
        brightest = std::max(brightest, Brightest(brightness(p, ci, cj)));
        deviation = std::max(deviation, Brightest(glm::abs(value - bilinear)));
      }
    }
    refine[p] = tolerance <= 0.0 || deviation > tolerance * std::max(brightest, scene) ? 1 : 0;
  }
  return refine;
}

/**
 * Computes `valueOf(node)` for the distinct nodes `nodes` into `ofNode[node]`, progress from
 * `from` to `to`; false when aborted. The nodes are independent: under MPI each rank computes
 * its share and the values are joined (RankShare.h), the same on every rank whatever K.
 */
template<typename ValueOf>
bool ComputeNodes(const std::vector<std::size_t>& nodes,
  const ValueOf& valueOf,
  std::vector<glm::dvec3>& ofNode,
  const RankShare& share,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  double from,
  double to)
{
  std::vector<glm::dvec3> values(nodes.size(), glm::dvec3(0.0));
  auto computeOne = [&](std::size_t k) { values[k] = valueOf(nodes[k]); };
  if (!ShareItems(share,
        nodes.size(),
        values,
        [&](const std::vector<std::size_t>& items)
        { return ForEachNode(items, computeOne, parallelFor, progress, from, to); }))
  {
    return false;
  }
  for (std::size_t k = 0; k < nodes.size(); ++k)
  {
    ofNode[nodes[k]] = values[k];
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
  return Bilinear(node(i, j), node(i + 1, j), node(i, j + 1), node(i + 1, j + 1), fx, fy);
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
  if (!(options.RefinementTolerance >= 0.0)) // NaN too
  {
    throw std::invalid_argument("ComputeDirectIrradiance: RefinementTolerance " +
      std::to_string(options.RefinementTolerance) + " is not a number >= 0");
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
  // Per lamp surface whether it is planar (NearlyPlanar over its pieces' nets together): a plane
  // cannot light itself, but a concave lamp (a bowl, the inside of a trough) lights its own
  // inside, and the propagation's version of the nodes' light (LampIrradiance) counts that too.
  std::vector<std::vector<glm::dvec3>> netOfSurface(lamps.size());
  std::vector<glm::dvec3> normalOfSurface(lamps.size(), glm::dvec3(0.0));
  for (const LampPiece& piece : pieces)
  {
    const BezierPatch& geometry = patches[piece.Patch].Geometry;
    const std::size_t surface = static_cast<std::size_t>(patches[piece.Patch].SurfaceIndex);
    std::vector<glm::dvec3>& net = netOfSurface[surface];
    net.insert(net.end(), geometry.ControlPoints().begin(), geometry.ControlPoints().end());
    if (normalOfSurface[surface] == glm::dvec3(0.0))
    {
      normalOfSurface[surface] = geometry.ControlNetNormal();
    }
  }
  std::vector<char> planarLamp(lamps.size(), 0);
  for (std::size_t surface = 0; surface < lamps.size(); ++surface)
  {
    const std::vector<glm::dvec3>& net = netOfSurface[surface];
    if (!net.empty())
    {
      glm::dvec3 low = net.front();
      glm::dvec3 high = net.front();
      for (const glm::dvec3& point : net)
      {
        low = glm::min(low, point);
        high = glm::max(high, point);
      }
      planarLamp[surface] =
        NearlyPlanar(net, normalOfSurface[surface], glm::length(high - low)) ? 1 : 0;
    }
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
    thread_local std::vector<std::size_t> near;
    caster.PatchesNear(rays.Origin, 2.0 * rays.Filter.SelfExclusion, near);
    if (std::all_of(near.begin(),
          near.end(),
          [&](std::size_t q) { return surfaceOfPatch[q] == patch.SurfaceIndex; }))
    {
      rays.RejectsAllNearer = rays.Filter.SelfExclusion;
    }
    return rays;
  };

  std::vector<glm::dvec3> irradianceOfNode(firstPatch.size(), glm::dvec3(0.0));
  // Rays beyond the panes' limit, summed over the threads (an integer: the sum is exact).
  std::atomic<uint64_t> paneLimitRays{ 0 };
  auto directAt = [&](std::size_t node)
  {
    uint64_t nodePaneLimit = 0;
    const std::size_t p = firstPatch[node];
    const Patch& patch = patches[p];
    const NodeRays rays = raysOf(node);
    const RayFilter filter = rays.Predicate();
    glm::dvec3 irradiance(0.0);
    for (const LampPiece& piece : pieces)
    {
      if (patches[piece.Patch].SurfaceIndex == patch.SurfaceIndex &&
        planarLamp[static_cast<std::size_t>(patch.SurfaceIndex)])
      {
        continue; // a planar lamp does not see itself
      }
      irradiance += piece.Emission *
        VisibleProjectedSolidAngleThroughPanes(caster,
          rays.Origin,
          rays.Normal,
          filter,
          piece.Patch,
          patches[piece.Patch],
          piece.MinimumSide,
          panes,
          &nodePaneLimit);
    }
    paneLimitRays += nodePaneLimit;
    return irradiance;
  };
  auto computeNodes = [&](const std::vector<std::size_t>& nodes, double from, double to) {
    return ComputeNodes(nodes, directAt, irradianceOfNode, share, parallelFor, progress, from, to);
  };

  // The coarse nodes, 3 x 3 per patch at fine indices 0, h and n - 1 (h = (n - 1) / 2), are
  // computed at every patch; a patch's other nodes only where its coarse nodes say the light
  // is not bilinear across it (RefineWhere), else they are interpolated from the coarse ones.
  // With n = 3 every node is coarse and nothing is refined.
  const int h = (n - 1) / 2;
  std::vector<char> computed(firstPatch.size(), 0);
  std::vector<std::size_t> coarseNodes;
  for (std::size_t p = 0; p < patches.size(); ++p)
  {
    for (int j = 0; j < n; j += h)
    {
      for (int i = 0; i < n; i += h)
      {
        const std::size_t node = nodeOf[p * nodesPerPatch + static_cast<std::size_t>(j * n + i)];
        if (!computed[node])
        {
          computed[node] = 1;
          coarseNodes.push_back(node);
        }
      }
    }
  }
  std::sort(coarseNodes.begin(), coarseNodes.end());
  const double directShare = bounce ? 0.25 : 1.0;
  const double coarseShare = n == 3 ? directShare : 0.5 * directShare;
  if (!computeNodes(coarseNodes, 0.0, coarseShare))
  {
    return false;
  }
  // Patch p's coarse node (ci, cj) of per-node values.
  auto coarseOf = [&](const std::vector<glm::dvec3>& ofNode)
  {
    const std::vector<glm::dvec3>* values = &ofNode; // not the reference: it ends here
    return [values, &nodeOf, nodesPerPatch, n, h](std::size_t p, int ci, int cj) {
      return (*values)[nodeOf[p * nodesPerPatch + static_cast<std::size_t>(cj * h * n + ci * h)]];
    };
  };
  // The distinct nodes of the patches marked in `refine` that `done` does not hold yet, in
  // ascending order; marks them in `done`.
  auto nodesOfRefined = [&](const std::vector<char>& refine, std::vector<char>& done)
  {
    std::vector<std::size_t> nodes;
    for (std::size_t p = 0; p < patches.size(); ++p)
    {
      for (std::size_t k = 0; refine[p] && k < nodesPerPatch; ++k)
      {
        const std::size_t node = nodeOf[p * nodesPerPatch + k];
        if (!done[node])
        {
          done[node] = 1;
          nodes.push_back(node);
        }
      }
    }
    std::sort(nodes.begin(), nodes.end());
    return nodes;
  };
  if (n > 3)
  {
    const std::vector<char> refined = RefineWhere(
      patches, coarseOf(irradianceOfNode), coarseOf(irradianceOfNode), options.RefinementTolerance);
    if (!computeNodes(nodesOfRefined(refined, computed), coarseShare, directShare))
    {
      return false;
    }
  }

  DirectIrradianceNodes direct;
  direct.NodesPerSide = n;
  direct.Values.assign(patches.size() * nodesPerPatch * 3, 0.0f);
  // Patch p's value at fine node (i, j): the node's own where it was computed (by this patch or
  // a refined neighbour that shares it, so that the two agree along their edge), else the
  // bilinear interpolation of p's coarse nodes.
  auto store = [&](const std::vector<glm::dvec3>& ofNode,
                 const std::vector<char>& own,
                 std::vector<float>& values)
  {
    const auto coarseNode = coarseOf(ofNode);
    for (std::size_t p = 0; p < patches.size(); ++p)
    {
      auto coarse = [&](int ci, int cj) { return coarseNode(p, ci, cj); };
      for (int j = 0; j < n; ++j)
      {
        for (int i = 0; i < n; ++i)
        {
          const std::size_t k = p * nodesPerPatch + static_cast<std::size_t>(j * n + i);
          glm::dvec3 irradiance = ofNode[nodeOf[k]];
          if (!own[nodeOf[k]])
          {
            const int ci = std::min(i / h, 1);
            const int cj = std::min(j / h, 1);
            const double fx = static_cast<double>(i - ci * h) / h;
            const double fy = static_cast<double>(j - cj * h) / h;
            irradiance = Bilinear(coarse(ci, cj),
              coarse(ci + 1, cj),
              coarse(ci, cj + 1),
              coarse(ci + 1, cj + 1),
              fx,
              fy);
          }
          values[3 * k + 0] = static_cast<float>(irradiance.x);
          values[3 * k + 1] = static_cast<float>(irradiance.y);
          values[3 * k + 2] = static_cast<float>(irradiance.z);
        }
      }
    }
  };
  store(irradianceOfNode, computed, direct.Values);

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
    auto strataOf = [](std::size_t node, int g, std::vector<glm::dvec3>& local)
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
    // Gathered at the coarse nodes, and at the finer ones of the patches where it is not
    // bilinear; elsewhere interpolated, as the direct light.
    std::vector<glm::dvec3> bounced(firstPatch.size(), glm::dvec3(0.0));
    auto gatherNode = [&](std::size_t node, int g)
    {
      thread_local std::vector<glm::dvec3> local;
      strataOf(node, g, local);
      const NodeRays rays = raysOf(node);
      const RayFilter filter = rays.Predicate();
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
            if (pane == MaxPanesPerRay && met && hit.FrontSide)
            {
              ++paneLimitRays;
            }
          }
        }
      }
      return sum / static_cast<double>(local.size());
    };
    // Gathers the bounce at the distinct nodes `nodes` with g x g rays each into bounced.
    auto gatherNodes = [&](const std::vector<std::size_t>& nodes, int g, double from, double to)
    {
      return ComputeNodes(
        nodes,
        [&](std::size_t node) { return gatherNode(node, g); },
        bounced,
        share,
        parallelFor,
        progress,
        from,
        to);
    };
    const double coarseEnd = n == 3 ? 1.0 : 0.5 * (1.0 + directShare);
    if (!gatherNodes(coarseNodes, g, directShare, coarseEnd))
    {
      return false;
    }
    std::vector<char> gatheredAt(firstPatch.size(), 0);
    for (const std::size_t node : coarseNodes)
    {
      gatheredAt[node] = 1;
    }
    if (n > 3)
    {
      // Where the bounce itself is not bilinear across a patch (beside a patch of light), its
      // finer nodes gather it too, with g / h rays per side: a refined patch's fine nodes then
      // cost about as many rays as its coarse ones, and their noise averages over the area.
      std::vector<glm::dvec3> total(firstPatch.size());
      for (std::size_t k = 0; k < total.size(); ++k)
      {
        total[k] = irradianceOfNode[k] + bounced[k];
      }
      const std::vector<char> refineBounce =
        RefineWhere(patches, coarseOf(bounced), coarseOf(total), options.RefinementTolerance);
      if (!gatherNodes(
            nodesOfRefined(refineBounce, gatheredAt), std::max(4, g / h), coarseEnd, 1.0))
      {
        return false;
      }
    }
    std::vector<float> values(direct.Values.size());
    store(bounced, gatheredAt, values);
    for (std::size_t k = 0; k < values.size(); ++k)
    {
      direct.Values[k] += values[k];
    }
  }
  direct.PaneLimitRays = paneLimitRays.load();
  result = std::move(direct);
  return true;
}
} // namespace sphcover
