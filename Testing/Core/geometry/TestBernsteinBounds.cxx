// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TestBernsteinBounds.cxx
 * @brief Range bounds of paper §4.2 (position, normal, facing function f of §4.2.1, squared
 * distance of §4.2.3, height above a plane of §4.2.2) by natural interval evaluation and by
 * the Bernstein form.
 *
 * What is checked, as mathematical facts:
 *  - enclosure: both methods contain every sampled value of the quantity over the rectangle,
 *    evaluated on the ORIGINAL patch in doubles (only the sampling round-off, 1e-12 of the
 *    quantity's scale, is allowed as slack), for random patches of all test degrees and all 32
 *    teapot patches, many random rectangles (full, interior, thin boundary strips, zero-width)
 *    and random points;
 *  - rigour: the Bernstein bounds contain the exact minimum and maximum Bernstein coefficient
 *    of the restricted nets, computed in exact rational arithmetic (GMP), although the
 *    implementation computes them in doubles with an a-priori rounding-error bound; and the
 *    bound is tight (within 1e-12 of the quantity's scale);
 *  - exactness where the polynomial is known: constants and the unit square's distance
 *    function are reproduced exactly, and the Bernstein box of the whole patch is the control
 *    net's box;
 *  - order: on the teapot the Bernstein bounds are never wider than the natural ones (each
 *    Bernstein coefficient is a convex combination of values the natural evaluation
 *    encloses); the mean width ratio for f is printed and recorded as a test property;
 *  - convergence: around a critical point of |Q - P|^2, halving the rectangle shrinks the
 *    Bernstein excess width by 4 (quadratic), the natural excess only by 2 (linear).
 */
#include "PatchTestUtilities.h"
#include "geometry/BernsteinBounds.h"
#include "geometry/DeCasteljau.h"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace
{

using sphcover::BezierPatch;
using sphcover::Interval;
using sphcover::IntervalVec3;
using sphcover::RangeMethod;
using sphcover::UVRect;
using sphcover_test::RandomPatch;
using sphcover_test::Teapot;
using sphcover_test::TestDegrees;

constexpr RangeMethod Methods[] = { RangeMethod::Bernstein, RangeMethod::NaturalInterval };

const char* Name(RangeMethod method)
{
  return method == RangeMethod::Bernstein ? "Bernstein" : "NaturalInterval";
}

/// All five bounded quantities for one rectangle, point and plane, by one method.
struct Ranges
{
  IntervalVec3 Position;
  IntervalVec3 Normal;
  Interval Facing;
  Interval SquaredDistance;
  Interval Height;
};

Ranges ComputeRanges(const BezierPatch& patch,
  const UVRect& rect,
  const glm::dvec3& point,
  const glm::dvec3& planeNormal,
  RangeMethod method)
{
  return { sphcover::RangeOfPosition(patch, rect, method),
    sphcover::RangeOfNormal(patch, rect, method),
    sphcover::RangeOfFacing(patch, rect, point, method),
    sphcover::RangeOfSquaredDistance(patch, rect, point, method),
    sphcover::RangeOfHeightAbovePlane(patch, rect, point, planeNormal, method) };
}

bool ContainsWithSlack(const Interval& range, double value, double slack)
{
  return range.Lower() - slack <= value && value <= range.Upper() + slack;
}

/**
 * Samples the quantities on a (samples+1)^2 grid of the rectangle on the original patch and
 * checks that both methods enclose them. The slack is 1e-12 S^k for a quantity of degree k in
 * lengths, with S the largest |Q|, |Q - P|, |Qu|, |Qv| seen: the round-off of the sampled
 * values in doubles is a few ulps of such products.
 */
void ExpectEnclosure(const BezierPatch& patch,
  const UVRect& rect,
  const glm::dvec3& point,
  const glm::dvec3& planeNormal,
  const std::string& what,
  int samples = 32)
{
  const Ranges ranges[2] = { ComputeRanges(patch, rect, point, planeNormal, Methods[0]),
    ComputeRanges(patch, rect, point, planeNormal, Methods[1]) };
  struct Sample
  {
    glm::dvec3 Q;
    glm::dvec3 N;
    double F;
    double G;
    double H;
  };
  std::vector<Sample> values;
  double scale = glm::length(planeNormal);
  for (int b = 0; b <= samples; ++b)
  {
    for (int a = 0; a <= samples; ++a)
    {
      const double u = rect.U0 + (rect.U1 - rect.U0) * a / samples;
      const double v = rect.V0 + (rect.V1 - rect.V0) * b / samples;
      Sample s;
      glm::dvec3 qu;
      glm::dvec3 qv;
      patch.EvaluateWithPartials(u, v, s.Q, qu, qv);
      s.N = glm::cross(qu, qv);
      s.F = glm::dot(s.N, s.Q - point);
      s.G = glm::dot(s.Q - point, s.Q - point);
      s.H = glm::dot(planeNormal, s.Q - point);
      values.push_back(s);
      scale = std::max(
        { scale, glm::length(s.Q), glm::length(s.Q - point), glm::length(qu), glm::length(qv) });
    }
  }
  const double slack1 = 1e-12 * scale;
  const double slack2 = slack1 * scale;
  const double slack3 = slack2 * scale;
  for (int k = 0; k < 2; ++k)
  {
    const Ranges& r = ranges[k];
    int failures = 0;
    for (const Sample& s : values)
    {
      bool ok = true;
      for (int axis = 0; axis < 3; ++axis)
      {
        ok = ok && ContainsWithSlack(r.Position[axis], s.Q[axis], slack1);
        ok = ok && ContainsWithSlack(r.Normal[axis], s.N[axis], slack2);
      }
      ok = ok && ContainsWithSlack(r.Facing, s.F, slack3);
      ok = ok && ContainsWithSlack(r.SquaredDistance, s.G, slack2);
      ok = ok && ContainsWithSlack(r.Height, s.H, slack2);
      if (!ok && ++failures <= 3)
      {
        ADD_FAILURE() << Name(Methods[k]) << " misses a sample on " << what << ": rect [" << rect.U0
                      << ", " << rect.U1 << "] x [" << rect.V0 << ", " << rect.V1 << "], f " << s.F
                      << " in " << r.Facing << ", g " << s.G << " in " << r.SquaredDistance
                      << ", h " << s.H << " in " << r.Height;
      }
    }
  }
}

/// Random rectangles of the kinds the subdivision produces, and a few it should survive.
UVRect RandomRect(std::mt19937_64& rng, int kind)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  switch (kind % 6)
  {
    case 0:
      return UVRect::Unit();
    case 1:
    {
      // A cell of a ternary subdivision at a random level (paper §4.3, note 3).
      const int levelU = int(unit(rng) * 5);
      const int levelV = int(unit(rng) * 5);
      const double cellU = std::pow(3.0, -levelU);
      const double cellV = std::pow(3.0, -levelV);
      const double u0 = std::floor(unit(rng) / cellU) * cellU;
      const double v0 = std::floor(unit(rng) / cellV) * cellV;
      return { u0, std::min(1.0, u0 + cellU), v0, std::min(1.0, v0 + cellV) };
    }
    case 2:
    {
      // A thin strip along a boundary edge (where the teapot's poles are).
      const double w = 1e-3 * unit(rng);
      return unit(rng) < 0.5 ? UVRect{ 0.0, 1.0, 0.0, w } : UVRect{ 1.0 - w, 1.0, 0.2, 0.9 };
    }
    case 3:
    {
      // Zero width in u: an iso-parameter curve of the patch.
      const double u = unit(rng);
      return { u, u, 0.1, 0.6 };
    }
    default:
    {
      double u0 = unit(rng);
      double u1 = unit(rng);
      double v0 = unit(rng);
      double v1 = unit(rng);
      return { std::min(u0, u1), std::max(u0, u1), std::min(v0, v1), std::max(v0, v1) };
    }
  }
}

glm::dvec3 RandomPointNear(std::mt19937_64& rng, const BezierPatch& patch)
{
  std::uniform_real_distribution<double> unit(-0.5, 1.5);
  const glm::dvec3 lower = patch.Bounds().Lower();
  const glm::dvec3 extent = patch.Bounds().Upper() - lower;
  return lower + glm::dvec3(unit(rng), unit(rng), unit(rng)) * extent;
}

glm::dvec3 RandomDirection(std::mt19937_64& rng)
{
  std::normal_distribution<double> normal;
  return glm::dvec3(normal(rng), normal(rng), normal(rng));
}

TEST(BernsteinBounds, BothMethodsEncloseSampledValuesOnRandomPatches)
{
  std::mt19937_64 rng(31);
  std::vector<std::pair<int, int>> degrees = TestDegrees();
  degrees.emplace_back(15, 15);
  for (const auto& d : degrees)
  {
    for (int p = 0; p < 3; ++p)
    {
      const BezierPatch patch = RandomPatch(rng, d.first, d.second);
      const int rects = d.first == 15 ? 6 : 24;
      for (int k = 0; k < rects; ++k)
      {
        std::ostringstream what;
        what << "random degree (" << d.first << ", " << d.second << ") patch " << p;
        ExpectEnclosure(patch,
          RandomRect(rng, k),
          RandomPointNear(rng, patch),
          RandomDirection(rng),
          what.str(),
          d.first == 15 ? 16 : 32);
      }
    }
  }
}

TEST(BernsteinBounds, BothMethodsEncloseSampledValuesOnTheTeapot)
{
  std::mt19937_64 rng(32);
  const std::vector<BezierPatch>& teapot = Teapot();
  ASSERT_EQ(teapot.size(), 32u);
  for (size_t p = 0; p < teapot.size(); ++p)
  {
    for (int k = 0; k < 12; ++k)
    {
      ExpectEnclosure(teapot[p],
        RandomRect(rng, k),
        RandomPointNear(rng, teapot[p]),
        RandomDirection(rng),
        "teapot patch " + std::to_string(p));
    }
  }
}

TEST(BernsteinBounds, ExactForConstantsAndTheUnitSquare)
{
  // Unit square z = 0 with front +z: N = (0,0,1), f = N.(Q - P) = -1 for P at height 1, and
  // g = (u - 1/2)^2 + (v - 1/2)^2 + 1 ranges over exactly [1, 3/2]. The Bernstein form has
  // linear precision and finds these ranges exactly; natural evaluation only encloses them,
  // as it cannot know that B_0(U) + B_1(U) = 1 (with U = [0,1] it gets [0,2]).
  const BezierPatch square(1, 1, { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } });
  const glm::dvec3 above(0.5, 0.5, 1.0);
  const double ulps = 32 * std::numeric_limits<double>::epsilon();
  const UVRect unit = UVRect::Unit();
  const Interval f = sphcover::RangeOfFacing(square, unit, above);
  EXPECT_NEAR(f.Lower(), -1.0, ulps);
  EXPECT_NEAR(f.Upper(), -1.0, ulps);
  // f < 0: P is on the front side of the whole patch (the header's sign convention).
  EXPECT_TRUE(f.IsNegative());
  EXPECT_TRUE(sphcover::RangeOfFacing(square, unit, -above).IsPositive());
  const Interval g = sphcover::RangeOfSquaredDistance(square, unit, above);
  EXPECT_NEAR(g.Lower(), 1.0, ulps);
  EXPECT_NEAR(g.Upper(), 1.5, ulps);
  const IntervalVec3 n = sphcover::RangeOfNormal(square, unit);
  EXPECT_NEAR(n.Z.Lower(), 1.0, ulps);
  EXPECT_NEAR(n.Z.Upper(), 1.0, ulps);
  const Interval fNatural =
    sphcover::RangeOfFacing(square, unit, above, RangeMethod::NaturalInterval);
  EXPECT_TRUE(fNatural.Contains(-1.0));
  EXPECT_LE(fNatural.Lower(), -4.0);
  const Interval gNatural =
    sphcover::RangeOfSquaredDistance(square, unit, above, RangeMethod::NaturalInterval);
  EXPECT_TRUE(gNatural.Lower() <= 1.0 && 1.5 <= gNatural.Upper());
  for (RangeMethod method : Methods)
  {
    SCOPED_TRACE(Name(method));
    // Components that are identically zero stay zero up to the outward rounding of 0.
    const IntervalVec3 normal = sphcover::RangeOfNormal(square, unit, method);
    EXPECT_LE(normal.X.Magnitude(), 1e-300);
    EXPECT_LE(normal.Y.Magnitude(), 1e-300);
    // The plane of the square through a point in it: every height is 0.
    const Interval h = sphcover::RangeOfHeightAbovePlane(
      square, UVRect{ 0.2, 0.9, 0.0, 0.3 }, glm::dvec3(7, -3, 0), glm::dvec3(0, 0, 2), method);
    EXPECT_LE(h.Magnitude(), 1e-300);
  }
  // Over a whole patch the Bernstein position box is the control net's box.
  std::mt19937_64 rng(33);
  for (const auto& d : TestDegrees())
  {
    const BezierPatch patch = RandomPatch(rng, d.first, d.second);
    const IntervalVec3 box = sphcover::RangeOfPosition(patch, UVRect::Unit());
    EXPECT_EQ(box.Lower(), patch.Bounds().Lower());
    EXPECT_EQ(box.Upper(), patch.Bounds().Upper());
  }
}

TEST(BernsteinBounds, ZeroWidthRectanglesCollapseToTheValueForBernstein)
{
  // On a single parameter point the restricted nets are that point repeated, so every
  // Bernstein coefficient is the value itself.
  std::mt19937_64 rng(34);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const auto& d : TestDegrees())
  {
    const BezierPatch patch = RandomPatch(rng, d.first, d.second);
    const double u = unit(rng);
    const double v = unit(rng);
    const glm::dvec3 point = RandomPointNear(rng, patch);
    const UVRect rect{ u, u, v, v };
    const glm::dvec3 q = patch.Evaluate(u, v);
    const glm::dvec3 n = patch.UnnormalizedNormal(u, v);
    const double scale = std::max(glm::length(q - point), glm::length(n) + 1.0);
    const Interval f = sphcover::RangeOfFacing(patch, rect, point);
    EXPECT_LT(f.Width(), 1e-12 * scale * scale * scale);
    EXPECT_NEAR(f.Midpoint(), glm::dot(n, q - point), 1e-12 * scale * scale * scale);
    const Interval g = sphcover::RangeOfSquaredDistance(patch, rect, point);
    EXPECT_LT(g.Width(), 1e-12 * scale * scale);
    const IntervalVec3 normal = sphcover::RangeOfNormal(patch, rect);
    for (int axis = 0; axis < 3; ++axis)
    {
      EXPECT_LT(normal[axis].Width(), 1e-12 * scale * scale);
    }
  }
}

