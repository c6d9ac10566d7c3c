// SPDX-License-Identifier: BSD-3-Clause
// HemisphereGrid: the (theta, phi) cells of paper §3.3, their cosine-weighted measures, the
// frame of a characteristic point and the stratified sample directions.
#include "cover/HemisphereGrid.h"

#include "math/Constants.h"
#include "subdivision/Patch.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

using namespace sphcover;

namespace
{

/// Sum over the samples of (cell measure / samples per cell) where `inside(direction)`.
template<typename Inside>
double SampledProjectedSolidAngle(const HemisphereGrid& grid, Inside inside)
{
  double sum = 0.0;
  for (int row = 0; row < grid.SampleRows(); ++row)
  {
    const double weight = grid.CellMeasure(row / grid.SamplesTheta()) / grid.SamplesPerCell();
    for (int column = 0; column < grid.SampleColumns(); ++column)
    {
      if (inside(grid.SampleDirection(row, column)))
      {
        sum += weight;
      }
    }
  }
  return sum;
}
}

TEST(HemisphereGrid, CellMeasuresSumToPi)
{
  for (const auto& bins :
    { std::pair<int, int>{ 1, 1 }, { 7, 13 }, { 32, 128 }, { 64, 256 }, { 1000, 3 } })
  {
    const HemisphereGrid grid(bins.first, bins.second);
    EXPECT_NEAR(grid.TotalMeasure(), Pi, 4e-15 * Pi) << bins.first << " x " << bins.second;
    // Each cell's measure is the integral of cos(theta) sin(theta) over the cell: compare
    // with a 64-point midpoint rule in theta (within 1e-4 of a cell even for a single row).
    for (int row = 0; row < grid.ThetaBins(); row += std::max(1, grid.ThetaBins() / 7))
    {
      const double t0 = grid.RowTheta(row);
      const double t1 = grid.RowTheta(row + 1);
      double integral = 0.0;
      for (int k = 0; k < 64; ++k)
      {
        const double t = t0 + (k + 0.5) * (t1 - t0) / 64;
        integral += std::cos(t) * std::sin(t) * (t1 - t0) / 64;
      }
      EXPECT_NEAR(grid.CellMeasure(row), integral * grid.PhiStep(), 1e-3 * grid.CellMeasure(row));
    }
  }
}

TEST(HemisphereGrid, DirectionCellRoundTrip)
{
  const HemisphereGrid grid(32, 128);
  for (int cell = 0; cell < grid.CellCount(); ++cell)
  {
    ASSERT_EQ(grid.CellOfLocalDirection(grid.CellCentreDirection(cell)), cell);
    EXPECT_EQ(grid.CellIndex(grid.RowOfCell(cell), grid.ColumnOfCell(cell)), cell);
  }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> thetaOf(0.0, Pi / 2);
  std::uniform_real_distribution<double> phiOf(0.0, 2 * Pi);
  for (int k = 0; k < 10000; ++k)
  {
    const double theta = thetaOf(rng);
    const double phi = phiOf(rng);
    double t;
    double p;
    HemisphereGrid::LocalAngles(HemisphereGrid::LocalDirection(theta, phi), t, p);
    ASSERT_NEAR(t, theta, 1e-12);
    ASSERT_NEAR(std::remainder(p - phi, 2 * Pi), 0.0, 1e-12);
    const int cell = grid.CellOfAngles(theta, phi);
    ASSERT_EQ(grid.RowOfCell(cell), static_cast<int>(theta / grid.ThetaStep()));
    ASSERT_EQ(grid.ColumnOfCell(cell), static_cast<int>(phi / grid.PhiStep()));
  }
  // The seam, the horizon, the pole and below the tangent plane.
  EXPECT_EQ(grid.ColumnOfCell(grid.CellOfAngles(0.3, 2 * Pi - 1e-12)), grid.PhiBins() - 1);
  EXPECT_EQ(grid.ColumnOfCell(grid.CellOfAngles(0.3, 2 * Pi)), 0);
  EXPECT_EQ(grid.ColumnOfCell(grid.CellOfAngles(0.3, -1e-9)), grid.PhiBins() - 1);
  EXPECT_EQ(grid.RowOfCell(grid.CellOfAngles(Pi / 2, 1.0)), grid.ThetaBins() - 1);
  EXPECT_EQ(grid.RowOfCell(grid.CellOfLocalDirection({ 0.0, 0.0, 1.0 })), 0);
  EXPECT_EQ(grid.CellOfLocalDirection({ 1.0, 0.0, -1e-9 }), -1);
  EXPECT_EQ(grid.CellOfAngles(std::nan(""), 0.0), -1);
}

