// SPDX-License-Identifier: BSD-3-Clause
// Interpolation over the characteristic points of a surface (paper §3.4, §5.3.2): on a uniform
// partition a bilinear field is reproduced exactly, inside and in the extrapolated margins
// near the edges (Fig. 6); on adaptive ternary layouts a linear field is; a constant stays
// constant everywhere; several surfaces do not mix; bad input is refused.
#include "subdivision/CharacteristicPointInterpolator.h"

#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <stdexcept>
#include <vector>

using namespace sphcover;

namespace
{
struct Layout
{
  std::vector<int> Surface;
  std::vector<UVRect> Domain;

  void Add(int surface, const UVRect& r)
  {
    this->Surface.push_back(surface);
    this->Domain.push_back(r);
  }
};

/// An nu x nv uniform partition of the unit square.
void AddUniform(Layout& layout, int surface, int nu, int nv)
{
  for (int j = 0; j < nv; ++j)
  {
    for (int i = 0; i < nu; ++i)
    {
      layout.Add(surface,
        { static_cast<double>(i) / nu,
          static_cast<double>(i + 1) / nu,
          static_cast<double>(j) / nv,
          static_cast<double>(j + 1) / nv });
    }
  }
}

/// The three pieces of a ternary split (paper §4.3 note 3) along u or v.
std::vector<UVRect> SplitInThree(const UVRect& r, bool alongU)
{
  std::vector<UVRect> pieces;
  for (int k = 0; k < 3; ++k)
  {
    UVRect piece = r;
    if (alongU)
    {
      const double w = (r.U1 - r.U0) / 3.0;
      piece.U0 = r.U0 + k * w;
      piece.U1 = k == 2 ? r.U1 : r.U0 + (k + 1) * w;
    }
    else
    {
      const double w = (r.V1 - r.V0) / 3.0;
      piece.V0 = r.V0 + k * w;
      piece.V1 = k == 2 ? r.V1 : r.V0 + (k + 1) * w;
    }
    pieces.push_back(piece);
  }
  return pieces;
}

/// An adaptive layout: random ternary splits, alternating directions, to depth `levels`.
void AddAdaptive(Layout& layout, int surface, unsigned seed, int levels)
{
  std::mt19937 rng(seed);
  std::vector<std::pair<UVRect, int>> work{ { UVRect::Unit(), 0 } };
  while (!work.empty())
  {
    const auto [r, level] = work.back();
    work.pop_back();
    // The first two levels always split (so every surface has neighbours in both directions),
    // later ones with probability 1/2.
    if (level < levels && (level < 2 || rng() % 2 == 0))
    {
      for (const UVRect& piece : SplitInThree(r, (level + rng() % 2) % 2 == 0))
      {
        work.emplace_back(piece, level + 1);
      }
    }
    else
    {
      layout.Add(surface, r);
    }
  }
}

double Interpolate(const CharacteristicPointInterpolator& interpolator,
  const Layout& layout,
  int surface,
  double u,
  double v,
  const std::function<double(double, double)>& field)
{
  InterpolationStencil stencil;
  EXPECT_TRUE(interpolator.Stencil(surface, u, v, stencil));
  double value = 0.0;
  double sum = 0.0;
  for (int k = 0; k < stencil.Count; ++k)
  {
    const UVRect& r = layout.Domain[stencil.Points[static_cast<size_t>(k)]];
    EXPECT_EQ(layout.Surface[stencil.Points[static_cast<size_t>(k)]], surface);
    value += stencil.Weights[static_cast<size_t>(k)] * field(r.CenterU(), r.CenterV());
    sum += stencil.Weights[static_cast<size_t>(k)];
  }
  EXPECT_NEAR(sum, 1.0, 1e-12);
  return value;
}

/// Query points: a random set plus the edges, corners and every patch border of a 1/243 grid.
std::vector<std::pair<double, double>> QueryPoints(unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::pair<double, double>> points;
  for (int k = 0; k < 2000; ++k)
  {
    points.emplace_back(unit(rng), unit(rng));
  }
  for (int k = 0; k <= 243; ++k)
  {
    const double t = k / 243.0;
    points.emplace_back(t, 0.0);
    points.emplace_back(t, 1.0);
    points.emplace_back(0.0, t);
    points.emplace_back(1.0, t);
    points.emplace_back(t, unit(rng));
    points.emplace_back(unit(rng), t);
  }
  return points;
}
}

TEST(CharacteristicPointInterpolator, UniformReproducesBilinearIncludingEdges)
{
  for (const auto& [nu, nv] : std::vector<std::pair<int, int>>{ { 2, 2 }, { 3, 9 }, { 27, 27 } })
  {
    Layout layout;
    AddUniform(layout, 0, nu, nv);
    const CharacteristicPointInterpolator interpolator(layout.Surface, layout.Domain);
    const auto field = [](double u, double v) { return 1.5 + 2.0 * u - 3.0 * v + 7.0 * u * v; };
    for (const auto& [u, v] : QueryPoints(7))
    {
      EXPECT_NEAR(Interpolate(interpolator, layout, 0, u, v, field), field(u, v), 1e-11)
        << nu << "x" << nv << " at (" << u << ", " << v << ")";
    }
  }
}