TEST(BernsteinBounds, InvalidRectanglesAreRejected)
{
  const BezierPatch patch = Teapot()[0];
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const glm::dvec3 p(0.0);
  for (const UVRect& rect : { UVRect{ 0.6, 0.5, 0, 1 },
         UVRect{ -0.1, 0.5, 0, 1 },
         UVRect{ 0, 1, 0.2, 1.01 },
         UVRect{ nan, 1, 0, 1 } })
  {
    for (RangeMethod method : Methods)
    {
      EXPECT_THROW(sphcover::RangeOfPosition(patch, rect, method), std::invalid_argument);
      EXPECT_THROW(sphcover::RangeOfNormal(patch, rect, method), std::invalid_argument);
      EXPECT_THROW(sphcover::RangeOfFacing(patch, rect, p, method), std::invalid_argument);
      EXPECT_THROW(sphcover::RangeOfSquaredDistance(patch, rect, p, method), std::invalid_argument);
      EXPECT_THROW(
        sphcover::RangeOfHeightAbovePlane(patch, rect, p, p, method), std::invalid_argument);
    }
  }
}

//------------------------------------------------------------------------------------------------
// Exact Bernstein coefficients in rational arithmetic, from the same restricted nets (computed
// by the same de Casteljau code, so bit for bit the doubles the implementation starts from).