TEST(HemisphereGrid, FrameFollowsPartialU)
{
  const glm::dvec3 normal = glm::normalize(glm::dvec3(1.0, 2.0, 3.0));
  const glm::dvec3 partialU(2.0, -1.0, 0.5);
  const HemisphereFrame frame =
    HemisphereFrame::FromPartials({ 1.0, 1.0, 1.0 }, normal, partialU, { 0.0, 1.0, 0.0 });
  EXPECT_NEAR(glm::dot(frame.Tangent, frame.Normal), 0.0, 1e-15);
  EXPECT_NEAR(glm::length(frame.Tangent), 1.0, 1e-15);
  EXPECT_NEAR(glm::length(glm::cross(frame.Normal, frame.Tangent) - frame.Bitangent), 0.0, 1e-15);
  // phi = 0 is dP/du projected onto the tangent plane.
  const glm::dvec3 projected = glm::normalize(partialU - glm::dot(partialU, normal) * normal);
  EXPECT_NEAR(glm::length(frame.Tangent - projected), 0.0, 1e-15);
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, -0.2, 0.9));
  EXPECT_NEAR(glm::length(frame.ToWorld(frame.ToLocal(d)) - d), 0.0, 1e-15);

  // dP/du vanishing (a collapsed edge): the direction dP/du would have, dP/dv x N.
  const HemisphereFrame collapsed = HemisphereFrame::FromPartials(
    { 0.0, 0.0, 0.0 }, { 0.0, 0.0, 1.0 }, { 0.0, 0.0, 0.0 }, { 0.0, 2.0, 0.0 });
  EXPECT_NEAR(glm::length(collapsed.Tangent - glm::dvec3(1.0, 0.0, 0.0)), 0.0, 1e-15);
  // Both vanishing: the world axis least parallel to N, projected.
  const HemisphereFrame fixed = HemisphereFrame::FromPartials({ 0.0, 0.0, 0.0 },
    glm::normalize(glm::dvec3(0.9, 0.1, 0.0)),
    { 0.0, 0.0, 0.0 },
    { 0.0, 0.0, 0.0 });
  EXPECT_NEAR(glm::length(fixed.Tangent - glm::dvec3(0.0, 0.0, 1.0)), 0.0, 1e-15);
}

TEST(HemisphereGrid, FrameOfPatchUsesItsCentre)
{
  const BezierPatch quad(1, 1, { { 0, 0, 0 }, { 2, 0, 0 }, { 0, 1, 0 }, { 2, 1, 0 } });
  const Patch patch(0, UVRect::Unit(), 0, quad);
  const HemisphereFrame frame = HemisphereFrame::OfPatch(patch);
  EXPECT_NEAR(glm::length(frame.Origin - glm::dvec3(1.0, 0.5, 0.0)), 0.0, 1e-15);
  EXPECT_NEAR(glm::length(frame.Normal - glm::dvec3(0.0, 0.0, 1.0)), 0.0, 1e-15);
  EXPECT_NEAR(glm::length(frame.Tangent - glm::dvec3(1.0, 0.0, 0.0)), 0.0, 1e-15);
}

TEST(HemisphereGrid, SamplesLieInTheirCells)
{
  const HemisphereGrid grid(16, 48, 4, 3);
  for (int row = 0; row < grid.SampleRows(); ++row)
  {
    for (int column = 0; column < grid.SampleColumns(); ++column)
    {
      const glm::dvec3 d = grid.SampleDirection(row, column);
      ASSERT_NEAR(glm::length(d), 1.0, 1e-15);
      ASSERT_EQ(grid.CellOfLocalDirection(d),
        grid.CellIndex(row / grid.SamplesTheta(), column / grid.SamplesPhi()));
    }
  }
  // Columns in [phiBegin, phiEnd): the samples whose phi lies there.
  int first;
  int last;
  grid.SampleColumnsIn(0.0, 2 * Pi, first, last);
  EXPECT_EQ(first, 0);
  EXPECT_EQ(last, grid.SampleColumns());
  grid.SampleColumnsIn(grid.SamplePhi(5), grid.SamplePhi(9), first, last);
  EXPECT_EQ(first, 5);
  EXPECT_EQ(last, 9);
  grid.SampleColumnsIn(1.0, 1.0, first, last);
  EXPECT_EQ(first, last);
}

TEST(HemisphereGrid, SamplesFromCentreArePermutation)
{
  for (const auto& k : { std::pair<int, int>{ 1, 1 }, { 3, 3 }, { 4, 2 }, { 5, 5 } })
  {
    const HemisphereGrid grid(4, 8, k.first, k.second);
    const std::vector<int>& order = grid.SamplesFromCentre();
    ASSERT_EQ(static_cast<int>(order.size()), grid.SamplesPerCell());
    EXPECT_EQ(std::set<int>(order.begin(), order.end()).size(), order.size());
    if (k.first % 2 == 1 && k.second % 2 == 1)
    {
      // Odd counts: the first is the central sample.
      EXPECT_EQ(order[0], (k.first / 2) * k.second + k.second / 2);
    }
  }
}

