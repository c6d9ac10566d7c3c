// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TestInterval.cxx
 * @brief Soundness of the outward-rounded interval arithmetic, checked in exact rationals.
 *
 * The subdivision criteria are only as trustworthy as the enclosures they are computed from,
 * so every operation of Interval.h and IntervalVector.h is checked against GMP rationals: an
 * mpq_class built from a double is exact, and so are its +, -, * and /. Each randomized trial
 * draws operand intervals, draws double points inside them (end points included), evaluates
 * the operation exactly at those points and requires the exact value to lie in the computed
 * interval, compared as rationals. Square roots are irrational, so they are checked through
 * squares instead.
 *
 * The operands mix moderate magnitudes (binary exponents in [-30, 30]) with intervals that
 * straddle zero, degenerate intervals, values a few ulps apart, subnormals (underflow) and
 * values near DBL_MAX (overflow), because those are where a one-ulp widening could be wrong.
 *
 * All trials come from fixed seeds, so a failure is reproducible; the failure message prints
 * the operands in hexadecimal floating point so that it can be pasted into a regression test.
 */
#include "math/Interval.h"
#include "math/IntervalVector.h"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <glm/vec3.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace
{

using sphcover::Interval;
using sphcover::IntervalVec3;

constexpr double Inf = std::numeric_limits<double>::infinity();
constexpr double MaxDouble = std::numeric_limits<double>::max();
constexpr double MinSubnormal = std::numeric_limits<double>::denorm_min();

/// The issue's acceptance criterion: at least this many random trials for each operation.
constexpr int TrialsPerOperation = 100000;

/// Each test seeds its own engine from this, so a test's trials do not depend on which other
/// tests ran before it (--gtest_filter, --gtest_shuffle).
constexpr std::uint64_t BaseSeed = 0x5eedc0ffee15badULL;

//------------------------------------------------------------------------------------------------
// Formatting for failure messages: hexadecimal floating point is exact and can be pasted back.

std::string Hex(double x)
{
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%a", x);
  return buffer;
}

std::string Hex(const Interval& a)
{
  return "[" + Hex(a.Lower()) + ", " + Hex(a.Upper()) + "]";
}

std::string Hex(const IntervalVec3& a)
{
  return "(" + Hex(a.X) + ", " + Hex(a.Y) + ", " + Hex(a.Z) + ")";
}

std::string Hex(const glm::dvec3& p)
{
  return "(" + Hex(p.x) + ", " + Hex(p.y) + ", " + Hex(p.z) + ")";
}

/// A rational can have thousands of digits (squared subnormals); its nearest double is enough
/// to see what went wrong.
std::string Approx(const mpq_class& q)
{
  return Hex(q.get_d());
}

//------------------------------------------------------------------------------------------------
/**
 * @brief Deterministic random operands and points.
 *
 * std::uniform_real_distribution and friends are implementation-defined and differ between
 * libstdc++ and libc++, so values are built from the raw bits of std::mt19937_64 (whose output
 * sequence the standard fixes): the trials are then identical on every platform.
 */
class OperandGenerator
{
public:
  explicit OperandGenerator(std::uint64_t seed)
    : Engine(seed)
  {
  }

  /// Uniform in [0, 1), 53 random bits.
  double Unit() { return static_cast<double>(this->Engine() >> 11) * 0x1.0p-53; }

  /// Uniform in [0, n); the modulo bias is irrelevant for test coverage.
  int Below(int n) { return static_cast<int>(this->Engine() % static_cast<std::uint64_t>(n)); }

  bool Chance(int percent) { return this->Below(100) < percent; }

  /// A mantissa in [1, 2): usually 53 random bits, sometimes only a few, because short
  /// mantissas make exact results and rounding ties (the half-ulp worst case) likely.
  double Mantissa()
  {
    if (this->Chance(20))
    {
      return 1.0 + this->Below(16) / 16.0;
    }
    return 1.0 + this->Unit();
  }

  /**
   * @brief A random finite double of random sign.
   *
   * Mostly moderate magnitudes; with @p extremes also subnormal-range values (to probe
   * underflow of products and quotients) and values near DBL_MAX (to probe overflow).
   */
  double Value(bool extremes = true)
  {
    const double sign = this->Chance(50) ? -1.0 : 1.0;
    const int kind = this->Below(100);
    if (kind < 4)
    {
      return sign * 0.0; // both signed zeros
    }
    if (kind < 10)
    {
      return sign * this->Below(8); // small integers, including 0
    }
    if (extremes && kind < 18)
    {
      // 2^-1074 .. 2^-975: ldexp rounds into the subnormal range below 2^-1022.
      return sign * std::ldexp(this->Mantissa(), -1074 + this->Below(100));
    }
    if (extremes && kind < 20)
    {
      // Up to just below DBL_MAX (a mantissa below 2 times 2^1022 stays finite).
      return sign * std::ldexp(this->Mantissa(), 960 + this->Below(63));
    }
    return sign * std::ldexp(this->Mantissa(), this->Below(61) - 30);
  }

  /// A random finite, non-empty interval of one of several shapes.
  Interval Operand(bool extremes = true)
  {
    const int kind = this->Below(100);
    if (kind < 15)
    {
      const double x = this->Value(extremes);
      return { x, x }; // degenerate
    }
    if (kind < 35)
    {
      // Straddles zero: the sign-dependent corner selection of * and / is exercised here.
      return { -std::fabs(this->Value(extremes)), std::fabs(this->Value(extremes)) };
    }
    if (kind < 45)
    {
      // A few ulps wide: the exact range is then hardly wider than the rounding error.
      const double x = this->Value(extremes);
      double y = x;
      for (int steps = 1 + this->Below(3); steps > 0 && y < MaxDouble; --steps)
      {
        y = sphcover::RoundUp(y);
      }
      return { x, y };
    }
    if (kind < 60)
    {
      // Relatively narrow: both ends share their magnitude.
      const double x = this->Value(extremes);
      const double y = x + std::fabs(x) * std::ldexp(this->Unit(), -this->Below(40));
      return { x, std::min(y, MaxDouble) };
    }
    const double x = this->Value(extremes);
    const double y = this->Value(extremes);
    return { std::min(x, y), std::max(x, y) };
  }

  /// An operand whose interval excludes zero (a divisor of a finite quotient).
  Interval NonZeroOperand(bool extremes = true)
  {
    for (;;)
    {
      const Interval b = this->Operand(extremes);
      if (!b.ContainsZero())
      {
        return b;
      }
    }
  }

  /// A double in [a.Lower(), a.Upper()] (finite ends): often an end point, since that is
  /// where the range of the monotone operations is attained.
  double PointIn(const Interval& a)
  {
    const double lo = a.Lower();
    const double hi = a.Upper();
    const int kind = this->Below(8);
    if (kind == 0)
    {
      return lo;
    }
    if (kind == 1)
    {
      return hi;
    }
    if (kind == 2)
    {
      // Log-uniform rather than uniform, so that small values inside an interval straddling
      // zero are drawn too; out-of-range candidates fall through to the uniform draw.
      const double x = this->Value();
      if (a.Contains(x))
      {
        return x;
      }
    }
    const double t = this->Unit();
    double x = lo + t * (hi - lo);
    if (!std::isfinite(x))
    {
      x = (1.0 - t) * lo + t * hi; // hi - lo overflowed
    }
    return std::min(std::max(x, lo), hi); // rounding may step just outside
  }

  glm::dvec3 PointIn(const IntervalVec3& a)
  {
    const double x = this->PointIn(a.X);
    const double y = this->PointIn(a.Y);
    const double z = this->PointIn(a.Z);
    return { x, y, z };
  }

  IntervalVec3 VectorOperand(bool extremes = true)
  {
    const Interval x = this->Operand(extremes);
    const Interval y = this->Operand(extremes);
    return { x, y, this->Operand(extremes) };
  }

private:
  std::mt19937_64 Engine;
};

//------------------------------------------------------------------------------------------------
/**
 * @brief Exact comparison of interval ends with rationals.
 *
 * The scratch rational is reused: assigning a double to an mpq_class reuses its limbs, which
 * keeps GMP's allocator out of the inner loops (this matters under ASan).
 */
class ExactChecker
{
public:
  /// d <= q exactly; -inf is below every rational, +inf and NaN are not.
  bool LessEqual(double d, const mpq_class& q)
  {
    if (std::isnan(d) || d == Inf)
    {
      return false;
    }
    if (d == -Inf)
    {
      return true;
    }
    this->Scratch = d;
    return this->Scratch <= q;
  }

  /// d >= q exactly; +inf is above every rational, -inf and NaN are not.
  bool GreaterEqual(double d, const mpq_class& q)
  {
    if (std::isnan(d) || d == -Inf)
    {
      return false;
    }
    if (d == Inf)
    {
      return true;
    }
    this->Scratch = d;
    return this->Scratch >= q;
  }

  /// r.Lower() <= exact <= r.Upper(), compared as rationals.
  ::testing::AssertionResult Encloses(const Interval& r, const mpq_class& exact)
  {
    if (this->LessEqual(r.Lower(), exact) && this->GreaterEqual(r.Upper(), exact))
    {
      return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure()
      << "result " << Hex(r) << " does not enclose the exact value ~" << Approx(exact);
  }

  /// The result of Sqrt encloses sqrt(x) for x >= 0: lo <= 0 or lo^2 <= x, and hi^2 >= x.
  ::testing::AssertionResult EnclosesSqrt(const Interval& r, const mpq_class& x)
  {
    bool lowerOk = r.Lower() <= 0.0;
    if (!lowerOk && std::isfinite(r.Lower()))
    {
      this->Scratch = r.Lower();
      this->Square = this->Scratch * this->Scratch;
      lowerOk = this->Square <= x;
    }
    bool upperOk = r.Upper() == Inf;
    if (!upperOk && std::isfinite(r.Upper()) && r.Upper() >= 0.0)
    {
      this->Scratch = r.Upper();
      this->Square = this->Scratch * this->Scratch;
      upperOk = this->Square >= x;
    }
    if (lowerOk && upperOk)
    {
      return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure()
      << "result " << Hex(r) << " does not enclose sqrt of ~" << Approx(x);
  }

private:
  mpq_class Scratch;
  mpq_class Square;
};

/// No NaN end, and no lower end of +inf or upper end of -inf (which would be an empty set).
::testing::AssertionResult WellFormed(const Interval& r)
{
  if (std::isnan(r.Lower()) || std::isnan(r.Upper()) || r.Lower() == Inf || r.Upper() == -Inf ||
    !(r.Lower() <= r.Upper()))
  {
    return ::testing::AssertionFailure() << "ill-formed result " << Hex(r);
  }
  return ::testing::AssertionSuccess();
}

//------------------------------------------------------------------------------------------------
// Generic drivers of the randomized containment tests of scalar operations.

/**
 * @brief Trials of a binary operation: interval result versus exact result at random points.
 * @param nonZeroDivisor draw the second operand so that it excludes zero (for division).
 */
template<typename IntervalOp, typename ExactOp>
void CheckBinary(std::uint64_t seed, bool nonZeroDivisor, IntervalOp intervalOp, ExactOp exactOp)
{
  OperandGenerator gen(seed);
  ExactChecker checker;
  mpq_class x;
  mpq_class y;
  mpq_class exact;
  for (int trial = 0; trial < TrialsPerOperation; ++trial)
  {
    const Interval a = gen.Operand();
    const Interval b = nonZeroDivisor ? gen.NonZeroOperand() : gen.Operand();
    const double xa = gen.PointIn(a);
    const double xb = gen.PointIn(b);
    const Interval r = intervalOp(a, b);
    x = xa;
    y = xb;
    exactOp(exact, x, y);
    ASSERT_TRUE(checker.Encloses(r, exact))
      << "trial " << trial << ": a = " << Hex(a) << ", b = " << Hex(b) << ", x = " << Hex(xa)
      << ", y = " << Hex(xb);
  }
}

template<typename IntervalOp, typename ExactOp>
void CheckUnary(std::uint64_t seed, IntervalOp intervalOp, ExactOp exactOp)
{
  OperandGenerator gen(seed);
  ExactChecker checker;
  mpq_class x;
  mpq_class exact;
  for (int trial = 0; trial < TrialsPerOperation; ++trial)
  {
    const Interval a = gen.Operand();
    const double xa = gen.PointIn(a);
    const Interval r = intervalOp(a);
    x = xa;
    exactOp(exact, x);
    ASSERT_TRUE(checker.Encloses(r, exact))
      << "trial " << trial << ": a = " << Hex(a) << ", x = " << Hex(xa);
  }
}

} // namespace

//------------------------------------------------------------------------------------------------
// Randomized containment of the scalar operations.

TEST(IntervalRandom, Addition)
{
  CheckBinary(
    BaseSeed + 1,
    false,
    [](const Interval& a, const Interval& b) { return a + b; },
    [](mpq_class& r, const mpq_class& x, const mpq_class& y) { r = x + y; });
}

TEST(IntervalRandom, Subtraction)
{
  CheckBinary(
    BaseSeed + 2,
    false,
    [](const Interval& a, const Interval& b) { return a - b; },
    [](mpq_class& r, const mpq_class& x, const mpq_class& y) { r = x - y; });
}

TEST(IntervalRandom, Multiplication)
{
  CheckBinary(
    BaseSeed + 3,
    false,
    [](const Interval& a, const Interval& b) { return a * b; },
    [](mpq_class& r, const mpq_class& x, const mpq_class& y) { r = x * y; });
}

TEST(IntervalRandom, Division)
{
  CheckBinary(
    BaseSeed + 4,
    true,
    [](const Interval& a, const Interval& b) { return a / b; },
    [](mpq_class& r, const mpq_class& x, const mpq_class& y) { r = x / y; });
}

TEST(IntervalRandom, Negation)
{
  CheckUnary(
    BaseSeed + 5,
    [](const Interval& a) { return -a; },
    [](mpq_class& r, const mpq_class& x) { r = -x; });
}

TEST(IntervalRandom, Sqr)
{
  CheckUnary(
    BaseSeed + 6,
    [](const Interval& a) { return sphcover::Sqr(a); },
    [](mpq_class& r, const mpq_class& x) { r = x * x; });
}

TEST(IntervalRandom, Sqrt)
{
  OperandGenerator gen(BaseSeed + 7);
  ExactChecker checker;
  mpq_class x;
  for (int trial = 0; trial < TrialsPerOperation; ++trial)
  {
    Interval a = gen.Operand();
    if (a.IsNegative())
    {
      a = -a; // keep straddling intervals (clipped part) but mostly real square roots
    }
    // Sqrt is defined on the non-negative part only, so points come from there.
    const double xa = gen.PointIn(Interval(std::max(a.Lower(), 0.0), a.Upper()));
    const Interval r = sphcover::Sqrt(a);
    x = xa;
    ASSERT_TRUE(WellFormed(r)) << "trial " << trial << ": a = " << Hex(a);
    ASSERT_GE(r.Lower(), 0.0) << "trial " << trial << ": a = " << Hex(a);
    ASSERT_TRUE(checker.EnclosesSqrt(r, x))
      << "trial " << trial << ": a = " << Hex(a) << ", x = " << Hex(xa);
  }
}

TEST(IntervalRandom, CompoundAssignment)
{
  // Four operations, TrialsPerOperation each. Besides containment, a compound assignment
  // must give bit for bit the result of the binary operator.
  OperandGenerator gen(BaseSeed + 8);
  ExactChecker checker;
  mpq_class x;
  mpq_class y;
  mpq_class exact;
  for (int trial = 0; trial < 4 * TrialsPerOperation; ++trial)
  {
    const int op = trial % 4;
    const Interval a = gen.Operand();
    const Interval b = op == 3 ? gen.NonZeroOperand() : gen.Operand();
    const double xa = gen.PointIn(a);
    const double xb = gen.PointIn(b);
    x = xa;
    y = xb;
    Interval r = a;
    Interval expected;
    switch (op)
    {
      case 0:
        r += b;
        expected = a + b;
        exact = x + y;
        break;
      case 1:
        r -= b;
        expected = a - b;
        exact = x - y;
        break;
      case 2:
        r *= b;
        expected = a * b;
        exact = x * y;
        break;
      default:
        r /= b;
        expected = a / b;
        exact = x / y;
        break;
    }
    ASSERT_EQ(r.Lower(), expected.Lower()) << "trial " << trial << " op " << op;
    ASSERT_EQ(r.Upper(), expected.Upper()) << "trial " << trial << " op " << op;
    ASSERT_TRUE(checker.Encloses(r, exact))
      << "trial " << trial << " op "
      << "+-*/"[op] << "=: a = " << Hex(a) << ", b = " << Hex(b) << ", x = " << Hex(xa)
      << ", y = " << Hex(xb);
  }
}

TEST(IntervalRandom, CompoundAssignmentAliasing)
{
  // a op= a reads its operand through the same reference it writes; the exact value at one
  // point x of a is x op x, which must be enclosed.
  OperandGenerator gen(BaseSeed + 9);
  ExactChecker checker;
  mpq_class x;
  mpq_class exact;
  for (int trial = 0; trial < 10000; ++trial)
  {
    const int op = trial % 4;
    Interval a = op == 3 ? gen.NonZeroOperand() : gen.Operand();
    const Interval& alias = a; // spelled a op= a, clang warns of a self-assignment
    const Interval original = a;
    const double xa = gen.PointIn(a);
    x = xa;
    switch (op)
    {
      case 0:
        a += alias;
        exact = x + x;
        break;
      case 1:
        a -= alias;
        exact = 0;
        break;
      case 2:
        a *= alias;
        exact = x * x;
        break;
      default:
        a /= alias;
        exact = 1;
        break;
    }
    ASSERT_TRUE(checker.Encloses(a, exact))
      << "trial " << trial << " op "
      << "+-*/"[op] << "=: a = " << Hex(original) << ", x = " << Hex(xa);
  }
}

TEST(IntervalRandom, DivisionByIntervalContainingZeroIsEntire)
{
  OperandGenerator gen(BaseSeed + 10);
  for (int trial = 0; trial < TrialsPerOperation; ++trial)
  {
    const Interval a = gen.Operand();
    Interval b;
    switch (trial % 4)
    {
      case 0:
        b = Interval(-std::fabs(gen.Value()), std::fabs(gen.Value()));
        break;
      case 1:
        b = Interval(0.0, std::fabs(gen.Value())); // zero as an end point, either signed zero
        break;
      case 2:
        b = Interval(-std::fabs(gen.Value()), gen.Chance(50) ? 0.0 : -0.0);
        break;
      default:
        b = gen.Chance(50) ? Interval(0.0) : Interval(-0.0, 0.0);
        break;
    }
    ASSERT_TRUE(b.ContainsZero());
    const Interval r = a / b;
    ASSERT_EQ(r.Lower(), -Inf) << "trial " << trial << ": a = " << Hex(a) << ", b = " << Hex(b);
    ASSERT_EQ(r.Upper(), Inf) << "trial " << trial << ": a = " << Hex(a) << ", b = " << Hex(b);
    Interval c = a;
    c /= b;
    ASSERT_EQ(c.Lower(), -Inf);
    ASSERT_EQ(c.Upper(), Inf);
  }
}

TEST(IntervalRandom, EnclosuresAreTight)
{
  // Containment alone would be met by returning Entire(). The exact range of +, -, * and /
  // over boxes is attained at corners (and of Sqr at the mignitude and magnitude); a correctly
  // rounded end widened by one ulp lies within two ulps of it.
  OperandGenerator gen(BaseSeed + 11);
  ExactChecker checker;
  std::array<mpq_class, 2> ea;
  std::array<mpq_class, 2> eb;
  mpq_class corner;
  mpq_class exactLo;
  mpq_class exactHi;
  constexpr int Trials = 20000;
  for (int trial = 0; trial < Trials; ++trial)
  {
    const int op = trial % 5;
    const Interval a = gen.Operand();
    const Interval b = op == 3 ? gen.NonZeroOperand() : gen.Operand();
    ea[0] = a.Lower();
    ea[1] = a.Upper();
    eb[0] = b.Lower();
    eb[1] = b.Upper();
    Interval r;
    if (op == 4)
    {
      r = sphcover::Sqr(a);
      corner = a.Mignitude();
      exactLo = corner * corner;
      corner = a.Magnitude();
      exactHi = corner * corner;
    }
    else
    {
      for (int k = 0; k < 4; ++k)
      {
        const mpq_class& x = ea[k / 2];
        const mpq_class& y = eb[k % 2];
        switch (op)
        {
          case 0:
            corner = x + y;
            break;
          case 1:
            corner = x - y;
            break;
          case 2:
            corner = x * y;
            break;
          default:
            corner = x / y;
            break;
        }
        if (k == 0 || corner < exactLo)
        {
          exactLo = corner;
        }
        if (k == 0 || corner > exactHi)
        {
          exactHi = corner;
        }
      }
      r = op == 0 ? a + b : (op == 1 ? a - b : (op == 2 ? a * b : a / b));
    }
    const double twoUlpsAboveLo = sphcover::RoundUp(sphcover::RoundUp(r.Lower()));
    const double twoUlpsBelowHi = sphcover::RoundDown(sphcover::RoundDown(r.Upper()));
    ASSERT_TRUE(
      checker.LessEqual(r.Lower(), exactLo) && checker.GreaterEqual(twoUlpsAboveLo, exactLo))
      << "trial " << trial << " op " << op << ": a = " << Hex(a) << ", b = " << Hex(b)
      << ", r = " << Hex(r) << ", exact lower end ~" << Approx(exactLo);
    ASSERT_TRUE(
      checker.GreaterEqual(r.Upper(), exactHi) && checker.LessEqual(twoUlpsBelowHi, exactHi))
      << "trial " << trial << " op " << op << ": a = " << Hex(a) << ", b = " << Hex(b)
      << ", r = " << Hex(r) << ", exact upper end ~" << Approx(exactHi);
  }
}

//------------------------------------------------------------------------------------------------
// Randomized containment of the vector operations.

namespace
{

void ToRationals(const glm::dvec3& p, std::array<mpq_class, 3>& q)
{
  q[0] = p.x;
  q[1] = p.y;
  q[2] = p.z;
}

} // namespace

TEST(IntervalVec3Random, Dot)
{
  OperandGenerator gen(BaseSeed + 20);
  ExactChecker checker;
  std::array<mpq_class, 3> x;
  std::array<mpq_class, 3> y;
  mpq_class exact;
  mpq_class term;
  for (int trial = 0; trial < TrialsPerOperation; ++trial)
  {
    const IntervalVec3 a = gen.VectorOperand();
    const IntervalVec3 b = gen.VectorOperand();
    const glm::dvec3 pa = gen.PointIn(a);
    const glm::dvec3 pb = gen.PointIn(b);
    ToRationals(pa, x);
    ToRationals(pb, y);
    // Term by term into one accumulator: a nested gmpxx expression would allocate temporaries.
    exact = x[0] * y[0];
    term = x[1] * y[1];
    exact += term;
    term = x[2] * y[2];
    exact += term;
    const Interval r = sphcover::Dot(a, b);
    ASSERT_TRUE(checker.Encloses(r, exact))
      << "trial " << trial << ": a = " << Hex(a) << ", b = " << Hex(b) << ", x = " << Hex(pa)
      << ", y = " << Hex(pb);
  }
}

TEST(IntervalVec3Random, Cross)
{
  OperandGenerator gen(BaseSeed + 21);
  ExactChecker checker;
  std::array<mpq_class, 3> x;
  std::array<mpq_class, 3> y;
  mpq_class exact;
  mpq_class term;
  for (int trial = 0; trial < TrialsPerOperation; ++trial)
  {
    const IntervalVec3 a = gen.VectorOperand();
    const IntervalVec3 b = gen.VectorOperand();
    const glm::dvec3 pa = gen.PointIn(a);
    const glm::dvec3 pb = gen.PointIn(b);
    ToRationals(pa, x);
    ToRationals(pb, y);
    const IntervalVec3 r = sphcover::Cross(a, b);
    for (int i = 0; i < 3; ++i)
    {
      const int j = (i + 1) % 3;
      const int k = (i + 2) % 3;
      exact = x[j] * y[k];
      term = x[k] * y[j];
      exact -= term;
      ASSERT_TRUE(checker.Encloses(r[i], exact))
        << "trial " << trial << ", component " << i << ": a = " << Hex(a) << ", b = " << Hex(b)
        << ", x = " << Hex(pa) << ", y = " << Hex(pb);
    }
  }
}

TEST(IntervalVec3Random, SquaredLength)
{
  OperandGenerator gen(BaseSeed + 22);
  ExactChecker checker;
  std::array<mpq_class, 3> x;
  mpq_class exact;
  mpq_class term;
  for (int trial = 0; trial < TrialsPerOperation; ++trial)
  {
    const IntervalVec3 a = gen.VectorOperand();
    const glm::dvec3 pa = gen.PointIn(a);
    ToRationals(pa, x);
    exact = x[0] * x[0];
    term = x[1] * x[1];
    exact += term;
    term = x[2] * x[2];
    exact += term;
    const Interval r = sphcover::SquaredLength(a);
    // A sum of squares is never negative: SquaredLength clips the widened lower end at 0.
    ASSERT_GE(r.Lower(), 0.0) << "trial " << trial << ": a = " << Hex(a);
    ASSERT_TRUE(checker.Encloses(r, exact))
      << "trial " << trial << ": a = " << Hex(a) << ", x = " << Hex(pa);
  }
}

TEST(IntervalVec3Random, ComponentwiseOperations)
{
  // a + b, a - b, -a and s * a, TrialsPerOperation each, plus the enclosure of Hull.
  OperandGenerator gen(BaseSeed + 23);
  ExactChecker checker;
  std::array<mpq_class, 3> x;
  std::array<mpq_class, 3> y;
  mpq_class s;
  mpq_class exact;
  for (int trial = 0; trial < TrialsPerOperation; ++trial)
  {
    const IntervalVec3 a = gen.VectorOperand();
    const IntervalVec3 b = gen.VectorOperand();
    const Interval scale = gen.Operand();
    const glm::dvec3 pa = gen.PointIn(a);
    const glm::dvec3 pb = gen.PointIn(b);
    const double ps = gen.PointIn(scale);
    ToRationals(pa, x);
    ToRationals(pb, y);
    s = ps;
    const IntervalVec3 sum = a + b;
    const IntervalVec3 difference = a - b;
    const IntervalVec3 negated = -a;
    const IntervalVec3 scaled = scale * a;
    const IntervalVec3 hull = sphcover::Hull(a, b);
    ASSERT_TRUE(hull.Contains(pa) && hull.Contains(pb)) << "trial " << trial;
    for (int i = 0; i < 3; ++i)
    {
      exact = x[i] + y[i];
      ASSERT_TRUE(checker.Encloses(sum[i], exact))
        << "trial " << trial << " a + b [" << i << "]: a = " << Hex(a) << ", b = " << Hex(b);
      exact = x[i] - y[i];
      ASSERT_TRUE(checker.Encloses(difference[i], exact))
        << "trial " << trial << " a - b [" << i << "]: a = " << Hex(a) << ", b = " << Hex(b);
      exact = -x[i];
      ASSERT_TRUE(checker.Encloses(negated[i], exact))
        << "trial " << trial << " -a [" << i << "]: a = " << Hex(a);
      exact = s * x[i];
      ASSERT_TRUE(checker.Encloses(scaled[i], exact))
        << "trial " << trial << " s * a [" << i << "]: s = " << Hex(scale) << ", a = " << Hex(a);
    }
  }
}

//------------------------------------------------------------------------------------------------
// Random expression trees: enclosures must compose.

namespace
{

/**
 * @brief A random expression over + - * / and Sqr with interval leaves, evaluated both in
 * interval arithmetic and exactly at one point of every leaf.
 *
 * Nodes are stored in preorder, so every child has a larger index than its parent and one
 * backwards sweep evaluates the whole tree; the storage is reused from trial to trial.
 */
class ExpressionTree
{
public:
  enum class Op : unsigned char
  {
    Leaf,
    Add,
    Sub,
    Mul,
    Div,
    Sqr
  };

  /// A depth-5 tree has at most 2^6 - 1 nodes.
  static constexpr int MaxNodes = 63;

  ExpressionTree()
    : Values(MaxNodes)
  {
    this->Nodes.reserve(MaxNodes);
    this->Ranges.resize(MaxNodes);
    this->Defined.resize(MaxNodes);
  }

  /// A new random tree whose deepest leaf is exactly @p depth operations below the root.
  void Generate(OperandGenerator& gen, int depth)
  {
    this->Nodes.clear();
    this->Add(gen, 0, depth, true);
  }

  /**
   * @brief Evaluates the root both ways.
   * @return false when the exact value is undefined (an exact division by zero), in which
   * case only the interval result is meaningful.
   */
  bool Evaluate(Interval& range, mpq_class& exact)
  {
    for (int i = static_cast<int>(this->Nodes.size()) - 1; i >= 0; --i)
    {
      const Node& node = this->Nodes[i];
      Interval& r = this->Ranges[i];
      mpq_class& v = this->Values[i];
      if (node.Kind == Op::Leaf)
      {
        r = node.Range;
        v = node.Point;
        this->Defined[i] = true;
        continue;
      }
      const Interval& a = this->Ranges[node.Left];
      const mpq_class& x = this->Values[node.Left];
      if (node.Kind == Op::Sqr)
      {
        r = sphcover::Sqr(a);
        v = x * x;
        this->Defined[i] = this->Defined[node.Left];
        continue;
      }
      const Interval& b = this->Ranges[node.Right];
      const mpq_class& y = this->Values[node.Right];
      this->Defined[i] = this->Defined[node.Left] && this->Defined[node.Right];
      switch (node.Kind)
      {
        case Op::Add:
          r = a + b;
          v = x + y;
          break;
        case Op::Sub:
          r = a - b;
          v = x - y;
          break;
        case Op::Mul:
          r = a * b;
          v = x * y;
          break;
        default:
          r = a / b;
          if (sgn(y) == 0)
          {
            this->Defined[i] = false;
          }
          else if (this->Defined[i])
          {
            v = x / y;
          }
          break;
      }
    }
    range = this->Ranges[0];
    exact = this->Values[0];
    return this->Defined[0];
  }

  /// The expression with its leaves and points, for failure messages.
  std::string ToString(int i = 0) const
  {
    const Node& node = this->Nodes[i];
    switch (node.Kind)
    {
      case Op::Leaf:
        return Hex(node.Range) + "@" + Hex(node.Point);
      case Op::Sqr:
        return "Sqr(" + this->ToString(node.Left) + ")";
      default:
        break;
    }
    const char* symbol = node.Kind == Op::Add ? " + "
      : node.Kind == Op::Sub                  ? " - "
      : node.Kind == Op::Mul                  ? " * "
                                              : " / ";
    return "(" + this->ToString(node.Left) + symbol + this->ToString(node.Right) + ")";
  }

private:
  struct Node
  {
    Op Kind = Op::Leaf;
    int Left = -1;
    int Right = -1;
    Interval Range;
    double Point = 0.0;
  };

  /**
   * @param spine the leftmost path is forced down to @p depth, other branches stop early.
   * @param divisor a leaf here excludes zero: divisions by intervals around zero give
   * Entire(), and too many unbounded results would leave little to check.
   */
  int Add(OperandGenerator& gen, int level, int depth, bool spine, bool divisor = false)
  {
    const int index = static_cast<int>(this->Nodes.size());
    this->Nodes.emplace_back();
    if (level == depth || (!spine && gen.Chance(35)))
    {
      // Values near DBL_MAX and subnormals only now and then: nested products would overflow
      // or underflow in most trials, which tests little.
      const bool extremes = gen.Chance(10);
      const Interval leaf = divisor ? gen.NonZeroOperand(extremes) : gen.Operand(extremes);
      this->Nodes[index].Range = leaf;
      this->Nodes[index].Point = gen.PointIn(leaf);
      return index;
    }
    const Op op = static_cast<Op>(1 + gen.Below(5));
    this->Nodes[index].Kind = op;
    const int left = this->Add(gen, level + 1, depth, spine);
    this->Nodes[index].Left = left;
    if (op != Op::Sqr)
    {
      const int right = this->Add(gen, level + 1, depth, false, op == Op::Div);
      this->Nodes[index].Right = right;
    }
    return index;
  }

  std::vector<Node> Nodes;
  std::vector<Interval> Ranges;
  std::vector<mpq_class> Values;
  std::vector<char> Defined;
};

} // namespace

TEST(IntervalRandom, ExpressionTrees)
{
  OperandGenerator gen(BaseSeed + 30);
  ExactChecker checker;
  ExpressionTree tree;
  Interval range;
  mpq_class exact;
  int bounded = 0;
  int undefined = 0;
  for (int trial = 0; trial < TrialsPerOperation; ++trial)
  {
    tree.Generate(gen, 3 + gen.Below(3));
    const bool defined = tree.Evaluate(range, exact);
    ASSERT_TRUE(WellFormed(range)) << "trial " << trial << ": " << tree.ToString();
    if (!defined)
    {
      ++undefined;
      continue;
    }
    ASSERT_TRUE(checker.Encloses(range, exact)) << "trial " << trial << ": " << tree.ToString();
    if (std::isfinite(range.Lower()) && std::isfinite(range.Upper()))
    {
      ++bounded;
    }
  }
  // Guard against a vacuous test: divisions by intervals around zero give infinite results,
  // but most trees must still have bounded enclosures for the containment to mean anything.
  EXPECT_GT(bounded, TrialsPerOperation / 2) << "undefined: " << undefined;
  std::printf("[          ] %d trees with bounded enclosures, %d with an exact division by 0\n",
    bounded,
    undefined);
}

//------------------------------------------------------------------------------------------------
// Deterministic edge cases.

namespace
{

/// Operands with infinite, zero and extreme ends, for the NaN-freedom tests.
std::vector<Interval> SpecialOperands()
{
  return { Interval::Entire(),
    Interval(1.0, Inf),
    Interval(-Inf, -1.0),
    Interval(0.0, Inf),
    Interval(-Inf, 0.0),
    Interval(-0.0, Inf),
    Interval(-Inf, -0.0),
    Interval(0.0),
    Interval(-0.0, 0.0),
    Interval(-1.0, 1.0),
    Interval(2.0, 3.0),
    Interval(-3.0, -2.0),
    Interval(MaxDouble),
    Interval(-MaxDouble, MaxDouble),
    Interval(MinSubnormal),
    Interval(-MinSubnormal, 0.0),
    Interval(0x1.0p-600, 0x1.0p-500),
    Interval(-Inf, 5.0),
    Interval(-5.0, Inf) };
}

/// Finite sample points of a possibly unbounded interval: its finite ends and a few values.
std::vector<double> SamplePoints(const Interval& a)
{
  std::vector<double> points;
  for (const double x : { a.Lower(),
         a.Upper(),
         0.0,
         -0.0,
         1.0,
         -1.0,
         0.5,
         7.0,
         -7.0,
         1e300,
         -1e300,
         MaxDouble,
         -MaxDouble,
         MinSubnormal })
  {
    if (std::isfinite(x) && a.Contains(x))
    {
      points.push_back(x);
    }
  }
  return points;
}

} // namespace

TEST(IntervalEdge, ZeroTimesAnything)
{
  // The exact product is 0 for every operand, including unbounded ones (intervals are sets of
  // reals, so 0 * inf never occurs); the only slack allowed is the one-ulp widening of 0.
  for (const Interval& zero : { Interval(0.0), Interval(-0.0), Interval(-0.0, 0.0) })
  {
    for (const Interval& b : SpecialOperands())
    {
      for (const Interval& r : { zero * b, b * zero })
      {
        ASSERT_TRUE(WellFormed(r)) << Hex(zero) << " * " << Hex(b);
        EXPECT_TRUE(r.ContainsZero()) << Hex(zero) << " * " << Hex(b);
        EXPECT_LE(r.Magnitude(), MinSubnormal) << Hex(zero) << " * " << Hex(b);
      }
    }
  }
}

TEST(IntervalEdge, NegationIsExact)
{
  OperandGenerator gen(BaseSeed + 40);
  for (int trial = 0; trial < 10000; ++trial)
  {
    const Interval a = gen.Operand();
    const Interval r = -a;
    // Bit for bit: negation flips the sign bit and rounds nothing, and it swaps the ends.
    ASSERT_EQ(r.Lower(), -a.Upper());
    ASSERT_EQ(r.Upper(), -a.Lower());
    ASSERT_EQ(std::signbit(r.Lower()), !std::signbit(a.Upper()));
    const Interval back = -r;
    ASSERT_EQ(back.Lower(), a.Lower());
    ASSERT_EQ(back.Upper(), a.Upper());
  }
  const Interval e = -Interval::Entire();
  EXPECT_EQ(e.Lower(), -Inf);
  EXPECT_EQ(e.Upper(), Inf);
}

TEST(IntervalEdge, SqrOfIntervalStraddlingZero)
{
  const Interval a(-3.0, 2.0);
  const Interval s = sphcover::Sqr(a);
  EXPECT_EQ(s.Lower(), 0.0); // exactly 0, where a * a would go down to -6
  EXPECT_GE(s.Upper(), 9.0);
  EXPECT_LE(s.Upper(), sphcover::RoundUp(9.0));
  EXPECT_LT((a * a).Lower(), 0.0);

  for (const Interval& b : { Interval(-0.0, 0.0),
         Interval(0.0, 1.0),
         Interval(-1.0, 0.0),
         Interval(-0x1.0p-1074, 0x1.0p-1074),
         Interval(-1e300, 1e-300),
         Interval::Entire() })
  {
    const Interval r = sphcover::Sqr(b);
    EXPECT_TRUE(WellFormed(r)) << Hex(b);
    EXPECT_EQ(r.Lower(), 0.0) << Hex(b);
    EXPECT_FALSE(std::signbit(r.Lower())) << Hex(b);
  }
  // Away from zero the lower end is the square of the mignitude.
  const Interval n = sphcover::Sqr(Interval(-3.0, -2.0));
  EXPECT_LE(n.Lower(), 4.0);
  EXPECT_GE(n.Lower(), sphcover::RoundDown(4.0));
  // A square that underflows keeps a lower end of 0, not -denorm_min.
  EXPECT_EQ(sphcover::Sqr(Interval(0x1.0p-600, 0x1.0p-599)).Lower(), 0.0);
}

TEST(IntervalEdge, SqrtOfSlightlyNegativeLowerEnd)
{
  // Rounding noise can make a squared length slightly negative; Sqrt clips it to 0.
  const Interval r = sphcover::Sqrt(Interval(-1e-17, 4.0));
  EXPECT_EQ(r.Lower(), 0.0);
  EXPECT_GE(r.Upper(), 2.0);
  EXPECT_LE(r.Upper(), sphcover::RoundUp(2.0));

  const Interval z = sphcover::Sqrt(Interval(-1e-17, 0.0));
  EXPECT_TRUE(WellFormed(z));
  EXPECT_EQ(z.Lower(), 0.0);
  EXPECT_GE(z.Upper(), 0.0);
  EXPECT_LE(z.Upper(), MinSubnormal);

  // Wholly negative: there is no real root, and the documented clipping gives [0, tiny].
  const Interval n = sphcover::Sqrt(Interval(-2.0, -1.0));
  EXPECT_TRUE(WellFormed(n));
  EXPECT_EQ(n.Lower(), 0.0);

  // Exact squares: the root is bracketed by one ulp on each side.
  const Interval q = sphcover::Sqrt(Interval(4.0, 9.0));
  EXPECT_EQ(q.Lower(), sphcover::RoundDown(2.0));
  EXPECT_EQ(q.Upper(), sphcover::RoundUp(3.0));

  const Interval e = sphcover::Sqrt(Interval::Entire());
  EXPECT_EQ(e.Lower(), 0.0);
  EXPECT_EQ(e.Upper(), Inf);
}

TEST(IntervalEdge, InfinitiesDoNotProduceNaN)
{
  // Unbounded intervals appear as soon as a divisor contains zero (Entire()); everything
  // computed from them must stay a well-formed enclosure, else ContainsZero() and the sign
  // tests silently answer false on NaN ends.
  ExactChecker checker;
  mpq_class x;
  mpq_class y;
  mpq_class exact;
  const std::vector<Interval> operands = SpecialOperands();
  for (const Interval& a : operands)
  {
    const std::vector<double> pa = SamplePoints(a);
    for (const Interval& r : { -a, sphcover::Sqr(a), sphcover::Sqrt(a) })
    {
      EXPECT_TRUE(WellFormed(r)) << "unary op of " << Hex(a);
    }
    for (const double px : pa)
    {
      x = px;
      exact = x * x;
      EXPECT_TRUE(checker.Encloses(sphcover::Sqr(a), exact)) << Hex(a) << " at " << Hex(px);
      if (px >= 0.0)
      {
        EXPECT_TRUE(checker.EnclosesSqrt(sphcover::Sqrt(a), x)) << Hex(a) << " at " << Hex(px);
      }
    }
    for (const Interval& b : operands)
    {
      const std::array<Interval, 4> results = { a + b, a - b, a * b, a / b };
      for (int op = 0; op < 4; ++op)
      {
        ASSERT_TRUE(WellFormed(results[op])) << Hex(a) << " "
                                             << "+-*/"[op] << " " << Hex(b);
      }
      for (const double px : pa)
      {
        x = px;
        for (const double py : SamplePoints(b))
        {
          y = py;
          exact = x + y;
          EXPECT_TRUE(checker.Encloses(results[0], exact)) << Hex(a) << " + " << Hex(b);
          exact = x - y;
          EXPECT_TRUE(checker.Encloses(results[1], exact)) << Hex(a) << " - " << Hex(b);
          exact = x * y;
          EXPECT_TRUE(checker.Encloses(results[2], exact)) << Hex(a) << " * " << Hex(b);
          if (py != 0.0)
          {
            exact = x / y;
            EXPECT_TRUE(checker.Encloses(results[3], exact))
              << Hex(a) << " / " << Hex(b) << " at " << Hex(px) << " / " << Hex(py);
          }
        }
      }
    }
  }
}

TEST(IntervalEdge, UnboundedCornersAreSound)
{
  // Regressions: with IEEE 0 * inf = NaN in the corner formula, std::min and std::max dropped
  // the NaN or kept it depending on argument order. [0, inf] * [0, inf] came out as
  // [-denorm_min, denorm_min] (unsound: it holds 1e300 * 1e300), Entire() * [0, 1] and
  // Entire() / [-inf, -1] (inf / inf) as [NaN, NaN].
  const Interval nonNegative(0.0, Inf);
  const Interval p = nonNegative * nonNegative;
  EXPECT_LE(p.Lower(), 0.0);
  EXPECT_EQ(p.Upper(), Inf);

  const Interval e = Interval::Entire() * Interval(0.0, 1.0);
  EXPECT_EQ(e.Lower(), -Inf);
  EXPECT_EQ(e.Upper(), Inf);

  const Interval h = Interval(-1.0, 0.0) * Interval(0.0, Inf);
  EXPECT_EQ(h.Lower(), -Inf);
  EXPECT_GE(h.Upper(), 0.0);
  EXPECT_LE(h.Upper(), MinSubnormal);

  // x / y over x <= 1, y <= -1 is [-1, inf): 1 / -1 at one corner, -big / -1 at another.
  const Interval q = Interval(-Inf, 1.0) / Interval(-Inf, -1.0);
  EXPECT_LE(q.Lower(), -1.0);
  EXPECT_GE(q.Lower(), sphcover::RoundDown(-1.0));
  EXPECT_EQ(q.Upper(), Inf);

  // x / y over x >= 1, y >= 1 is (0, inf): the inf / inf corner counts as 0.
  const Interval r = Interval(1.0, Inf) / Interval(1.0, Inf);
  EXPECT_LE(r.Lower(), 0.0);
  EXPECT_GE(r.Lower(), -MinSubnormal);
  EXPECT_EQ(r.Upper(), Inf);

  const Interval d = Interval::Entire() / Interval(-Inf, -1.0);
  EXPECT_EQ(d.Lower(), -Inf);
  EXPECT_EQ(d.Upper(), Inf);
}

TEST(IntervalEdge, OverflowAndUnderflow)
{
  ExactChecker checker;
  mpq_class exact;
  // Overflow: the rounded sum is +inf, the lower end stays finite and below the exact sum.
  const Interval big(MaxDouble);
  const Interval sum = big + big;
  EXPECT_EQ(sum.Lower(), MaxDouble);
  EXPECT_EQ(sum.Upper(), Inf);
  const Interval product = -big * big;
  EXPECT_EQ(product.Lower(), -Inf);
  EXPECT_EQ(product.Upper(), -MaxDouble);

  // Underflow: the exact product 2^-1200 rounds to 0; widening 0 keeps it enclosed, so the
  // product of two positive intervals is (soundly) not IsPositive().
  const Interval tiny(0x1.0p-600);
  const Interval p = tiny * tiny;
  exact = tiny.Lower();
  exact *= exact;
  EXPECT_TRUE(checker.Encloses(p, exact));
  EXPECT_FALSE(p.IsPositive());
  EXPECT_TRUE(p.ContainsZero());

  // A quotient below the smallest subnormal rounds to 0 (tie to even); the widened 0 must
  // still reach up to the exact 2^-1075.
  const Interval q = Interval(MinSubnormal) / Interval(2.0);
  exact = MinSubnormal;
  exact /= 2;
  EXPECT_TRUE(checker.Encloses(q, exact));
  EXPECT_EQ(q.Upper(), MinSubnormal);

  // Sums of subnormals are exact, so the widening is the only slack.
  const Interval s = Interval(MinSubnormal) + Interval(MinSubnormal);
  EXPECT_EQ(s.Lower(), MinSubnormal);
  EXPECT_EQ(s.Upper(), 3 * MinSubnormal);
}

TEST(IntervalPredicates, SignTestsAndMagnitudes)
{
  const Interval positive(1.0, 2.0);
  EXPECT_TRUE(positive.IsPositive());
  EXPECT_FALSE(positive.IsNegative());
  EXPECT_FALSE(positive.ContainsZero());
  EXPECT_EQ(positive.Mignitude(), 1.0);
  EXPECT_EQ(positive.Magnitude(), 2.0);

  const Interval negative(-3.0, -0.5);
  EXPECT_FALSE(negative.IsPositive());
  EXPECT_TRUE(negative.IsNegative());
  EXPECT_FALSE(negative.ContainsZero());
  EXPECT_EQ(negative.Mignitude(), 0.5);
  EXPECT_EQ(negative.Magnitude(), 3.0);

  const Interval straddling(-4.0, 2.5);
  EXPECT_FALSE(straddling.IsPositive());
  EXPECT_FALSE(straddling.IsNegative());
  EXPECT_TRUE(straddling.ContainsZero());
  EXPECT_EQ(straddling.Mignitude(), 0.0);
  EXPECT_EQ(straddling.Magnitude(), 4.0);

  // A zero end point is neither positive nor negative: the sign tests are strict.
  for (const Interval& a : { Interval(0.0, 1.0),
         Interval(-0.0, 1.0),
         Interval(-1.0, 0.0),
         Interval(-1.0, -0.0),
         Interval(0.0),
         Interval(-0.0) })
  {
    EXPECT_FALSE(a.IsPositive()) << Hex(a);
    EXPECT_FALSE(a.IsNegative()) << Hex(a);
    EXPECT_TRUE(a.ContainsZero()) << Hex(a);
    EXPECT_EQ(a.Mignitude(), 0.0) << Hex(a);
  }

  const Interval tinyPositive(MinSubnormal, MinSubnormal);
  EXPECT_TRUE(tinyPositive.IsPositive());
  EXPECT_EQ(tinyPositive.Mignitude(), MinSubnormal);

  const Interval entire = Interval::Entire();
  EXPECT_TRUE(entire.ContainsZero());
  EXPECT_FALSE(entire.IsPositive());
  EXPECT_FALSE(entire.IsNegative());
  EXPECT_EQ(entire.Mignitude(), 0.0);
  EXPECT_EQ(entire.Magnitude(), Inf);
  EXPECT_EQ(Interval(1.0, Inf).Mignitude(), 1.0);
  EXPECT_EQ(Interval(-Inf, -2.0).Mignitude(), 2.0);
}

TEST(IntervalPredicates, ConstructionAndQueries)
{
  // Default construction is [0, 0]; a double converts to the exact degenerate interval.
  const Interval zero;
  EXPECT_EQ(zero.Lower(), 0.0);
  EXPECT_EQ(zero.Upper(), 0.0);
  const Interval point = 0.1;
  EXPECT_EQ(point.Lower(), 0.1);
  EXPECT_EQ(point.Upper(), 0.1);

  const Interval a(-1.5, 2.0);
  EXPECT_TRUE(a.Contains(-1.5));
  EXPECT_TRUE(a.Contains(2.0));
  EXPECT_TRUE(a.Contains(0.0));
  EXPECT_FALSE(a.Contains(sphcover::RoundUp(2.0)));
  EXPECT_FALSE(a.Contains(sphcover::RoundDown(-1.5)));
  EXPECT_GE(a.Width(), 3.5); // an upper bound of the width
  EXPECT_TRUE(a.Contains(a.Midpoint()));

  // The width is rounded up: the exact width 1 - 2^-60 is not a double.
  const Interval narrow(0x1.0p-60, 1.0);
  mpq_class exactWidth = 1.0;
  exactWidth -= mpq_class(0x1.0p-60);
  EXPECT_GE(mpq_class(narrow.Width()), exactWidth);

  const Interval h = sphcover::Hull(Interval(1.0, 2.0), Interval(-3.0, -2.0));
  EXPECT_EQ(h.Lower(), -3.0);
  EXPECT_EQ(h.Upper(), 2.0);

  const Interval e = Interval::Entire();
  EXPECT_EQ(e.Lower(), -Inf);
  EXPECT_EQ(e.Upper(), Inf);
}

TEST(IntervalVec3Edge, AccessorsAndConstruction)
{
  const glm::dvec3 p(1.0, -2.0, 0.25);
  const IntervalVec3 v(p);
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_EQ(v[i].Lower(), p[i]);
    EXPECT_EQ(v[i].Upper(), p[i]);
  }
  EXPECT_TRUE(v.Contains(p));
  EXPECT_EQ(v.Lower(), p);
  EXPECT_EQ(v.Upper(), p);

  IntervalVec3 w(Interval(0.0, 1.0), Interval(-1.0, 0.0), Interval(2.0, 3.0));
  w[1] = Interval(-5.0, 5.0);
  EXPECT_EQ(w.Y.Lower(), -5.0);
  EXPECT_EQ(w.Upper(), glm::dvec3(1.0, 5.0, 3.0));
  EXPECT_TRUE(w.Contains(glm::dvec3(0.5, 0.0, 2.5)));
  EXPECT_FALSE(w.Contains(glm::dvec3(0.5, 0.0, 3.5)));

  // SquaredLength uses Sqr, so a box straddling the axis planes has a lower end of exactly 0,
  // where Dot(a, a) goes down to -(1 + 2 + 1.5).
  const IntervalVec3 box(Interval(-1.0, 1.0), Interval(-2.0, 1.0), Interval(-0.5, 3.0));
  const Interval squaredLength = sphcover::SquaredLength(box);
  EXPECT_EQ(squaredLength.Lower(), 0.0);
  EXPECT_GE(squaredLength.Upper(), 1.0 + 4.0 + 9.0);
  EXPECT_LT(sphcover::Dot(box, box).Lower(), -4.0);
}