using Rational = mpq_class;
using RationalVec3 = std::array<Rational, 3>;

Rational Binomial(int n, int k)
{
  mpz_class c;
  mpz_bin_uiui(c.get_mpz_t(), static_cast<unsigned long>(n), static_cast<unsigned long>(k));
  return Rational(c);
}

RationalVec3 Exact(const glm::dvec3& p)
{
  return { Rational(p.x), Rational(p.y), Rational(p.z) };
}

std::vector<RationalVec3> RestrictedExactNet(std::vector<glm::dvec3> net,
  int degreeU,
  int degreeV,
  const UVRect& rect)
{
  sphcover::RestrictNet(net.data(), degreeU, degreeV, rect);
  std::vector<RationalVec3> exact;
  for (const glm::dvec3& p : net)
  {
    exact.push_back(Exact(p));
  }
  return exact;
}

/// Exact min and max of a set of rational coefficients.
struct ExactRange
{
  Rational Lo;
  Rational Hi;
  bool Empty = true;
  void Add(const Rational& c)
  {
    if (this->Empty || c < this->Lo)
    {
      this->Lo = c;
    }
    if (this->Empty || c > this->Hi)
    {
      this->Hi = c;
    }
    this->Empty = false;
  }
};

/// The exact coefficient ranges of N (per axis), f, g (and of each squared axis of g).
struct ExactCoefficientRanges
{
  ExactRange Normal[3];
  ExactRange Facing;
  ExactRange SquaredDistance;
  ExactRange SquaredAxis[3];
  ExactRange Height;
};

