// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Interval.h
 * @brief Closed real intervals with outward rounding (paper §4.1).
 *
 * Every operation computes its end points in round-to-nearest IEEE double arithmetic and then
 * moves the lower end one ulp down and the upper end one ulp up. A correctly rounded result is
 * within half an ulp of the exact value, so the widened interval always encloses the exact
 * range of the operation over its operand intervals. This is cheaper and more portable than
 * switching the FPU rounding mode, which compilers do not respect across optimisations.
 *
 * Division by an interval that contains zero is not defined by the paper (§4.1); here it
 * returns the whole real line, which keeps enclosures sound for the range tests that use it.
 */
#ifndef SPHCOVER_INTERVAL_H
#define SPHCOVER_INTERVAL_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>

namespace sphcover
{

/// The next double above x (one ulp towards plus infinity); +inf and NaN pass through.
/// A bit step, not std::nextafter: the range tests make millions of these (why:
/// Documentation/notes/interval-arithmetic.md).
inline double RoundUp(double x)
{
  if (!(x < std::numeric_limits<double>::infinity())) // +inf or NaN
  {
    return x;
  }
  if (x == 0.0) // +0 or -0
  {
    return std::numeric_limits<double>::denorm_min();
  }
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  // IEEE doubles of one sign are ordered like their bit patterns: step the magnitude up for a
  // positive x, down for a negative one (-inf steps to -DBL_MAX).
  bits = x > 0.0 ? bits + 1 : bits - 1;
  std::memcpy(&x, &bits, sizeof bits);
  return x;
}

/// The next double below x (one ulp towards minus infinity); -inf and NaN pass through.
inline double RoundDown(double x)
{
  return -RoundUp(-x);
}

class Interval
{
public:
  constexpr Interval() = default;
  /// The degenerate interval [x, x]; exact, no widening.
  constexpr Interval(double x) // NOLINT(google-explicit-constructor): a real is an interval
    : Lo(x)
    , Hi(x)
  {
  }
  constexpr Interval(double lo, double hi)
    : Lo(lo)
    , Hi(hi)
  {
  }

  static Interval Entire()
  {
    return { -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity() };
  }

  constexpr double Lower() const { return this->Lo; }
  constexpr double Upper() const { return this->Hi; }
  double Width() const { return RoundUp(this->Hi - this->Lo); }
  double Midpoint() const { return 0.5 * (this->Lo + this->Hi); }
  constexpr bool Contains(double x) const { return this->Lo <= x && x <= this->Hi; }
  constexpr bool ContainsZero() const { return this->Lo <= 0.0 && 0.0 <= this->Hi; }
  /// True when every value is > 0 (resp. < 0): the sign tests of the subdivision criteria.
  constexpr bool IsPositive() const { return this->Lo > 0.0; }
  constexpr bool IsNegative() const { return this->Hi < 0.0; }
  /// Smallest |x| over the interval.
  double Mignitude() const
  {
    return this->ContainsZero() ? 0.0 : std::min(std::fabs(this->Lo), std::fabs(this->Hi));
  }
  /// Largest |x| over the interval.
  double Magnitude() const { return std::max(std::fabs(this->Lo), std::fabs(this->Hi)); }

