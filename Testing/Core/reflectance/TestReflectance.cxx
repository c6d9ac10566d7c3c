// SPDX-License-Identifier: BSD-3-Clause
// The BRDF models (paper §3.5): the tabulated BRDF format and its errors, the phong lobe's
// energy-conserving normalization, and the weight tables w(out, in-cell): their rows
// reproduce the albedo, their columns conserve energy, their strip sums and the whole-hemisphere
// Reflect agree with cell sums.
#include "cover/HemisphereGrid.h"
#include "math/Constants.h"
#include "reflectance/Reflectance.h"
#include "reflectance/ReflectanceWeights.h"
#include "scene/BrdfTable.h"
#include "scene/InputError.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

using namespace sphcover;

namespace
{

std::string ClayPath()
{
  return std::string(SPHCOVER_DATA_DIR) + "/brdf/clay.brdf.csv";
}

/// One material of each non-diffuse kind: phong (diffuse + lobe of the given exponent), a
/// coloured mirror and the clay table.
std::tuple<Material, Material, Material> NonDiffuseMaterials(double exponent)
{
  Material phong;
  phong.Type = MaterialType::Phong;
  phong.Diffuse = glm::dvec3(0.1, 0.3, 0.5);
  phong.Specular = glm::dvec3(0.5, 0.3, 0.1);
  phong.PhongExponent = exponent;
  Material mirror;
  mirror.Type = MaterialType::Mirror;
  mirror.Specular = glm::dvec3(0.9, 0.8, 0.7);
  Material clay;
  clay.Type = MaterialType::Tabulated;
  clay.TableFile = ClayPath();
  return { phong, mirror, clay };
}

/// The clay formula of Data/brdf/tools/make_clay_table.py.
glm::dvec3 Clay(double ti, double to, double dphi)
{
  return glm::dvec3(0.75, 0.55, 0.35) / Pi *
    (1.0 + 0.8 * std::sin(ti) * std::sin(to) * std::cos(dphi));
}

/// The error message of parsing `text`, or "" if it parses.
std::string ParseError(const std::string& text)
{
  std::istringstream in(text);
  try
  {
    BrdfTable::Parse(in, "t.brdf.csv");
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}

/// integral f(in, out) cos(theta_in) dw_in by a fine midpoint rule in (sin^2 theta, phi),
/// independent of the code under test.
glm::dvec3 IntegrateAlbedo(const Reflectance& model, double thetaOut)
{
  const int steps = 400;
  const int azimuths = 800;
  const glm::dvec3 out(std::sin(thetaOut), 0.0, std::cos(thetaOut));
  glm::dvec3 sum(0.0);
  for (int a = 0; a < steps; ++a)
  {
    const double s = (a + 0.5) / steps;
    for (int c = 0; c < azimuths; ++c)
    {
      const double phi = (c + 0.5) * 2.0 * Pi / azimuths;
      const glm::dvec3 in(
        std::sqrt(s) * std::cos(phi), std::sqrt(s) * std::sin(phi), std::sqrt(1.0 - s));
      sum += model.Evaluate(in, out);
    }
  }
  return sum * (0.5 / steps) * (2.0 * Pi / azimuths);
}
}

TEST(BrdfTable, ReadsTheShippedClayTable)
{
  const BrdfTable table = BrdfTable::Load(ClayPath());
  EXPECT_EQ(table.ThetaIn().size(), 10u);
  EXPECT_EQ(table.DeltaPhi().size(), 13u);
  // At the grid points the table is the formula (9 significant digits in the file).
  for (double ti : { 0.0, 30.0, 80.0 })
  {
    for (double dphi : { 0.0, 45.0, 180.0 })
    {
      const glm::dvec3 f = table.Evaluate(ti * Pi / 180, 50.0 * Pi / 180, dphi * Pi / 180);
      const glm::dvec3 g = Clay(ti * Pi / 180, 50.0 * Pi / 180, dphi * Pi / 180);
      for (int b = 0; b < 3; ++b)
      {
        EXPECT_NEAR(f[b], g[b], 1e-8);
      }
    }
  }
  // Isotropic and mirror-symmetric in delta_phi; clamped beyond 90 degrees.
  const glm::dvec3 a = table.Evaluate(0.3, 0.7, 0.4);
  EXPECT_EQ(a, table.Evaluate(0.3, 0.7, -0.4));
  EXPECT_NEAR(a.y, table.Evaluate(0.3, 0.7, 0.4 + 2 * Pi).y, 1e-14);
  // Constant albedo, as designed: the cos(delta_phi) term integrates to zero.
  for (double theta : { 0.0, 0.5, 1.0, 1.5 })
  {
    const glm::dvec3 albedo = table.Albedo(theta);
    EXPECT_NEAR(albedo.x, 0.75, 1e-6);
    EXPECT_NEAR(albedo.y, 0.55, 1e-6);
    EXPECT_NEAR(albedo.z, 0.35, 1e-6);
  }
}

TEST(BrdfTable, ErrorsNameFileLineAndProblem)
{
  const std::string header = "# comment\ntheta_in,theta_out,delta_phi,r,g,b\n";
  EXPECT_EQ(ParseError(header + "0,0,0,0.1,0.1,0.1\n"), "");
  EXPECT_EQ(ParseError("theta,phi\n"),
    "t.brdf.csv: line 1: expected the header 'theta_in,theta_out,delta_phi,r,g,b'");
  EXPECT_EQ(ParseError(header + "0,0,0,0.1,0.1\n"),
    "t.brdf.csv: line 3: expected 6 comma-separated numbers, got 5");
  EXPECT_EQ(ParseError(header + "0,0,0,0.1,abc,0.1\n"),
    "t.brdf.csv: line 3: expected a number in column 5");
  EXPECT_EQ(ParseError(header + "0,0,0,0.1,nan,0.1\n"),
    "t.brdf.csv: line 3: not a finite number in column 5");
  EXPECT_EQ(ParseError(header + "0,95,0,0.1,0.1,0.1\n"),
    "t.brdf.csv: line 3: theta_in and theta_out must be in [0, 90] degrees");
  EXPECT_EQ(ParseError(header + "0,0,200,0.1,0.1,0.1\n"),
    "t.brdf.csv: line 3: delta_phi must be in [0, 180] degrees");
  EXPECT_EQ(
    ParseError(header + "0,0,0,0.1,-0.1,0.1\n"), "t.brdf.csv: line 3: BRDF values must be >= 0");
  EXPECT_EQ(ParseError(header + "0,0,0,0.1,0.1,0.1\n\n0,0,0,0.2,0.1,0.1\n"),
    "t.brdf.csv: line 5: duplicate grid point (first given on line 3)");
  EXPECT_EQ(ParseError(header + "0,0,0,0.1,0.1,0.1\n0,0,90,0.1,0.1,0.1\n90,0,0,0.1,0.1,0.1\n"),
    "t.brdf.csv: line 5: missing grid point theta_in = 90, theta_out = 0, delta_phi = 90 (the "
    "rows must give every combination of the listed angles: 2 x 1 x 2 values, 3 rows)");
  EXPECT_EQ(ParseError(header), "t.brdf.csv: line 2: the table has no rows");
  EXPECT_EQ(ParseError(""),
    "t.brdf.csv: line 1: expected the header "
    "'theta_in,theta_out,delta_phi,r,g,b'");
  // A constant f = 0.5 / sr reflects pi / 2 > 1 of what it receives.
  const std::string bright = ParseError(header + "0,0,0,0.1,0.5,0.1\n");
  EXPECT_NE(bright.find("t.brdf.csv: directional albedo 1.5708 exceeds 1 at theta_out = 0 degrees "
                        "in band 1"),
    std::string::npos)
    << bright;
  EXPECT_THROW(BrdfTable::Load(ClayPath() + ".missing"), InputError);
}

TEST(Reflectance, PhongLobeReflectsExactlyItsAlbedoFromEveryDirection)
{
  // The energy-conserving normalization (Reflectance.h): the directional albedo is
  // k_d + k_s for every direction, checked by an independent fine quadrature; the BRDF is
  // reciprocal.
  for (double exponent : { 0.0, 5.0, 40.0 })
  {
    Material material;
    material.Type = MaterialType::Phong;
    material.Diffuse = glm::dvec3(0.2, 0.1, 0.0);
    material.Specular = glm::dvec3(0.3, 0.5, 0.9);
    material.PhongExponent = exponent;
    const Reflectance model(material);
    for (double theta : { 0.0, 0.6, 1.2, 1.45 })
    {
      const glm::dvec3 albedo = IntegrateAlbedo(model, theta);
      for (int b = 0; b < 3; ++b)
      {
        EXPECT_NEAR(albedo[b], material.Diffuse[b] + material.Specular[b], 5e-3)
          << "n = " << exponent << ", theta = " << theta << ", band " << b;
      }
    }
    const glm::dvec3 in(0.3, -0.2, std::sqrt(1 - 0.13));
    const glm::dvec3 out(-0.5, 0.1, std::sqrt(1 - 0.26));
    EXPECT_NEAR(model.Evaluate(in, out).z, model.Evaluate(out, in).z, 1e-12);
    // For a narrow lobe, near normal incidence the classic (n + 2) / (2 pi) holds.
    if (exponent >= 40.0)
      EXPECT_NEAR(model.LobeNormalization(0.0) * model.LobeNormalization(0.0),
        (exponent + 2) / (2 * Pi),
        0.03 * (exponent + 2) / (2 * Pi))
        << "n = " << exponent;
  }
  Material tooBright;
  tooBright.Type = MaterialType::Phong;
  tooBright.Diffuse = glm::dvec3(0.6);
  tooBright.Specular = glm::dvec3(0.5);
  EXPECT_THROW(Reflectance{ tooBright }, std::invalid_argument);
}

TEST(ReflectanceWeights, RowsGiveTheAlbedoColumnsConserveEnergy)
{
  const HemisphereGrid grid(16, 48);
  const auto [phong, mirror, clay] = NonDiffuseMaterials(20.0);
  for (const Material& material : { phong, mirror, clay })
  {
    const Reflectance model(material);
    const ReflectanceWeights table(model, grid);
    for (int ro = 0; ro < grid.ThetaBins(); ++ro)
    {
      // sum over every in-cell toward one out cell = the albedo (the furnace identity).
      glm::dvec3 row(0.0);
      // sum over every out cell of Omega_o w(o, c) for one in-cell c = Omega_c a(c) (energy).
      glm::dvec3 column(0.0);
      for (int r = 0; r < grid.ThetaBins(); ++r)
      {
        row += table.RowWeight(ro, r);
        for (int d = 0; d < grid.PhiBins(); ++d)
        {
          column += grid.CellMeasure(r) * table.Weight(r, ro, d);
        }
      }
      // The table holds the BRDF without its Lambertian part.
      const glm::dvec3 albedo =
        model.Albedo(grid.RowTheta(ro) + 0.5 * grid.ThetaStep()) - model.LambertianReflectance();
      for (int b = 0; b < 3; ++b)
      {
        EXPECT_NEAR(row[b], albedo[b], 1e-3) << MaterialTypeName(material.Type);
        EXPECT_NEAR(row[b], table.RowAlbedo(ro)[b], 1e-12);
        EXPECT_NEAR(
          column[b], grid.CellMeasure(ro) * table.RowAlbedo(ro)[b], 1e-12 * grid.CellMeasure(ro));
      }
    }
    // The scaled table is the sampled BRDF up to a small correction.
    EXPECT_LT(table.LargestScaling(), 0.05) << MaterialTypeName(material.Type);
    // Strip sums agree with cell sums, across the phi seam too.
    for (int ro : { 0, 7, 15 })
    {
      for (int ri : { 0, 7, 15 })
      {
        for (int ob : { 0, 5, 40 })
        {
          const int oe = std::min(grid.PhiBins(), ob + 8);
          const int cb = 30;
          const int ce = 48;
          glm::dvec3 cells(0.0);
          for (int o = ob; o < oe; ++o)
          {
            glm::dvec3 strip(0.0);
            for (int c = cb; c < ce; ++c)
            {
              strip += table.Weight(ro, ri, (c - o + grid.PhiBins()) % grid.PhiBins());
            }
            const glm::dvec3 fast = table.StripWeight(ro, o, ri, cb, ce);
            EXPECT_NEAR(fast.y, strip.y, 1e-12);
            cells += strip;
          }
          const glm::dvec3 pair = table.StripPairWeight(ro, ob, oe, ri, cb, ce);
          for (int b = 0; b < 3; ++b)
          {
            EXPECT_NEAR(pair[b], cells[b], 1e-12);
          }
        }
      }
    }
  }
  // The mirror's table is the delta: k_s on the cell across the normal, nothing else.
  const Reflectance model(mirror);
  const ReflectanceWeights table(model, grid);
  EXPECT_EQ(table.Weight(3, 3, grid.PhiBins() / 2), mirror.Specular);
  EXPECT_EQ(table.Weight(3, 3, grid.PhiBins() / 2 + 1), glm::dvec3(0.0));
  EXPECT_FALSE(table.RowsCoupled(3, 4));
}

TEST(ReflectanceWeights, PhongTableFollowsTheLobe)
{
  // A weight of the table over the in-cell's measure is the BRDF between the two cells: the
  // peak lies on the mirror cell and the value there matches Evaluate within the sampling.
  const HemisphereGrid grid(32, 128);
  Material phong;
  phong.Type = MaterialType::Phong;
  phong.Diffuse = glm::dvec3(0.0);
  phong.Specular = glm::dvec3(1.0);
  phong.PhongExponent = 10.0;
  const Reflectance model(phong);
  const ReflectanceWeights table(model, grid);
  const int row = 12;
  int best = -1;
  double peak = -1.0;
  for (int d = 0; d < grid.PhiBins(); ++d)
  {
    const double v = table.Weight(row, row, d).x;
    if (v > peak)
    {
      peak = v;
      best = d;
    }
  }
  EXPECT_TRUE(best == grid.PhiBins() / 2 || best == grid.PhiBins() / 2 - 1) << best;
  const double theta = grid.RowTheta(row) + 0.5 * grid.ThetaStep();
  const double f = model.Evaluate(theta, theta, Pi).x;
  EXPECT_NEAR(table.Weight(row, row, grid.PhiBins() / 2).x / grid.CellMeasure(row), f, 0.05 * f);
}

TEST(ReflectanceWeights, ReflectEqualsTheCellSum)
{
  // Reflect (direct terms and Fourier transforms over the column difference) against the plain
  // sum I(o) = sum_c w(o, c) e_c over all cells, for every kind, on even and odd PhiBins
  // (the mirror splits k_s over two cells then) and an incident radiance with empty rows.
  const auto [phong, mirror, clay] = NonDiffuseMaterials(40.0);
  Material wide = phong;
  wide.PhongExponent = 2.0;
  for (const HemisphereGrid& grid : { HemisphereGrid(16, 64), HemisphereGrid(9, 35) })
  {
    const std::size_t cells = static_cast<std::size_t>(grid.CellCount());
    std::vector<glm::dvec3> incident(cells, glm::dvec3(0.0));
    for (std::size_t c = 0; c < cells; ++c)
    {
      const int row = grid.RowOfCell(static_cast<int>(c));
      if (row % 3 != 1)
      {
        // A deterministic, uneven pattern, with a bright spot.
        incident[c] = glm::dvec3(
          1.0 + std::sin(0.37 * c), 0.5 + 0.5 * std::cos(0.11 * c), c % 17 == 0 ? 40.0 : 0.25);
      }
    }
    for (const Material& material : { phong, wide, mirror, clay })
    {
      const Reflectance model(material);
      const ReflectanceWeights table(model, grid);
      // Even in the column difference (what makes the transforms real), up to the rounding of
      // the cumulative sums Weight reads.
      for (int ro = 0; ro < grid.ThetaBins(); ro += 4)
      {
        const int ri = std::min(ro + 1, grid.ThetaBins() - 1);
        const glm::dvec3 scale = table.RowWeight(ro, ri);
        for (int d = 1; d < grid.PhiBins(); ++d)
        {
          const glm::dvec3 a = table.Weight(ro, ri, d);
          const glm::dvec3 b = table.Weight(ro, ri, grid.PhiBins() - d);
          for (int k = 0; k < 3; ++k)
          {
            EXPECT_NEAR(a[k], b[k], 1e-13 * scale[k]);
          }
        }
      }
      std::vector<glm::dvec3> fast;
      table.Reflect(incident, fast);
      ASSERT_EQ(fast.size(), cells);
      double worst = 0.0;
      double largest = 0.0;
      for (std::size_t o = 0; o < cells; ++o)
      {
        const int ro = grid.RowOfCell(static_cast<int>(o));
        const int co = grid.ColumnOfCell(static_cast<int>(o));
        glm::dvec3 sum(0.0);
        for (std::size_t c = 0; c < cells; ++c)
        {
          const int ri = grid.RowOfCell(static_cast<int>(c));
          const int d =
            (grid.ColumnOfCell(static_cast<int>(c)) - co + grid.PhiBins()) % grid.PhiBins();
          sum += table.Weight(ro, ri, d) * incident[c];
        }
        for (int b = 0; b < 3; ++b)
        {
          EXPECT_GE(fast[o][b], 0.0);
          worst = std::max(worst, std::fabs(fast[o][b] - sum[b]));
          largest = std::max(largest, sum[b]);
        }
      }
      EXPECT_GT(largest, 0.0);
      EXPECT_LT(worst, 1e-12 * largest)
        << MaterialTypeName(material.Type) << " " << grid.ThetaBins() << "x" << grid.PhiBins();
    }
  }
}