ExactCoefficientRanges ExactRanges(const BezierPatch& patch,
  const UVRect& rect,
  const glm::dvec3& point,
  const glm::dvec3& planeNormal)
{
  const int m = patch.DegreeU();
  const int n = patch.DegreeV();
  const std::vector<RationalVec3> du = RestrictedExactNet(patch.DerivativeNetU(), m - 1, n, rect);
  const std::vector<RationalVec3> dv = RestrictedExactNet(patch.DerivativeNetV(), m, n - 1, rect);
  std::vector<RationalVec3> offset = RestrictedExactNet(patch.ControlPoints(), m, n, rect);
  const RationalVec3 p = Exact(point);
  for (RationalVec3& q : offset)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      q[axis] -= p[axis];
    }
  }
  // Scaled basis: products of polynomials are convolutions of C(d,i)-weighted coefficients.
  const int normalRow = 2 * m;
  std::vector<RationalVec3> normal(static_cast<size_t>(4 * m * n), { 0, 0, 0 });
  for (int j1 = 0; j1 <= n; ++j1)
  {
    for (int i1 = 0; i1 < m; ++i1)
    {
      const RationalVec3& a = du[size_t(j1 * m + i1)];
      const Rational wa = Binomial(m - 1, i1) * Binomial(n, j1);
      for (int j2 = 0; j2 < n; ++j2)
      {
        for (int i2 = 0; i2 <= m; ++i2)
        {
          const RationalVec3& b = dv[size_t(j2 * (m + 1) + i2)];
          const Rational w = wa * Binomial(m, i2) * Binomial(n - 1, j2);
          RationalVec3& c = normal[size_t((j1 + j2) * normalRow + i1 + i2)];
          c[0] += w * (a[1] * b[2] - a[2] * b[1]);
          c[1] += w * (a[2] * b[0] - a[0] * b[2]);
          c[2] += w * (a[0] * b[1] - a[1] * b[0]);
        }
      }
    }
  }
  ExactCoefficientRanges ranges;
  const RationalVec3 direction = Exact(planeNormal);
  for (const RationalVec3& q : offset)
  {
    ranges.Height.Add(direction[0] * q[0] + direction[1] * q[1] + direction[2] * q[2]);
  }
  for (int J = 0; J < 2 * n; ++J)
  {
    for (int I = 0; I < 2 * m; ++I)
    {
      const Rational divisor = Binomial(2 * m - 1, I) * Binomial(2 * n - 1, J);
      for (int axis = 0; axis < 3; ++axis)
      {
        ranges.Normal[axis].Add(normal[size_t(J * normalRow + I)][axis] / divisor);
      }
    }
  }
  for (int L = 0; L < 3 * n; ++L)
  {
    for (int K = 0; K < 3 * m; ++K)
    {
      Rational sum = 0;
      for (int J = std::max(0, L - n); J <= std::min(2 * n - 1, L); ++J)
      {
        for (int I = std::max(0, K - m); I <= std::min(2 * m - 1, K); ++I)
        {
          const RationalVec3& a = normal[size_t(J * normalRow + I)];
          const RationalVec3& b = offset[size_t((L - J) * (m + 1) + K - I)];
          sum +=
            Binomial(m, K - I) * Binomial(n, L - J) * (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
        }
      }
      ranges.Facing.Add(sum / (Binomial(3 * m - 1, K) * Binomial(3 * n - 1, L)));
    }
  }
  for (int L = 0; L <= 2 * n; ++L)
  {
    for (int K = 0; K <= 2 * m; ++K)
    {
      RationalVec3 sum = { 0, 0, 0 };
      for (int ja = std::max(0, L - n); ja <= std::min(n, L); ++ja)
      {
        for (int ia = std::max(0, K - m); ia <= std::min(m, K); ++ia)
        {
          const RationalVec3& a = offset[size_t(ja * (m + 1) + ia)];
          const RationalVec3& b = offset[size_t((L - ja) * (m + 1) + K - ia)];
          const Rational w =
            Binomial(m, ia) * Binomial(n, ja) * Binomial(m, K - ia) * Binomial(n, L - ja);
          for (int axis = 0; axis < 3; ++axis)
          {
            sum[axis] += w * a[axis] * b[axis];
          }
        }
      }
      const Rational divisor = Binomial(2 * m, K) * Binomial(2 * n, L);
      for (int axis = 0; axis < 3; ++axis)
      {
        ranges.SquaredAxis[axis].Add(sum[axis] / divisor);
      }
      ranges.SquaredDistance.Add((sum[0] + sum[1] + sum[2]) / divisor);
    }
  }
  return ranges;
}