TEST(CharacteristicPointInterpolator, UniformIsContinuousAcrossBorders)
{
  Layout layout;
  AddUniform(layout, 0, 9, 9);
  const CharacteristicPointInterpolator interpolator(layout.Surface, layout.Domain);
  // A field that is not bilinear: both sides of a border must still use the same four points.
  const auto field = [](double u, double v) { return std::sin(5.0 * u) * std::cos(3.0 * v); };
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int border = 1; border < 9; ++border)
  {
    const double b = border / 9.0;
    for (int k = 0; k < 50; ++k)
    {
      const double t = unit(rng);
      EXPECT_NEAR(Interpolate(interpolator, layout, 0, b - 1e-9, t, field),
        Interpolate(interpolator, layout, 0, b + 1e-9, t, field),
        1e-7);
      EXPECT_NEAR(Interpolate(interpolator, layout, 0, t, b - 1e-9, field),
        Interpolate(interpolator, layout, 0, t, b + 1e-9, field),
        1e-7);
    }
  }
}

TEST(CharacteristicPointInterpolator, AdaptiveReproducesLinearIncludingEdges)
{
  for (unsigned seed = 1; seed <= 12; ++seed)
  {
    Layout layout;
    AddAdaptive(layout, 0, seed, 4);
    const CharacteristicPointInterpolator interpolator(layout.Surface, layout.Domain);
    const auto field = [](double u, double v) { return -0.5 + 4.0 * u + 2.5 * v; };
    for (const auto& [u, v] : QueryPoints(seed))
    {
      EXPECT_NEAR(Interpolate(interpolator, layout, 0, u, v, field), field(u, v), 1e-10)
        << "seed " << seed << " at (" << u << ", " << v << ")";
    }
  }
}

TEST(CharacteristicPointInterpolator, ConstantStaysConstantEverywhere)
{
  Layout layout;
  AddUniform(layout, 0, 1, 1);
  AddUniform(layout, 1, 3, 1);
  AddAdaptive(layout, 2, 5, 5);
  AddUniform(layout, 3, 9, 27);
  const CharacteristicPointInterpolator interpolator(layout.Surface, layout.Domain);
  for (int surface = 0; surface < 4; ++surface)
  {
    for (const auto& [u, v] : QueryPoints(11))
    {
      EXPECT_NEAR(
        Interpolate(
          interpolator, layout, surface, u, v, [surface](double, double) { return 2.0 + surface; }),
        2.0 + surface,
        1e-12);
    }
  }
}

TEST(CharacteristicPointInterpolator, LocatesContainingPatchAndRefusesBadInput)
{
  Layout layout;
  AddAdaptive(layout, 0, 9, 5);
  AddUniform(layout, 2, 3, 3);
  const CharacteristicPointInterpolator interpolator(layout.Surface, layout.Domain);
  EXPECT_TRUE(interpolator.HasPoints(0));
  EXPECT_FALSE(interpolator.HasPoints(1));
  EXPECT_FALSE(interpolator.HasPoints(3));
  EXPECT_FALSE(interpolator.HasPoints(-1));
  InterpolationStencil stencil;
  EXPECT_FALSE(interpolator.Stencil(1, 0.5, 0.5, stencil));
  for (const auto& [u, v] : QueryPoints(2))
  {
    const std::ptrdiff_t p = interpolator.ContainingPoint(0, u, v);
    ASSERT_GE(p, 0);
    const UVRect& r = layout.Domain[static_cast<size_t>(p)];
    EXPECT_TRUE(r.U0 <= u && u <= r.U1 && r.V0 <= v && v <= r.V1);
  }
  EXPECT_THROW(CharacteristicPointInterpolator({ 0 }, {}), std::invalid_argument);
  EXPECT_THROW(CharacteristicPointInterpolator({ -1 }, { UVRect::Unit() }), std::invalid_argument);
  EXPECT_THROW(CharacteristicPointInterpolator({ 0 }, { UVRect{ 0.5, 0.5, 0.0, 1.0 } }),
    std::invalid_argument);
}

TEST(CharacteristicPointInterpolator, ExcludedPointsTakePartInNoStencil)
{
  // A 9 x 9 partition whose middle 3 x 3 points are excluded (the floor under a block): every
  // stencil leaves them out, and the kept points' linear field is still reproduced everywhere,
  // next to the excluded block and inside it.
  Layout layout;
  AddUniform(layout, 0, 9, 9);
  CharacteristicPointInterpolator interpolator(layout.Surface, layout.Domain);
  std::vector<bool> excluded(layout.Domain.size(), false);
  for (size_t p = 0; p < layout.Domain.size(); ++p)
  {
    const UVRect& r = layout.Domain[p];
    excluded[p] = r.CenterU() > 1.0 / 3.0 && r.CenterU() < 2.0 / 3.0 && r.CenterV() > 1.0 / 3.0 &&
      r.CenterV() < 2.0 / 3.0;
  }
  interpolator.SetExcludedPoints(excluded);
  const auto field = [](double u, double v) { return 1.5 + 2.0 * u - 3.0 * v; };
  for (const auto& [u, v] : QueryPoints(11))
  {
    InterpolationStencil stencil;
    ASSERT_TRUE(interpolator.Stencil(0, u, v, stencil));
    for (int k = 0; k < stencil.Count; ++k)
    {
      EXPECT_FALSE(excluded[stencil.Points[static_cast<size_t>(k)]])
        << "(" << u << ", " << v << ") uses an excluded point";
    }
    EXPECT_NEAR(Interpolate(interpolator, layout, 0, u, v, field), field(u, v), 1e-11)
      << "(" << u << ", " << v << ")";
  }
  // One flag per point, or none.
  EXPECT_THROW(interpolator.SetExcludedPoints(std::vector<bool>(3, true)), std::invalid_argument);
  interpolator.SetExcludedPoints({});
  EXPECT_FALSE(interpolator.IsExcluded(40));
}