TEST(HemisphereGrid, SamplesIntegrateProjectedSolidAngle)
{
  // A cap theta < alpha has projected solid angle pi sin^2(alpha). The samples are uniform in
  // sin^2(theta), so the sampled value errs by at most half a sample stratum of one row.
  const HemisphereGrid grid(16, 64, 3, 3);
  for (const double alpha : { 0.1, 0.5, 0.77, 1.2, 1.5 })
  {
    const double sampled = SampledProjectedSolidAngle(
      grid, [alpha](const glm::dvec3& d) { return d.z > std::cos(alpha); });
    const int row = static_cast<int>(alpha / grid.ThetaStep());
    const double bound = grid.CellMeasure(row) * grid.PhiBins() * 0.5 / grid.SamplesTheta();
    EXPECT_NEAR(sampled, Pi * std::sin(alpha) * std::sin(alpha), bound + 1e-12) << alpha;
  }
  // A region bounded by a great circle tilted by gamma from the tangent plane:
  // {d : d . m > 0} with m at angle gamma from N has projected solid angle pi (1 + cos g) / 2
  // (its orthographic projection is half the unit disk plus half an ellipse of axes 1, cos g).
  // The error falls as the samples per cell grow.
  for (const double gamma : { 0.3, 1.0, 2.2 })
  {
    const glm::dvec3 m(std::sin(gamma), 0.0, std::cos(gamma));
    const double exact = Pi * (1.0 + std::cos(gamma)) / 2.0;
    double previous = 1.0;
    for (const int k : { 1, 4, 16 })
    {
      const HemisphereGrid fine(8, 16, k, k);
      const double error = std::fabs(SampledProjectedSolidAngle(fine,
                                       [&m](const glm::dvec3& d) { return glm::dot(d, m) > 0.0; }) -
        exact);
      EXPECT_LT(error, previous) << "gamma " << gamma << " samples " << k;
      previous = error;
    }
    EXPECT_LT(previous, 2e-3 * exact);
  }
}

TEST(HemisphereGrid, SampleFractionIsCosineWeighted)
{
  // The lower half (in theta) of a row holds a cosine-weighted fraction
  // (sin^2 tm - sin^2 t0) / (sin^2 t1 - sin^2 t0) of the row, not one half; the fraction of
  // samples inside must match the weighted one.
  const HemisphereGrid grid(4, 4, 16, 1);
  for (int row = 0; row < grid.ThetaBins(); ++row)
  {
    const double t0 = grid.RowTheta(row);
    const double t1 = grid.RowTheta(row + 1);
    const double tm = 0.5 * (t0 + t1);
    const double weighted = (std::pow(std::sin(tm), 2) - std::pow(std::sin(t0), 2)) /
      (std::pow(std::sin(t1), 2) - std::pow(std::sin(t0), 2));
    int inside = 0;
    for (int a = 0; a < grid.SamplesTheta(); ++a)
    {
      inside += grid.SampleCosTheta(row * grid.SamplesTheta() + a) > std::cos(tm) ? 1 : 0;
    }
    EXPECT_NEAR(static_cast<double>(inside) / grid.SamplesTheta(),
      weighted,
      0.5 / grid.SamplesTheta() + 1e-12)
      << "row " << row;
  }
}

TEST(HemisphereGrid, RejectsBadSizes)
{
  EXPECT_THROW(HemisphereGrid(0, 8), std::invalid_argument);
  EXPECT_THROW(HemisphereGrid(8, 70000), std::invalid_argument);
  EXPECT_THROW(HemisphereGrid(8, 8, 0, 1), std::invalid_argument);
  EXPECT_THROW(HemisphereGrid(8, 8, 1, 17), std::invalid_argument);
}

TEST(HemisphereGrid, CellOfLocalDirectionIsTheCellOfItsAngles)
{
  // The edge tests without trigonometry must give the atan2 path's cell for every direction:
  // random ones, and ones at and within a few ulps to 1e-6 rad of the row and column edges,
  // the pole and the horizon, on grids of odd and even sizes.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const auto& size : { std::pair<int, int>(32, 128), std::pair<int, int>(7, 13) })
  {
    const HemisphereGrid grid(size.first, size.second, 1, 1);
    const double dTheta = 0.5 * Pi / size.first;
    const double dPhi = 2.0 * Pi / size.second;
    std::size_t compared = 0;
    auto check = [&](double theta, double phi)
    {
      const glm::dvec3 local(
        std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      double t;
      double p;
      HemisphereGrid::LocalAngles(local, t, p);
      ASSERT_EQ(grid.CellOfLocalDirection(local), grid.CellOfAngles(t, p))
        << "theta " << theta << " phi " << phi;
      ++compared;
    };
    for (int k = 0; k < 20000; ++k)
    {
      check(0.5 * Pi * unit(rng), 2.0 * Pi * unit(rng) - Pi);
    }
    for (const double offset : { 0.0, 1e-15, -1e-15, 1e-12, -1e-12, 1e-9, -1e-9, 1e-6, -1e-6 })
    {
      for (int r = 0; r <= size.first; ++r)
      {
        check(std::clamp(r * dTheta + offset, 0.0, 0.5 * Pi), 2.0 * Pi * unit(rng));
      }
      for (int c = -size.second; c <= size.second; ++c)
      {
        check(0.5 * Pi * unit(rng), c * dPhi + offset);
      }
    }
    EXPECT_GT(compared, 20000u);
  }
}