/// The bound must contain [lo, hi] (exactly, compared as rationals) and exceed it by at most
/// `tightness`.
void ExpectRigorousAndTight(const Interval& bound,
  const Rational& lo,
  const Rational& hi,
  double tightness,
  const std::string& what)
{
  EXPECT_TRUE(Rational(bound.Lower()) <= lo && hi <= Rational(bound.Upper()))
    << what << ": " << bound << " does not contain [" << lo.get_d() << ", " << hi.get_d()
    << "] (exact coefficient range)";
  EXPECT_LE(lo.get_d() - bound.Lower(), tightness) << what;
  EXPECT_LE(bound.Upper() - hi.get_d(), tightness) << what;
}

void ExpectRigorousBernstein(const BezierPatch& patch,
  const UVRect& rect,
  const glm::dvec3& point,
  const glm::dvec3& planeNormal,
  const std::string& what)
{
  const ExactCoefficientRanges exact = ExactRanges(patch, rect, point, planeNormal);
  // Tightness scale: the largest |Qu|, |Qv|, |Q - P| over the net, as in the enclosure test.
  double scale = 1.0;
  for (const glm::dvec3& p : patch.ControlPoints())
  {
    scale = std::max(scale, glm::length(p - point));
  }
  for (const glm::dvec3& d : patch.DerivativeNetU())
  {
    scale = std::max(scale, glm::length(d));
  }
  for (const glm::dvec3& d : patch.DerivativeNetV())
  {
    scale = std::max(scale, glm::length(d));
  }
  const double slack2 = 1e-12 * scale * scale;
  const IntervalVec3 normal = sphcover::RangeOfNormal(patch, rect);
  for (int axis = 0; axis < 3; ++axis)
  {
    ExpectRigorousAndTight(normal[axis],
      exact.Normal[axis].Lo,
      exact.Normal[axis].Hi,
      slack2,
      what + " normal axis " + std::to_string(axis));
  }
  ExpectRigorousAndTight(sphcover::RangeOfFacing(patch, rect, point),
    exact.Facing.Lo,
    exact.Facing.Hi,
    slack2 * scale,
    what + " facing");
  // The squared distance intersects the range of g's coefficients with the sum of the
  // clipped ranges of its three squared coordinates.
  Rational axisLo = 0;
  Rational axisHi = 0;
  for (const ExactRange& r : exact.SquaredAxis)
  {
    axisLo += std::max(r.Lo, Rational(0));
    axisHi += std::max(r.Hi, Rational(0));
  }
  const Rational gLo = std::max({ exact.SquaredDistance.Lo, axisLo, Rational(0) });
  const Rational gHi = std::min(exact.SquaredDistance.Hi, axisHi);
  ExpectRigorousAndTight(
    sphcover::RangeOfSquaredDistance(patch, rect, point), gLo, gHi, slack2, what + " g");
  ExpectRigorousAndTight(sphcover::RangeOfHeightAbovePlane(patch, rect, point, planeNormal),
    exact.Height.Lo,
    exact.Height.Hi,
    slack2 * glm::length(planeNormal),
    what + " h");
}

