// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/BernsteinBounds.h"

#include "geometry/DeCasteljau.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>

namespace sphcover
{

namespace
{

// ---------------------------------------------------------------------------------------------
// Binomial coefficients up to the degree of the facing function, 3*15 - 1 = 44. All of them
// (C(45,22) ~ 4.1e12) are integers below 2^53, so the table is exact.
constexpr int MaxProductDegree = 3 * BezierPatch::MaxDegree;

struct BinomialTable
{
  double Value[MaxProductDegree + 1][MaxProductDegree + 1];
};

constexpr BinomialTable MakeBinomialTable()
{
  BinomialTable table{};
  for (int n = 0; n <= MaxProductDegree; ++n)
  {
    table.Value[n][0] = 1.0;
    table.Value[n][n] = 1.0;
    for (int k = 1; k < n; ++k)
    {
      table.Value[n][k] = table.Value[n - 1][k - 1] + table.Value[n - 1][k];
    }
  }
  return table;
}

constexpr BinomialTable Binomials = MakeBinomialTable();

inline double Binomial(int n, int k)
{
  return Binomials.Value[n][k];
}

void CheckRect(const UVRect& rect)
{
  if (!rect.IsValid())
  {
    throw std::invalid_argument("range bounds need 0 <= U0 <= U1 <= 1 and 0 <= V0 <= V1 <= 1, "
                                "got [" +
      std::to_string(rect.U0) + ", " + std::to_string(rect.U1) + "] x [" + std::to_string(rect.V0) +
      ", " + std::to_string(rect.V1) + "]");
  }
}

/// p - q with outward rounding.
inline IntervalVec3 Difference(const glm::dvec3& p, const glm::dvec3& q)
{
  return IntervalVec3(p) - IntervalVec3(q);
}

// ---------------------------------------------------------------------------------------------
// Rounding-error bounds for the Bernstein coefficients.
//
// The coefficients are sums of products of the restricted nets, computed in plain double
// arithmetic; an a-priori bound on their rounding error then widens the final min/max. This is
// exactly as rigorous as evaluating every operation in Interval arithmetic, at a small fraction
// of the cost (Interval rounds every operation outward with two calls of nextafter; for a
// bicubic patch the facing function has 81 coefficients built from some 3500 products, and the
// interval version took about 50 times longer).
//
// Model (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed., §2.2, Lemma 3.1):
// each operation gives fl(x op y) = (x op y)(1 + delta), |delta| <= u = 2^-53, and a product
// of k factors (1 + delta_i)^(+-1) is 1 + theta with |theta| <= gamma_k = k u / (1 - k u). A
// computed sum of terms t, each of which went through at most k roundings, therefore differs
// from the exact sum by at most gamma_k sum |t| (fused multiply-adds only remove roundings).
// Every term here is a product of exact input coordinates (the restricted nets and the point)
// and exact integer weights; the weights of one coefficient sum to its divisor (Vandermonde's
// identity), so sum |t| / divisor is at most the same product of the largest input magnitudes,
// per coordinate. A product or quotient that underflows errs by at most 2^-1075 in absolute
// terms instead; UnderflowAllowance bounds the effect of all of them. A result that overflows
// is not finite and gives the whole real line.

constexpr double UnitRoundoff = 0x1p-53;

/**
 * An upper bound of gamma_k for the allowances below. For k < 10^6, k u < 1.2e-10, so
 * gamma_k < k u (1 + 2.4e-10); the factor 1 + 1e-6 covers that and, with a wide margin, the
 * relative rounding (a few u) of the non-negative products and sums that form an allowance and
 * of the magnitudes of Q - P taken from computed differences (within 2u of the exact ones).
 */
double GammaBound(int roundings)
{
  return roundings * UnitRoundoff * (1.0 + 1e-6);
}

/**
 * Upper bound of the absolute error caused by underflow: at most `operations` underflowing
 * products or quotients per elementary term, each erring by at most 2^-1075 and then
 * multiplied by at most the largest magnitudes of the other factors.
 */
double UnderflowAllowance(double terms, double operations, std::initializer_list<double> factors)
{
  double bound = terms * operations;
  for (const double f : factors)
  {
    bound *= 1.0 + f;
  }
  // Scale last (a product >= 1 above rounds by a relative u); 2^-1073 instead of 2^-1075 leaves
  // room for the rounding of a subnormal result (at most 2^-1075 absolute).
  return bound * 0x1p-1073;
}

/// gamma_roundings * magnitude + underflow, an upper bound (see GammaBound).
double RoundingAllowance(int roundings, double magnitude, double underflow)
{
  return GammaBound(roundings) * magnitude + underflow;
}

/// [lo - allowance, hi + allowance] rounded outward; the whole line if anything overflowed.
Interval Widened(double lo, double hi, double allowance, bool finite)
{
  if (!finite || !std::isfinite(lo) || !std::isfinite(hi) || !std::isfinite(allowance))
  {
    return Interval::Entire();
  }
  return { (Interval(lo) - Interval(allowance)).Lower(),
    (Interval(hi) + Interval(allowance)).Upper() };
}

/// Running min/max of computed coefficients, remembering whether all were finite.
struct CoefficientHull
{
  double Lo = std::numeric_limits<double>::infinity();
  double Hi = -std::numeric_limits<double>::infinity();
  bool Finite = true;
  void Add(double c)
  {
    this->Finite = this->Finite && std::isfinite(c);
    this->Lo = std::min(this->Lo, c);
    this->Hi = std::max(this->Hi, c);
  }
};

inline glm::dvec3 MaxAbs(const glm::dvec3& a, const glm::dvec3& b)
{
  return glm::max(a, glm::abs(b));
}

inline double MaxComponent(const glm::dvec3& a)
{
  return std::max({ a.x, a.y, a.z });
}

// ---------------------------------------------------------------------------------------------
// Bernstein (convex-hull) form. Polynomials are kept in the scaled Bernstein basis
// C(p,a) B_a^p, in which a product of polynomials is a plain convolution of coefficients; the
// true coefficients are recovered by one division per coefficient at the end. `Capacity` sizes
// the stack buffers (the smallest of 3, 7, 15 that holds the patch's degrees), so the common
// bicubic case touches little memory.

/// Control nets of Q, Qu and Qv restricted to the rectangle, in doubles.
template<int Capacity>
struct RestrictedNets
{
  glm::dvec3 Position[(Capacity + 1) * (Capacity + 1)];
  glm::dvec3 DerivativeU[Capacity * (Capacity + 1)];
  glm::dvec3 DerivativeV[(Capacity + 1) * Capacity];

