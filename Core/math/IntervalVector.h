// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file IntervalVector.h
 * @brief 3-vectors of intervals: an axis-aligned box that encloses a set of points or vectors.
 *
 * The subdivision criteria of paper §4.2 are dot and cross products of positions and normals
 * whose ranges over a sub-patch are known only as intervals; these are their enclosures.
 */
#ifndef SPHCOVER_INTERVALVECTOR_H
#define SPHCOVER_INTERVALVECTOR_H

#include "math/Interval.h"

#include <algorithm>

#include <glm/vec3.hpp>

namespace sphcover
{

struct IntervalVec3
{
  Interval X;
  Interval Y;
  Interval Z;

  IntervalVec3() = default;
  IntervalVec3(const Interval& x, const Interval& y, const Interval& z)
    : X(x)
    , Y(y)
    , Z(z)
  {
  }
  /// The degenerate box around one point.
  explicit IntervalVec3(const glm::dvec3& p)
    : X(p.x)
    , Y(p.y)
    , Z(p.z)
  {
  }

  const Interval& operator[](int i) const
  {
    return i == 0 ? this->X : (i == 1 ? this->Y : this->Z);
  }
  Interval& operator[](int i) { return i == 0 ? this->X : (i == 1 ? this->Y : this->Z); }

  glm::dvec3 Lower() const { return { this->X.Lower(), this->Y.Lower(), this->Z.Lower() }; }
  glm::dvec3 Upper() const { return { this->X.Upper(), this->Y.Upper(), this->Z.Upper() }; }
  bool Contains(const glm::dvec3& p) const
  {
    return this->X.Contains(p.x) && this->Y.Contains(p.y) && this->Z.Contains(p.z);
  }
};

inline IntervalVec3 operator+(const IntervalVec3& a, const IntervalVec3& b)
{
  return { a.X + b.X, a.Y + b.Y, a.Z + b.Z };
}

inline IntervalVec3 operator-(const IntervalVec3& a, const IntervalVec3& b)
{
  return { a.X - b.X, a.Y - b.Y, a.Z - b.Z };
}

inline IntervalVec3 operator-(const IntervalVec3& a)
{
  return { -a.X, -a.Y, -a.Z };
}

inline IntervalVec3 operator*(const Interval& s, const IntervalVec3& a)
{
  return { s * a.X, s * a.Y, s * a.Z };
}

inline Interval Dot(const IntervalVec3& a, const IntervalVec3& b)
{
  return a.X * b.X + a.Y * b.Y + a.Z * b.Z;
}

inline IntervalVec3 Cross(const IntervalVec3& a, const IntervalVec3& b)
{
  return { a.Y * b.Z - a.Z * b.Y, a.Z * b.X - a.X * b.Z, a.X * b.Y - a.Y * b.X };
}

/// |a|^2 with Sqr per component, tighter than Dot(a, a) for boxes straddling an axis plane.
inline Interval SquaredLength(const IntervalVec3& a)
{
  // A sum of squares is never negative: the outward widening of 0 + 0 may not pass below 0.
  const Interval sum = Sqr(a.X) + Sqr(a.Y) + Sqr(a.Z);
  return { std::max(sum.Lower(), 0.0), sum.Upper() };
}

inline IntervalVec3 Hull(const IntervalVec3& a, const IntervalVec3& b)
{
  return { Hull(a.X, b.X), Hull(a.Y, b.Y), Hull(a.Z, b.Z) };
}

} // namespace sphcover

#endif