  Interval& operator+=(const Interval& b);
  Interval& operator-=(const Interval& b);
  Interval& operator*=(const Interval& b);
  Interval& operator/=(const Interval& b);

private:
  double Lo = 0.0;
  double Hi = 0.0;
};

inline Interval operator-(const Interval& a)
{
  return { -a.Upper(), -a.Lower() }; // negation is exact
}

inline Interval operator+(const Interval& a, const Interval& b)
{
  return { RoundDown(a.Lower() + b.Lower()), RoundUp(a.Upper() + b.Upper()) };
}

inline Interval operator-(const Interval& a, const Interval& b)
{
  return { RoundDown(a.Lower() - b.Upper()), RoundUp(a.Upper() - b.Lower()) };
}

/**
 * @brief Product of two end points for the corner formula of operator*, with 0 * inf = 0.
 *
 * An infinite end stands for "unbounded", not for an element: intervals hold reals only, and
 * the hull of the exact products is still the hull of the corner products once 0 * inf counts
 * as 0 (the convention of IEEE 1788). The IEEE 754 product is NaN, which std::min and std::max
 * then drop or keep depending on argument order: [0, inf] * [0, inf] came out as [-tiny, tiny]
 * and Entire() * [0, 1] as [NaN, NaN].
 */
inline double CornerProduct(double x, double y)
{
  return (x == 0.0 || y == 0.0) ? 0.0 : x * y;
}

/**
 * @brief Quotient of two end points for the corner formula of operator/, with inf / inf = 0.
 *
 * For a divisor that excludes zero, a / b is a * (1 / b) and 1 / (+-inf) = 0; the corner
 * (+-inf) / (+-inf) is thus 0 * inf, which is 0 for the same reason as in CornerProduct. The
 * IEEE 754 quotient is NaN (Entire() / [-inf, -1] came out as [NaN, NaN]).
 */
inline double CornerQuotient(double x, double y)
{
  return (std::isinf(x) && std::isinf(y)) ? 0.0 : x / y;
}

inline Interval operator*(const Interval& a, const Interval& b)
{
  const double p0 = CornerProduct(a.Lower(), b.Lower());
  const double p1 = CornerProduct(a.Lower(), b.Upper());
  const double p2 = CornerProduct(a.Upper(), b.Lower());
  const double p3 = CornerProduct(a.Upper(), b.Upper());
  const double lo = std::min(std::min(p0, p1), std::min(p2, p3));
  const double hi = std::max(std::max(p0, p1), std::max(p2, p3));
  // Always widen, even a zero end point: a product can underflow to 0 with a non-zero exact
  // value of either sign.
  return { RoundDown(lo), RoundUp(hi) };
}

inline Interval operator/(const Interval& a, const Interval& b)
{
  if (b.ContainsZero())
  {
    return Interval::Entire();
  }
  const double q0 = CornerQuotient(a.Lower(), b.Lower());
  const double q1 = CornerQuotient(a.Lower(), b.Upper());
  const double q2 = CornerQuotient(a.Upper(), b.Lower());
  const double q3 = CornerQuotient(a.Upper(), b.Upper());
  const double lo = std::min(std::min(q0, q1), std::min(q2, q3));
  const double hi = std::max(std::max(q0, q1), std::max(q2, q3));
  return { RoundDown(lo), RoundUp(hi) };
}

inline Interval& Interval::operator+=(const Interval& b)
{
  return *this = *this + b;
}
inline Interval& Interval::operator-=(const Interval& b)
{
  return *this = *this - b;
}
inline Interval& Interval::operator*=(const Interval& b)
{
  return *this = *this * b;
}
inline Interval& Interval::operator/=(const Interval& b)
{
  return *this = *this / b;
}

/// x^2: tighter than x*x when the interval straddles zero (the result is never negative).
inline Interval Sqr(const Interval& a)
{
  const double m = a.Mignitude();
  const double M = a.Magnitude();
  // The exact square is >= 0, so a lower end that rounds to 0 stays a valid bound.
  return { std::max(RoundDown(m * m), 0.0), RoundUp(M * M) };
}

/// sqrt over the non-negative part of the interval; negative parts are clipped to 0
/// (rounding noise can make a squared length slightly negative).
inline Interval Sqrt(const Interval& a)
{
  const double lo = std::max(a.Lower(), 0.0);
  const double hi = std::max(a.Upper(), 0.0);
  const double slo = std::sqrt(lo);
  return { slo == 0.0 ? 0.0 : RoundDown(slo), RoundUp(std::sqrt(hi)) };
}

inline Interval Hull(const Interval& a, const Interval& b)
{
  return { std::min(a.Lower(), b.Lower()), std::max(a.Upper(), b.Upper()) };
}

inline std::ostream& operator<<(std::ostream& os, const Interval& a)
{
  return os << '[' << a.Lower() << ", " << a.Upper() << ']';
}

} // namespace sphcover

#endif