  void RestrictPosition(const BezierPatch& patch, const UVRect& rect)
  {
    std::copy(patch.ControlPoints().begin(), patch.ControlPoints().end(), this->Position);
    RestrictNet(this->Position, patch.DegreeU(), patch.DegreeV(), rect);
  }

  /// The hodographs restricted to the rectangle are the derivative nets of the restricted
  /// patch in the ORIGINAL parameters (no division by the rectangle size, so zero-width
  /// rectangles work and small ones do not cancel).
  void RestrictDerivatives(const BezierPatch& patch, const UVRect& rect)
  {
    std::copy(patch.DerivativeNetU().begin(), patch.DerivativeNetU().end(), this->DerivativeU);
    RestrictNet(this->DerivativeU, patch.DegreeU() - 1, patch.DegreeV(), rect);
    std::copy(patch.DerivativeNetV().begin(), patch.DerivativeNetV().end(), this->DerivativeV);
    RestrictNet(this->DerivativeV, patch.DegreeU(), patch.DegreeV() - 1, rect);
  }
};

/// Scaled Bernstein coefficients of N = Qu x Qv, degree (2m-1, 2n-1), and the magnitudes the
/// rounding-error bounds need.
template<int Capacity>
struct NormalProduct
{
  glm::dvec3 Coefficients[4 * Capacity * Capacity]; // index J*2m + I
  glm::dvec3 MaxU{ 0.0 };                           // per coordinate max |Qu_ij|
  glm::dvec3 MaxV{ 0.0 };                           // per coordinate max |Qv_ij|
  double MaxScaledU = 0.0;
  double MaxScaledV = 0.0;

