// SPDX-License-Identifier: BSD-3-Clause
#include "cover/DirectIrradiance.h"

#include "cover/RayCastFill.h"
#include "geometry/RayCaster.h"
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

/// The shadow rays' filter: whatever the ray meets right at the node is where the node lies
/// (its own surface's tessellation, and at a node on an edge where surfaces meet, the other
/// surface's plane, which the ray leaves at once).
struct NodeFilter
{
  float SelfExclusion;
  bool BackFacesOcclude;
};

bool AcceptForNode(const void* context, std::size_t, float distance, bool front)
{
  const NodeFilter& node = *static_cast<const NodeFilter*>(context);
  if (!front && !node.BackFacesOcclude)
  {
    return false;
  }
  return !(distance < node.SelfExclusion);
}

/// One lamp piece: its patch, its emission and its quadrature's least side.
struct LampPiece
{
  std::size_t Patch;
  glm::dvec3 Emission;
  int MinimumSide;
};

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
  const DirectIrradianceOptions& options,
  DirectIrradianceNodes& result,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress)
{
  if (emission.size() != patches.size() || caster.PatchCount() != patches.size())
  {
    throw std::invalid_argument("ComputeDirectIrradiance: " + std::to_string(patches.size()) +
      " patches, the emission of " + std::to_string(emission.size()) + " and a caster of " +
      std::to_string(caster.PatchCount()));
  }
  const int n = options.NodesPerSide;
  if (n < 3 || n > 33 || n % 2 == 0)
  {
    throw std::invalid_argument("ComputeDirectIrradiance: NodesPerSide " + std::to_string(n) +
      " is not an odd number from 3 to 33");
  }
  result = DirectIrradianceNodes();

  std::vector<std::size_t> piecesOfSurface(lamps.size(), 0);
  for (std::size_t k = 0; k < patches.size(); ++k)
  {
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

  std::vector<glm::dvec3> irradianceOfNode(firstPatch.size(), glm::dvec3(0.0));
  auto computeNode = [&](std::size_t node)
  {
    const std::size_t p = firstPatch[node];
    const Patch& patch = patches[p];
    const NodeFilter nodeFilter{ static_cast<float>(
                                   options.SelfExclusionFraction * patch.Geometry.Size()),
      options.BackFacesOcclude };
    const RayFilter filter{ AcceptForNode, &nodeFilter };
    const double s = static_cast<double>(firstIndex[node] % n) / (n - 1);
    const double t = static_cast<double>(firstIndex[node] / n) / (n - 1);
    const glm::dvec3 origin = patch.Geometry.Evaluate(s, t);
    const glm::dvec3 normal = patch.Geometry.Normal(s, t);
    glm::dvec3 irradiance(0.0);
    for (const LampPiece& piece : pieces)
    {
      if (patches[piece.Patch].SurfaceIndex == patch.SurfaceIndex)
      {
        continue; // the lamp's own light is not direct light on it
      }
      irradiance += piece.Emission *
        VisibleProjectedSolidAngle(
          caster, origin, normal, filter, piece.Patch, patches[piece.Patch], piece.MinimumSide);
    }
    irradianceOfNode[node] = irradiance;
  };

  // Batches of nodes through the ParallelFor; progress and abort between batches. Every node
  // is written by one task, so the result does not depend on the threads.
  const std::size_t count = firstPatch.size();
  const std::size_t batch = std::max<std::size_t>(256, count / 50);
  for (std::size_t first = 0; first < count; first += batch)
  {
    const std::size_t last = std::min(count, first + batch);
    parallelFor(last - first,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t k = begin; k < end; ++k)
        {
          computeNode(first + k);
        }
      });
    if (progress && !progress(static_cast<double>(last) / static_cast<double>(count)))
    {
      return false;
    }
  }
  std::vector<float> values(patches.size() * nodesPerPatch * 3, 0.0f);
  for (std::size_t k = 0; k < nodeOf.size(); ++k)
  {
    const glm::dvec3& irradiance = irradianceOfNode[nodeOf[k]];
    values[3 * k + 0] = static_cast<float>(irradiance.x);
    values[3 * k + 1] = static_cast<float>(irradiance.y);
    values[3 * k + 2] = static_cast<float>(irradiance.z);
  }
  result.NodesPerSide = n;
  result.Values = std::move(values);
  return true;
}

} // namespace sphcover
