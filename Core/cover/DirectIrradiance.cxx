// SPDX-License-Identifier: BSD-3-Clause
#include "cover/DirectIrradiance.h"

#include "cover/RayCastFill.h"
#include "geometry/RayCaster.h"
#include "subdivision/Patch.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

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

  const std::size_t nodesPerPatch = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  std::vector<float> values(patches.size() * nodesPerPatch * 3, 0.0f);
  auto computePatch = [&](std::size_t p)
  {
    const Patch& patch = patches[p];
    const NodeFilter nodeFilter{ static_cast<float>(
                                   options.SelfExclusionFraction * patch.Geometry.Size()),
      options.BackFacesOcclude };
    const RayFilter filter{ AcceptForNode, &nodeFilter };
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const double s = static_cast<double>(i) / (n - 1);
        const double t = static_cast<double>(j) / (n - 1);
        const glm::dvec3 origin = patch.Geometry.Evaluate(s, t);
        const glm::dvec3 normal = patch.Geometry.Normal(s, t);
        glm::dvec3 irradiance(0.0);
        for (const LampPiece& piece : pieces)
        {
          if (piece.Patch == p)
          {
            continue; // a surface does not light itself directly
          }
          irradiance += piece.Emission *
            VisibleProjectedSolidAngle(
              caster, origin, normal, filter, piece.Patch, patches[piece.Patch], piece.MinimumSide);
        }
        float* out =
          &values[((p * static_cast<size_t>(n) + static_cast<size_t>(j)) * static_cast<size_t>(n) +
                    static_cast<size_t>(i)) *
            3];
        out[0] = static_cast<float>(irradiance.x);
        out[1] = static_cast<float>(irradiance.y);
        out[2] = static_cast<float>(irradiance.z);
      }
    }
  };

  // Batches of patches through the ParallelFor; progress and abort between batches. Every
  // patch's nodes are written by one task, so the result does not depend on the threads.
  const std::size_t batch = std::max<std::size_t>(64, patches.size() / 50);
  for (std::size_t first = 0; first < patches.size(); first += batch)
  {
    const std::size_t last = std::min(patches.size(), first + batch);
    parallelFor(last - first,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t k = begin; k < end; ++k)
        {
          computePatch(first + k);
        }
      });
    if (progress && !progress(static_cast<double>(last) / static_cast<double>(patches.size())))
    {
      return false;
    }
  }
  result.NodesPerSide = n;
  result.Values = std::move(values);
  return true;
}

} // namespace sphcover