  /// The convolution of C(m-1,i)C(n,j) Qu_ij with C(m,i)C(n-1,j) Qv_ij under the cross
  /// product. Each term goes through 4 roundings (two weights, product, difference) and at
  /// most m(n+1) accumulations.
  NormalProduct(const RestrictedNets<Capacity>& nets, int m, int n)
  {
    glm::dvec3 scaledU[Capacity * (Capacity + 1)];
    glm::dvec3 scaledV[(Capacity + 1) * Capacity];
    glm::dvec3 maxScaled(0.0);
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i < m; ++i)
      {
        const glm::dvec3& d = nets.DerivativeU[j * m + i];
        this->MaxU = MaxAbs(this->MaxU, d);
        scaledU[j * m + i] = (Binomial(m - 1, i) * Binomial(n, j)) * d;
        maxScaled = MaxAbs(maxScaled, scaledU[j * m + i]);
      }
    }
    this->MaxScaledU = MaxComponent(maxScaled);
    maxScaled = glm::dvec3(0.0);
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i <= m; ++i)
      {
        const glm::dvec3& d = nets.DerivativeV[j * (m + 1) + i];
        this->MaxV = MaxAbs(this->MaxV, d);
        scaledV[j * (m + 1) + i] = (Binomial(m, i) * Binomial(n - 1, j)) * d;
        maxScaled = MaxAbs(maxScaled, scaledV[j * (m + 1) + i]);
      }
    }
    this->MaxScaledV = MaxComponent(maxScaled);
    const int rowLength = 2 * m;
    std::fill(this->Coefficients, this->Coefficients + rowLength * 2 * n, glm::dvec3(0.0));
    for (int j1 = 0; j1 <= n; ++j1)
    {
      for (int i1 = 0; i1 < m; ++i1)
      {
        const glm::dvec3 a = scaledU[j1 * m + i1];
        for (int j2 = 0; j2 < n; ++j2)
        {
          glm::dvec3* row = this->Coefficients + (j1 + j2) * rowLength + i1;
          const glm::dvec3* b = scaledV + j2 * (m + 1);
          for (int i2 = 0; i2 <= m; ++i2)
          {
            row[i2] += glm::dvec3(a.y * b[i2].z - a.z * b[i2].y,
              a.z * b[i2].x - a.x * b[i2].z,
              a.x * b[i2].y - a.y * b[i2].x);
          }
        }
      }
    }
  }
};

/// Scaled Bernstein coefficients C(m,i)C(n,j) (Q_ij - P) of Q - P, degree (m, n); each has
/// gone through 2 roundings (difference, weight).
template<int Capacity>
struct OffsetNet
{
  glm::dvec3 Coefficients[(Capacity + 1) * (Capacity + 1)];
  glm::dvec3 MaxOffset{ 0.0 }; // per coordinate max |fl(Q_ij - P)|
  double MaxScaled = 0.0;

  OffsetNet(const RestrictedNets<Capacity>& nets, int m, int n, const glm::dvec3& point)
  {
    glm::dvec3 maxScaled(0.0);
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i <= m; ++i)
      {
        const int k = j * (m + 1) + i;
        const glm::dvec3 offset = nets.Position[k] - point;
        this->MaxOffset = MaxAbs(this->MaxOffset, offset);
        this->Coefficients[k] = (Binomial(m, i) * Binomial(n, j)) * offset;
        maxScaled = MaxAbs(maxScaled, this->Coefficients[k]);
      }
    }
    this->MaxScaled = MaxComponent(maxScaled);
  }
};

template<int Capacity>
struct BernsteinKernels
{
  static IntervalVec3 Position(const BezierPatch& patch, const UVRect& rect)
  {
    // The restricted control points are the Bernstein coefficients themselves.
    RestrictedNets<Capacity> nets;
    nets.RestrictPosition(patch, rect);
    const int count = (patch.DegreeU() + 1) * (patch.DegreeV() + 1);
    glm::dvec3 lower = nets.Position[0];
    glm::dvec3 upper = nets.Position[0];
    for (int k = 1; k < count; ++k)
    {
      lower = glm::min(lower, nets.Position[k]);
      upper = glm::max(upper, nets.Position[k]);
    }
    return { Interval(lower.x, upper.x), Interval(lower.y, upper.y), Interval(lower.z, upper.z) };
  }