TEST(BernsteinBounds, BernsteinBoundsContainTheExactCoefficientRange)
{
  std::mt19937_64 rng(37);
  std::vector<std::pair<int, int>> degrees = TestDegrees();
  for (const auto& d : degrees)
  {
    const int cases = d.first == 7 && d.second == 7 ? 2 : 8;
    for (int k = 0; k < cases; ++k)
    {
      const BezierPatch patch = RandomPatch(rng, d.first, d.second);
      ExpectRigorousBernstein(patch,
        RandomRect(rng, k),
        RandomPointNear(rng, patch),
        RandomDirection(rng),
        "degree (" + std::to_string(d.first) + ", " + std::to_string(d.second) + ")");
    }
  }
  for (size_t p = 0; p < Teapot().size(); ++p)
  {
    ExpectRigorousBernstein(Teapot()[p],
      RandomRect(rng, int(p)),
      RandomPointNear(rng, Teapot()[p]),
      RandomDirection(rng),
      "teapot patch " + std::to_string(p));
  }
  // The hardest case for a sign test: a flat patch whose coordinates are not representable
  // (so it is planar only up to rounding) and a point in its plane. The exact coefficients of
  // f and of the height above the patch's own plane are tiny, of either sign; the bounds must
  // still contain them.
  const glm::dvec3 e1(0.1, 0.7, 0.3);
  const glm::dvec3 e2(-0.3, 0.2, 0.9);
  const glm::dvec3 o(1.1, 2.3, -0.7);
  std::vector<glm::dvec3> flat;
  for (int j = 0; j <= 3; ++j)
  {
    for (int i = 0; i <= 3; ++i)
    {
      flat.push_back(o + (i / 3.0 + 0.05 * j * j) * e1 + (j / 3.0 - 0.04 * i * j) * e2);
    }
  }
  const BezierPatch plane(3, 3, flat);
  const glm::dvec3 planeNormal = glm::cross(e1, e2);
  ExpectRigorousBernstein(
    plane, UVRect::Unit(), o + 2.0 * e1 - 0.7 * e2, planeNormal, "flat patch");
  ExpectRigorousBernstein(
    plane, UVRect{ 0.1, 0.2, 0.5, 0.9 }, o + 0.3 * e1, planeNormal, "flat patch");
}

