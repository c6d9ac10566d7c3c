// SPDX-License-Identifier: BSD-3-Clause
#include "subdivision/Patch.h"

#include "math/Constants.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

namespace sphcover
{
namespace
{
/// Lengths in 3-D of the patch along u and along v, from its control net (mean polygon length
/// of the rows and of the columns): what "square in Euclidean space" compares (§4.3 note 3).
void NetLengths(const BezierPatch& patch, double& alongU, double& alongV)
{
  const int m = patch.DegreeU();
  const int n = patch.DegreeV();
  alongU = 0.0;
  alongV = 0.0;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i < m; ++i)
    {
      alongU += glm::length(patch.ControlPoint(i + 1, j) - patch.ControlPoint(i, j));
    }
  }
  for (int i = 0; i <= m; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      alongV += glm::length(patch.ControlPoint(i, j + 1) - patch.ControlPoint(i, j));
    }
  }
  alongU /= (n + 1);
  alongV /= (m + 1);
}

/// Nodes and weights of n-point Gauss-Legendre quadrature on [0,1] (Newton on P_n).
struct GaussLegendre
{
  std::vector<double> Nodes;
  std::vector<double> Weights;

  explicit GaussLegendre(int n)
  {
    for (int k = 0; k < n; ++k)
    {
      double x = std::cos(Pi * (k + 0.75) / (n + 0.5));
      double derivative = 0.0;
      for (int iteration = 0; iteration < 100; ++iteration)
      {
        double p0 = 1.0;
        double p1 = x;
        for (int j = 2; j <= n; ++j)
        {
          const double p2 = ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p0) / j;
          p0 = p1;
          p1 = p2;
        }
        derivative = n * (x * p1 - p0) / (x * x - 1.0);
        const double step = p1 / derivative;
        x -= step;
        if (std::fabs(step) < 1e-16)
        {
          break;
        }
      }
      this->Nodes.push_back(0.5 * (1.0 - x));
      this->Weights.push_back(1.0 / ((1.0 - x * x) * derivative * derivative));
    }
  }
};

const GaussLegendre& RuleOfOrder(int n)
{
  static std::array<std::unique_ptr<GaussLegendre>, 64> rules;
  static std::once_flag once[64];
  std::call_once(
    once[n], [n] { rules[static_cast<size_t>(n)] = std::make_unique<GaussLegendre>(n); });
  return *rules[static_cast<size_t>(n)];
}
}

double PatchArea(const BezierPatch& patch)
{
  // |N| is a square root of a polynomial of degree (4m-2, 4n-2): smooth wherever N does not
  // vanish. A composite 2 x 2 rule of order 2*max(m,n)+6 per cell integrates the patches of
  // the scenes (and the collapsed poles, where |N| goes to zero linearly) to ~1e-14.
  const int order = std::min(2 * std::max(patch.DegreeU(), patch.DegreeV()) + 6, 63);
  const GaussLegendre& rule = RuleOfOrder(order);
  double area = 0.0;
  for (int cellV = 0; cellV < 2; ++cellV)
  {
    for (int cellU = 0; cellU < 2; ++cellU)
    {
      for (int b = 0; b < order; ++b)
      {
        const double v = 0.5 * (cellV + rule.Nodes[static_cast<size_t>(b)]);
        double row = 0.0;
        for (int a = 0; a < order; ++a)
        {
          const double u = 0.5 * (cellU + rule.Nodes[static_cast<size_t>(a)]);
          row += rule.Weights[static_cast<size_t>(a)] * glm::length(patch.UnnormalizedNormal(u, v));
        }
        area += rule.Weights[static_cast<size_t>(b)] * row;
      }
    }
  }
  return 0.25 * area;
}

Patch::Patch(int surfaceIndex, const UVRect& domain, int level, BezierPatch geometry)
  : SurfaceIndex(surfaceIndex)
  , Domain(domain)
  , Level(level)
  , Geometry(std::move(geometry))
  , Point(this->Geometry.Evaluate(0.5, 0.5))
  , Normal(this->Geometry.Normal(0.5, 0.5))
  , Area(PatchArea(this->Geometry))
{
}

std::vector<Patch> CollectPatches(const std::vector<Patch>& nodes, const std::vector<int>& leaves)
{
  std::vector<Patch> patches;
  patches.reserve(leaves.size());
  for (int node : leaves)
  {
    patches.push_back(nodes[static_cast<size_t>(node)]);
  }
  std::sort(patches.begin(),
    patches.end(),
    [](const Patch& a, const Patch& b)
    {
      if (a.SurfaceIndex != b.SurfaceIndex)
      {
        return a.SurfaceIndex < b.SurfaceIndex;
      }
      if (a.Domain.V0 != b.Domain.V0)
      {
        return a.Domain.V0 < b.Domain.V0;
      }
      return a.Domain.U0 < b.Domain.U0;
    });
  return patches;
}

const char* SplitReasonName(SplitReason reason)
{
  switch (reason)
  {
    case SplitReason::None:
      return "None";
    case SplitReason::SelfShadowing:
      return "SelfShadowing";
    case SplitReason::HemisphericalContainment:
      return "HemisphericalContainment";
    case SplitReason::SphericalShape:
      return "SphericalShape";
    case SplitReason::Characterisability:
      return "Characterisability";
    case SplitReason::RBuffer:
      return "RBuffer";
  }
  return "Unknown";
}

std::array<Patch, 3> SplitInThree(const Patch& parent,
  const BezierPatch& surface,
  SplitReason reason)
{
  double alongU = 0.0;
  double alongV = 0.0;
  NetLengths(parent.Geometry, alongU, alongV);
  const bool splitU = alongU >= alongV;
  const UVRect d = parent.Domain;
  const double lo = splitU ? d.U0 : d.V0;
  const double hi = splitU ? d.U1 : d.V1;
  // The cut values are computed once and shared by neighbouring pieces, so the pieces tile the
  // parent's domain exactly.
  const double cuts[4] = { lo, lo + (hi - lo) / 3.0, lo + 2.0 * (hi - lo) / 3.0, hi };
  auto piece = [&](int k)
  {
    const UVRect rect = splitU ? UVRect{ cuts[k], cuts[k + 1], d.V0, d.V1 }
                               : UVRect{ d.U0, d.U1, cuts[k], cuts[k + 1] };
    Patch result(parent.SurfaceIndex, rect, parent.Level + 1, surface.SubPatch(rect));
    result.Reason = reason;
    return result;
  };
  return { piece(0), piece(1), piece(2) };
}

} // namespace sphcover