  static IntervalVec3 Normal(const BezierPatch& patch, const UVRect& rect)
  {
    const int m = patch.DegreeU();
    const int n = patch.DegreeV();
    RestrictedNets<Capacity> nets;
    nets.RestrictDerivatives(patch, rect);
    const NormalProduct<Capacity> normal(nets, m, n);
    CoefficientHull hull[3];
    for (int J = 0; J < 2 * n; ++J)
    {
      for (int I = 0; I < 2 * m; ++I)
      {
        const double divisor = Binomial(2 * m - 1, I) * Binomial(2 * n - 1, J);
        const glm::dvec3 c = normal.Coefficients[J * 2 * m + I] / divisor;
        hull[0].Add(c.x);
        hull[1].Add(c.y);
        hull[2].Add(c.z);
      }
    }
    // Roundings per term: 4 in the cross product, m(n+1) accumulations, divisor and division.
    const int roundings = 6 + m * (n + 1);
    const double terms = 2.0 * (m * (n + 1)) * ((m + 1) * n);
    const double underflow =
      UnderflowAllowance(terms, 4.0, { normal.MaxScaledU, normal.MaxScaledV });
    const glm::dvec3& a = normal.MaxU;
    const glm::dvec3& b = normal.MaxV;
    const double magnitude[3] = {
      a.y * b.z + a.z * b.y, a.z * b.x + a.x * b.z, a.x * b.y + a.y * b.x
    };
    IntervalVec3 result;
    for (int axis = 0; axis < 3; ++axis)
    {
      result[axis] = Widened(hull[axis].Lo,
        hull[axis].Hi,
        RoundingAllowance(roundings, magnitude[axis], underflow),
        hull[axis].Finite);
    }
    return result;
  }

  static Interval Facing(const BezierPatch& patch, const UVRect& rect, const glm::dvec3& point)
  {
    const int m = patch.DegreeU();
    const int n = patch.DegreeV();
    RestrictedNets<Capacity> nets;
    nets.RestrictPosition(patch, rect);
    nets.RestrictDerivatives(patch, rect);
    const NormalProduct<Capacity> normal(nets, m, n);
    const OffsetNet<Capacity> offset(nets, m, n, point);

    // f = N . (Q - P), degree (3m-1, 3n-1): coefficient (K, L) gathers the products of normal
    // coefficient (I, J) and offset coefficient (K-I, L-J).
    CoefficientHull hull;
    const int normalRow = 2 * m;
    for (int L = 0; L < 3 * n; ++L)
    {
      const int jBegin = std::max(0, L - n);
      const int jEnd = std::min(2 * n - 1, L);
      for (int K = 0; K < 3 * m; ++K)
      {
        const int iBegin = std::max(0, K - m);
        const int iEnd = std::min(2 * m - 1, K);
        double sum = 0.0;
        for (int J = jBegin; J <= jEnd; ++J)
        {
          const glm::dvec3* normalRowJ = normal.Coefficients + J * normalRow;
          const glm::dvec3* offsetRow = offset.Coefficients + (L - J) * (m + 1);
          for (int I = iBegin; I <= iEnd; ++I)
          {
            sum += glm::dot(normalRowJ[I], offsetRow[K - I]);
          }
        }
        hull.Add(sum / (Binomial(3 * m - 1, K) * Binomial(3 * n - 1, L)));
      }
    }
    // Roundings per term: 4 in N's terms, at most m(n+1) accumulations into N, 2 in Q - P and
    // its weight, 3 in the dot product, at most (m+1)(n+1) accumulations, divisor and division.
    const int roundings = 11 + m * (n + 1) + (m + 1) * (n + 1);
    const double terms = 6.0 * (m * (n + 1)) * ((m + 1) * n) * ((m + 1) * (n + 1));
    const double underflow =
      UnderflowAllowance(terms, 6.0, { normal.MaxScaledU, normal.MaxScaledV, offset.MaxScaled });
    // sum over the 6 terms of the determinant [Qu, Qv, Q - P] of |products| <= the permanent
    // of the per-coordinate maxima.
    const glm::dvec3& a = normal.MaxU;
    const glm::dvec3& b = normal.MaxV;
    const glm::dvec3& c = offset.MaxOffset;
    const double permanent =
      a.x * (b.y * c.z + b.z * c.y) + a.y * (b.x * c.z + b.z * c.x) + a.z * (b.x * c.y + b.y * c.x);
    return Widened(
      hull.Lo, hull.Hi, RoundingAllowance(roundings, permanent, underflow), hull.Finite);
  }