/// width(bernstein) <= width(natural), up to the outward rounding of either.
bool NotWider(const Interval& bernstein, const Interval& natural)
{
  return bernstein.Width() <= natural.Width() * (1.0 + 1e-9) + 1e-300;
}

TEST(BernsteinBounds, BernsteinIsNeverWiderThanNaturalOnTheTeapot)
{
  std::mt19937_64 rng(35);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::vector<BezierPatch>& teapot = Teapot();
  // Mean width ratio Bernstein / natural for f, per ternary subdivision level (cells of side
  // 3^-level, paper §4.3 note 3) and over all levels.
  constexpr int Levels = 5;
  double ratioSum[Levels] = {};
  int ratioCount[Levels] = {};
  double allSum = 0.0;
  int allCount = 0;
  for (const BezierPatch& patch : teapot)
  {
    for (int k = 0; k < 100; ++k)
    {
      const int level = k % Levels;
      const double cell = std::pow(3.0, -level);
      const double u0 = std::floor(unit(rng) / cell) * cell;
      const double v0 = std::floor(unit(rng) / cell) * cell;
      const UVRect rect{ u0, std::min(1.0, u0 + cell), v0, std::min(1.0, v0 + cell) };
      const glm::dvec3 point = RandomPointNear(rng, patch);
      const glm::dvec3 plane = RandomDirection(rng);
      const Ranges b = ComputeRanges(patch, rect, point, plane, RangeMethod::Bernstein);
      const Ranges n = ComputeRanges(patch, rect, point, plane, RangeMethod::NaturalInterval);
      EXPECT_TRUE(NotWider(b.Facing, n.Facing)) << b.Facing << " vs " << n.Facing;
      EXPECT_TRUE(NotWider(b.SquaredDistance, n.SquaredDistance))
        << b.SquaredDistance << " vs " << n.SquaredDistance;
      EXPECT_TRUE(NotWider(b.Height, n.Height)) << b.Height << " vs " << n.Height;
      for (int axis = 0; axis < 3; ++axis)
      {
        EXPECT_TRUE(NotWider(b.Position[axis], n.Position[axis]));
        EXPECT_TRUE(NotWider(b.Normal[axis], n.Normal[axis]));
      }
      if (n.Facing.Width() > 0.0)
      {
        const double ratio = b.Facing.Width() / n.Facing.Width();
        ratioSum[level] += ratio;
        ++ratioCount[level];
        allSum += ratio;
        ++allCount;
      }
    }
  }
  ASSERT_GT(allCount, 0);
  const double mean = allSum / allCount;
  std::ostringstream perLevel;
  perLevel << std::setprecision(3);
  for (int level = 0; level < Levels; ++level)
  {
    perLevel << (level ? " " : "") << ratioSum[level] / std::max(1, ratioCount[level]);
  }
  std::cout << "[ teapot  ] mean width ratio Bernstein/natural of f (paper 4.2.1) over " << allCount
            << " rectangles: " << std::fixed << std::setprecision(3) << mean
            << "; per ternary level 0.." << Levels - 1 << ": " << perLevel.str() << std::endl;
  RecordProperty("FacingWidthRatioBernsteinOverNatural", std::to_string(mean));
  RecordProperty("FacingWidthRatioPerTernaryLevel", perLevel.str());
  EXPECT_LT(mean, 1.0);
}