  static Interval SquaredDistance(const BezierPatch& patch,
    const UVRect& rect,
    const glm::dvec3& point)
  {
    const int m = patch.DegreeU();
    const int n = patch.DegreeV();
    RestrictedNets<Capacity> nets;
    nets.RestrictPosition(patch, rect);
    const OffsetNet<Capacity> offset(nets, m, n, point);

    // Each squared coordinate (x(u,v) - p_x)^2, degree (2m, 2n), separately: the product of
    // coefficients a and b contributes to coefficient a + b; by symmetry a < b counts twice.
    constexpr int SquareCapacity = (2 * Capacity + 1) * (2 * Capacity + 1);
    glm::dvec3 squares[SquareCapacity];
    const int squareRow = 2 * m + 1;
    std::fill(squares, squares + squareRow * (2 * n + 1), glm::dvec3(0.0));
    const int count = (m + 1) * (n + 1);
    for (int a = 0; a < count; ++a)
    {
      const int ia = a % (m + 1);
      const int ja = a / (m + 1);
      const glm::dvec3 pa = offset.Coefficients[a];
      squares[(2 * ja) * squareRow + 2 * ia] += pa * pa;
      const glm::dvec3 twice = 2.0 * pa;
      for (int b = a + 1; b < count; ++b)
      {
        const int ib = b % (m + 1);
        const int jb = b / (m + 1);
        squares[(ja + jb) * squareRow + ia + ib] += twice * offset.Coefficients[b];
      }
    }

    // Two Bernstein enclosures, intersected: the coefficients of g itself, and the sum of the
    // coefficient ranges of the three squares, each clipped at 0 (a square is never
    // negative). The second keeps the result inside the natural interval bound when a
    // coordinate range straddles the point, where mixed products of g's coefficients go
    // negative.
    CoefficientHull total;
    CoefficientHull perAxis[3];
    for (int L = 0; L <= 2 * n; ++L)
    {
      for (int K = 0; K <= 2 * m; ++K)
      {
        const glm::dvec3 c = squares[L * squareRow + K] / (Binomial(2 * m, K) * Binomial(2 * n, L));
        perAxis[0].Add(c.x);
        perAxis[1].Add(c.y);
        perAxis[2].Add(c.z);
        total.Add(c.x + c.y + c.z);
      }
    }
    // Roundings per term: 2 per factor of Q - P (difference, weight), the product, at most
    // (m+1)(n+1) accumulations, divisor and division; the sum over the axes adds 2.
    const int roundings = 7 + (m + 1) * (n + 1);
    const double terms = double(count) * count;
    const double underflow = UnderflowAllowance(terms, 4.0, { offset.MaxScaled, offset.MaxScaled });
    const glm::dvec3& c = offset.MaxOffset;
    Interval axisSum(0.0);
    double magnitudeSum = 0.0;
    for (int axis = 0; axis < 3; ++axis)
    {
      const double magnitude = c[axis] * c[axis];
      magnitudeSum += magnitude;
      const Interval r = Widened(perAxis[axis].Lo,
        perAxis[axis].Hi,
        RoundingAllowance(roundings, magnitude, underflow),
        perAxis[axis].Finite);
      axisSum += Interval(std::max(r.Lower(), 0.0), std::max(r.Upper(), 0.0));
    }
    const Interval t = Widened(total.Lo,
      total.Hi,
      RoundingAllowance(roundings + 2, magnitudeSum, 3.0 * underflow),
      total.Finite);
    return { std::max({ t.Lower(), axisSum.Lower(), 0.0 }),
      std::max(0.0, std::min(t.Upper(), axisSum.Upper())) };
  }

  static Interval HeightAbovePlane(const BezierPatch& patch,
    const UVRect& rect,
    const glm::dvec3& planePoint,
    const glm::dvec3& planeNormal)
  {
    // Same degree (m, n) as Q: the coefficients are the heights of the restricted control
    // points, no products of polynomials needed.
    RestrictedNets<Capacity> nets;
    nets.RestrictPosition(patch, rect);
    const int count = (patch.DegreeU() + 1) * (patch.DegreeV() + 1);
    CoefficientHull hull;
    glm::dvec3 maxOffset(0.0);
    for (int k = 0; k < count; ++k)
    {
      const glm::dvec3 offset = nets.Position[k] - planePoint;
      maxOffset = MaxAbs(maxOffset, offset);
      hull.Add(glm::dot(planeNormal, offset));
    }
    // Roundings per term: the difference, the product and 2 additions.
    const glm::dvec3 weight = glm::abs(planeNormal);
    const double magnitude = glm::dot(weight, maxOffset);
    const double underflow =
      UnderflowAllowance(3.0, 1.0, { MaxComponent(weight), MaxComponent(maxOffset) });
    return Widened(hull.Lo, hull.Hi, RoundingAllowance(4, magnitude, underflow), hull.Finite);
  }
};

/// Runs Kernel<Capacity>::Call for the smallest capacity that holds the patch's degrees.
template<typename Functor>
auto DispatchOnCapacity(const BezierPatch& patch, Functor&& functor)
{
  const int degree = std::max(patch.DegreeU(), patch.DegreeV());
  if (degree <= 3)
  {
    return functor(BernsteinKernels<3>());
  }
  if (degree <= 7)
  {
    return functor(BernsteinKernels<7>());
  }
  return functor(BernsteinKernels<BezierPatch::MaxDegree>());
}

// ---------------------------------------------------------------------------------------------
// Natural interval evaluation (paper §4.1).

/// B_i^d(T) = C(d,i) T^i (1-T)^(d-i) for i = 0..d, each factor an interval.
void BernsteinBasisOnInterval(int degree, const Interval& t, Interval* basis)
{
  Interval powers[BezierPatch::MaxDegree + 1];
  Interval complementPowers[BezierPatch::MaxDegree + 1];
  // 1 - T is exactly non-negative for T in [0,1]; clip the rounding below 0.
  const Interval complement(std::max(0.0, RoundDown(1.0 - t.Upper())), RoundUp(1.0 - t.Lower()));
  powers[0] = Interval(1.0);
  complementPowers[0] = Interval(1.0);
  for (int k = 1; k <= degree; ++k)
  {
    powers[k] = powers[k - 1] * t;
    complementPowers[k] = complementPowers[k - 1] * complement;
  }
  for (int i = 0; i <= degree; ++i)
  {
    basis[i] = Interval(Binomial(degree, i)) * powers[i] * complementPowers[degree - i];
  }
}

/// sum_i basisU[i] (sum_j basisV[j] (net_ij - origin)) in interval arithmetic; without an
/// origin, of net_ij itself.
IntervalVec3 EvaluateNetOnIntervals(const glm::dvec3* net,
  int degreeU,
  int degreeV,
  const Interval* basisU,
  const Interval* basisV,
  const glm::dvec3* origin = nullptr)
{
  IntervalVec3 result(glm::dvec3(0.0));
  for (int i = 0; i <= degreeU; ++i)
  {
    IntervalVec3 column(glm::dvec3(0.0));
    for (int j = 0; j <= degreeV; ++j)
    {
      const glm::dvec3& p = net[j * (degreeU + 1) + i];
      column = column + basisV[j] * (origin ? Difference(p, *origin) : IntervalVec3(p));
    }
    result = result + basisU[i] * column;
  }
  return result;
}

/// The interval Bernstein bases a patch of degree (m, n) and its hodographs need.
struct NaturalBases
{
  Interval U[BezierPatch::MaxDegree + 1];      // degree m
  Interval ULower[BezierPatch::MaxDegree + 1]; // degree m-1
  Interval V[BezierPatch::MaxDegree + 1];      // degree n
  Interval VLower[BezierPatch::MaxDegree + 1]; // degree n-1

  NaturalBases(const BezierPatch& patch, const UVRect& rect, bool withDerivatives)
  {
    const Interval u(rect.U0, rect.U1);
    const Interval v(rect.V0, rect.V1);
    BernsteinBasisOnInterval(patch.DegreeU(), u, this->U);
    BernsteinBasisOnInterval(patch.DegreeV(), v, this->V);
    if (withDerivatives)
    {
      BernsteinBasisOnInterval(patch.DegreeU() - 1, u, this->ULower);
      BernsteinBasisOnInterval(patch.DegreeV() - 1, v, this->VLower);
    }
  }
};