/// Width of the range of g = |Q - P|^2 sampled densely on the rectangle.
double SampledSquaredDistanceWidth(const BezierPatch& patch,
  const UVRect& rect,
  const glm::dvec3& point)
{
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  const int samples = 32;
  for (int b = 0; b <= samples; ++b)
  {
    for (int a = 0; a <= samples; ++a)
    {
      const double u = rect.U0 + (rect.U1 - rect.U0) * a / samples;
      const double v = rect.V0 + (rect.V1 - rect.V0) * b / samples;
      const glm::dvec3 d = patch.Evaluate(u, v) - point;
      lo = std::min(lo, glm::dot(d, d));
      hi = std::max(hi, glm::dot(d, d));
    }
  }
  return hi - lo;
}

TEST(BernsteinBounds, BernsteinExcessShrinksQuadraticallyNaturalLinearly)
{
  // P sits on the normal line of Q(u*,v*), so g = |Q - P|^2 has a critical point there and its
  // range over the square of half-side d around (u*,v*) has width O(d^2). Bernstein
  // coefficients differ from the function by O(d^2), so the excess width of the Bernstein
  // bound shrinks by 4 per halving of d; natural interval evaluation overestimates by O(d),
  // so its excess shrinks by 2. (Where f or g is monotone over a small rectangle the
  // Bernstein bound is exact up to rounding: its extreme coefficients are the corner values.)
  std::mt19937_64 rng(36);
  std::uniform_real_distribution<double> centre(0.3, 0.7);
  for (int trial = 0; trial < 6; ++trial)
  {
    const BezierPatch patch = RandomPatch(rng, 3, 3);
    const double u = centre(rng);
    const double v = centre(rng);
    const glm::dvec3 point = patch.Evaluate(u, v) + 0.5 * patch.Normal(u, v);
    double previous[2] = { 0.0, 0.0 };
    for (int halving = 0; halving < 4; ++halving)
    {
      const double half = 0.005 * std::pow(0.5, halving);
      const UVRect rect{ u - half, u + half, v - half, v + half };
      const double sampled = SampledSquaredDistanceWidth(patch, rect, point);
      const double excess[2] = {
        sphcover::RangeOfSquaredDistance(patch, rect, point, RangeMethod::Bernstein).Width() -
          sampled,
        sphcover::RangeOfSquaredDistance(patch, rect, point, RangeMethod::NaturalInterval).Width() -
          sampled
      };
      if (halving > 0)
      {
        EXPECT_NEAR(excess[0] / previous[0], 0.25, 0.02) << "trial " << trial;
        if (halving == 3)
        {
          EXPECT_NEAR(excess[1] / previous[1], 0.5, 0.05) << "trial " << trial;
        }
      }
      previous[0] = excess[0];
      previous[1] = excess[1];
    }
  }
}

} // namespace