IntervalVec3 NaturalPosition(const BezierPatch& patch, const NaturalBases& bases)
{
  return EvaluateNetOnIntervals(
    patch.ControlPoints().data(), patch.DegreeU(), patch.DegreeV(), bases.U, bases.V);
}

/**
 * Q - point over the rectangle, evaluated as the Bezier form with control points P_ij - point
 * (the same polynomial, since the basis sums to 1). Evaluating Q first and subtracting the
 * point afterwards would widen the result by |Q| times the excess of the basis sum (up to 2^m
 * for U = [0,1]), making the bound depend on where the origin of the scene is.
 */
IntervalVec3 NaturalOffset(const BezierPatch& patch,
  const NaturalBases& bases,
  const glm::dvec3& point)
{
  return EvaluateNetOnIntervals(
    patch.ControlPoints().data(), patch.DegreeU(), patch.DegreeV(), bases.U, bases.V, &point);
}

IntervalVec3 NaturalNormal(const BezierPatch& patch, const NaturalBases& bases)
{
  const IntervalVec3 partialU = EvaluateNetOnIntervals(
    patch.DerivativeNetU().data(), patch.DegreeU() - 1, patch.DegreeV(), bases.ULower, bases.V);
  const IntervalVec3 partialV = EvaluateNetOnIntervals(
    patch.DerivativeNetV().data(), patch.DegreeU(), patch.DegreeV() - 1, bases.U, bases.VLower);
  return Cross(partialU, partialV);
}

} // namespace

IntervalVec3 RangeOfPosition(const BezierPatch& patch, const UVRect& rect, RangeMethod method)
{
  CheckRect(rect);
  if (method == RangeMethod::NaturalInterval)
  {
    return NaturalPosition(patch, NaturalBases(patch, rect, false));
  }
  return DispatchOnCapacity(
    patch, [&](auto kernels) { return decltype(kernels)::Position(patch, rect); });
}

IntervalVec3 RangeOfNormal(const BezierPatch& patch, const UVRect& rect, RangeMethod method)
{
  CheckRect(rect);
  if (method == RangeMethod::NaturalInterval)
  {
    return NaturalNormal(patch, NaturalBases(patch, rect, true));
  }
  return DispatchOnCapacity(
    patch, [&](auto kernels) { return decltype(kernels)::Normal(patch, rect); });
}

Interval RangeOfFacing(const BezierPatch& patch,
  const UVRect& rect,
  const glm::dvec3& point,
  RangeMethod method)
{
  CheckRect(rect);
  if (method == RangeMethod::NaturalInterval)
  {
    const NaturalBases bases(patch, rect, true);
    return Dot(NaturalNormal(patch, bases), NaturalOffset(patch, bases, point));
  }
  return DispatchOnCapacity(
    patch, [&](auto kernels) { return decltype(kernels)::Facing(patch, rect, point); });
}

Interval RangeOfSquaredDistance(const BezierPatch& patch,
  const UVRect& rect,
  const glm::dvec3& point,
  RangeMethod method)
{
  CheckRect(rect);
  if (method == RangeMethod::NaturalInterval)
  {
    const NaturalBases bases(patch, rect, false);
    return SquaredLength(NaturalOffset(patch, bases, point));
  }
  return DispatchOnCapacity(
    patch, [&](auto kernels) { return decltype(kernels)::SquaredDistance(patch, rect, point); });
}

Interval RangeOfHeightAbovePlane(const BezierPatch& patch,
  const UVRect& rect,
  const glm::dvec3& planePoint,
  const glm::dvec3& planeNormal,
  RangeMethod method)
{
  CheckRect(rect);
  if (method == RangeMethod::NaturalInterval)
  {
    const NaturalBases bases(patch, rect, false);
    return Dot(IntervalVec3(planeNormal), NaturalOffset(patch, bases, planePoint));
  }
  return DispatchOnCapacity(patch,
    [&](auto kernels)
    { return decltype(kernels)::HeightAbovePlane(patch, rect, planePoint, planeNormal); });
}

} // namespace sphcover
