// SPDX-License-Identifier: BSD-3-Clause
// The R-buffer of paper §4.2.5 and its two fills: coverage classification, the projection
// fill's pole / seam / horizon / depth handling against Lambert's exact projected solid angle
// of a polygon, culling, and the agreement of the projection and ray-casting fills.
#include "cover/RBuffer.h"

#include "CoverTestUtilities.h"
#include "cover/CandidateCulling.h"
#include "cover/RayCastFill.h"
#include "math/Constants.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{

/// Projected solid angle of the samples covered by `source` (sample resolution, no rounding
/// to cells).
double SampledProjectedSolidAngle(const RBuffer& buffer, int32_t source)
{
  const HemisphereGrid& grid = buffer.Grid();
  double sum = 0.0;
  for (int row = 0; row < grid.SampleRows(); ++row)
  {
    const double weight = grid.CellMeasure(row / grid.SamplesTheta()) / grid.SamplesPerCell();
    for (int column = 0; column < grid.SampleColumns(); ++column)
    {
      sum += buffer.SampleSource(grid.SampleIndex(row, column)) == source ? weight : 0.0;
    }
  }
  return sum;
}

double CellProjectedSolidAngle(const RBuffer& buffer, int32_t source)
{
  const HemisphereGrid& grid = buffer.Grid();
  double sum = 0.0;
  for (int cell = 0; cell < grid.CellCount(); ++cell)
  {
    sum += buffer.CellSource(cell) == source ? grid.CellMeasureOfCell(cell) : 0.0;
  }
  return sum;
}

/// A unit floor patch at the origin facing +z (dP/du = +x): the receiver, patch 0.
Patch Floor()
{
  return Patch(0, UVRect::Unit(), 0, Parallelogram({ -0.5, -0.5, 0.0 }, { 1, 0, 0 }, { 0, 1, 0 }));
}

/// The rectangle's polygon in the order origin, +e1, +e1+e2, +e2.
std::vector<glm::dvec3> Polygon(const glm::dvec3& origin,
  const glm::dvec3& e1,
  const glm::dvec3& e2)
{
  return { origin, origin + e1, origin + e1 + e2, origin + e2 };
}

struct FillCase
{
  const char* Name;
  glm::dvec3 Origin;
  glm::dvec3 E1;
  glm::dvec3 E2;
  /// The part above the tangent plane (for the Lambert reference).
  std::vector<glm::dvec3> Visible;
};
}

TEST(RBuffer, ClassifiesByCoverageOfSurfacesThenPatches)
{
  // One cell per theta row: the carries of the error diffusion restart at every row, so each
  // cell is a plain plurality vote.
  const HemisphereGrid grid(4, 1, 3, 3);
  RBuffer buffer(grid);
  buffer.Reset(0);
  // Patches 0 and 1 belong to surface 0, patch 2 to surface 1.
  const std::vector<int32_t> surfaces{ 0, 0, 1 };
  auto set = [&](int cell, const std::vector<int32_t>& sources)
  {
    for (int k = 0; k < 9; ++k)
    {
      buffer.SetSample(grid.SampleIndex(cell * 3 + k / 3, k % 3),
        sources[static_cast<size_t>(k)],
        1.0f + k,
        false);
    }
  };
  const int32_t none = RBuffer::NoSource;
  // Cell 0: 5 of patch 0 against 4 empty.
  set(0, { 0, 0, 0, 0, 0, none, none, none, none });
  // Cell 1: surface 0 covers 5 (3 + 2) against 4 empty: surface 0 wins, then patch 0.
  set(1, { 0, 0, 0, 1, 1, none, none, none, none });
  // Cell 2: 4 to 4 between patch 1 and patch 2 (other surfaces): the tie goes to the one at the
  // central sample (index 4), patch 2.
  set(2, { 1, 1, 1, 1, 2, 2, 2, 2, none });
  // Cell 3: empty but for one sample.
  set(3, { none, none, none, none, none, none, none, none, 2 });
  buffer.Classify(nullptr, &surfaces);
  EXPECT_EQ(buffer.CellSource(0), 0);
  EXPECT_EQ(buffer.CellVotes(0), 5);
  EXPECT_EQ(buffer.CellSource(1), 0);
  EXPECT_EQ(buffer.CellFlags(1) & RBuffer::CellTie, 0);
  EXPECT_EQ(buffer.CellSource(2), 2);
  EXPECT_NE(buffer.CellFlags(2) & RBuffer::CellTie, 0);
  EXPECT_EQ(buffer.CellSource(3), none);
  // The cell's R is its winner's at the winner's sample nearest the centre: sample 4 of cell 2
  // (depth 5), sample 4 of cell 0 (depth 5), sample 0 of cell 1 (patch 0 is not at the centre:
  // order from the centre visits 1, 3, 5, 7 first; sample 1 has depth 2).
  EXPECT_FLOAT_EQ(buffer.CellDepth(2), 5.0f);
  EXPECT_FLOAT_EQ(buffer.CellDepth(0), 5.0f);
  EXPECT_FLOAT_EQ(buffer.CellDepth(1), 2.0f);
  // Without surfaces, every patch votes alone: cell 1 goes empty (4 > 3 > 2).
  buffer.Classify(nullptr);
  EXPECT_EQ(buffer.CellSource(1), none);
  EXPECT_NEAR(
    buffer.CoveredProjectedSolidAngle(), grid.CellMeasure(0) + grid.CellMeasure(2), 1e-15);
}

TEST(RBuffer, ErrorDiffusionAlongARowKeepsEachSourcesCoverage)
{
  // A row of 9 cells, each a third covered by patch 0 (3 of its 9 samples) and two thirds by
  // patch 1 (another surface): a cell-by-cell plurality vote gives every cell to patch 1 and
  // patch 0 nothing (a bias of -100 %); the carry gives patch 0 one cell in three, exactly its
  // coverage. The same with a third surface split into two patches (2 and 3) that cover the
  // third between them (2 + 1 samples): the surface gets three cells and its patches their
  // shares, 2 and 1.
  const HemisphereGrid grid(1, 9, 3, 3);
  RBuffer buffer(grid);
  for (const bool split : { false, true })
  {
    buffer.Reset(0);
    for (int column = 0; column < 9; ++column)
    {
      for (int k = 0; k < 9; ++k)
      {
        const int32_t source = k < 3 ? (split ? (k < 2 ? 2 : 3) : 0) : 1;
        buffer.SetSample(grid.SampleIndex(k / 3, column * 3 + k % 3), source, 1.0f, false);
      }
    }
    const std::vector<int32_t> surfaces{ 0, 1, 2, 2 };
    buffer.Classify(nullptr, &surfaces, true);
    std::vector<int> cells(4, 0);
    for (int cell = 0; cell < 9; ++cell)
    {
      ASSERT_GE(buffer.CellSource(cell), 0);
      ++cells[static_cast<size_t>(buffer.CellSource(cell))];
    }
    EXPECT_EQ(cells[1], 6);
    if (split)
    {
      EXPECT_EQ(cells[2], 2);
      EXPECT_EQ(cells[3], 1);
    }
    else
    {
      EXPECT_EQ(cells[0], 3);
    }
  }
}

TEST(RBuffer, FillsMatchLambertAtPoleSeamAndHorizon)
{
  // Sources seen from the floor's centre: a square over the pole (its projection contains
  // theta = 0), a wall across the phi = 0 seam (T = +x), and a wall crossing the tangent plane
  // (the half below it must be clipped).
  const std::vector<FillCase> cases = {
    { "pole", { -1.0, -0.7, 1.0 }, { 0, 1.6, 0 }, { 2.2, 0, 0 }, {} },
    { "seam", { 1.0, -1.0, 0.2 }, { 0, 0, 1.3 }, { 0, 2.0, 0 }, {} },
    { "horizon", { 1.0, -0.6, -1.0 }, { 0, 0, 2.0 }, { 0, 1.5, 0 }, {} },
  };
  const std::vector<std::vector<glm::dvec3>> visible = {
    Polygon({ -1.0, -0.7, 1.0 }, { 0, 1.6, 0 }, { 2.2, 0, 0 }),
    Polygon({ 1.0, -1.0, 0.2 }, { 0, 0, 1.3 }, { 0, 2.0, 0 }),
    Polygon({ 1.0, -0.6, 0.0 }, { 0, 0, 1.0 }, { 0, 1.5, 0 }),
  };
  const HemisphereGrid grid(32, 128, 3, 3);
  for (size_t c = 0; c < cases.size(); ++c)
  {
    std::vector<Patch> patches{ Floor() };
    // Split into 2 x 2 so that patch boundaries run through the region too.
    AppendSplit(patches, Parallelogram(cases[c].Origin, cases[c].E1, cases[c].E2), 1, 2, 2);
    const double exact =
      LambertProjectedSolidAngle(patches[0].Point, patches[0].Normal, visible[c]);
    for (const RBufferFill fill : { RBufferFill::Projection, RBufferFill::RayCasting })
    {
      const auto filler = RBufferFiller::Create(fill, patches, grid);
      RBuffer buffer(grid);
      filler->Fill(0, buffer, nullptr);
      double sampled = 0.0;
      double cells = 0.0;
      for (int32_t j = 1; j < 5; ++j)
      {
        sampled += SampledProjectedSolidAngle(buffer, j);
        cells += CellProjectedSolidAngle(buffer, j);
      }
      std::printf("[ RBuffer  ] %-8s %-10s exact %.6f samples %.6f (%+.1e) cells %.6f (%+.1e)\n",
        cases[c].Name,
        RBufferFillName(fill),
        exact,
        sampled,
        sampled / exact - 1,
        cells,
        cells / exact - 1);
      // Samples: only the quadrature error of the sample grid remains. It is largest for
      // edges parallel to the normal (these walls' vertical edges), which project onto
      // meridians and cut every row's samples at the same phi: up to half a sample column,
      // (1/2)(pi / (PhiBins SamplesPhi)) ~ 4e-3 per edge over the rows it spans.
      EXPECT_NEAR(sampled, exact, 5e-3 * exact) << cases[c].Name << " " << RBufferFillName(fill);
      // Cells: each boundary cell is rounded to all or nothing.
      EXPECT_NEAR(cells, exact, 2e-2 * exact) << cases[c].Name << " " << RBufferFillName(fill);
      EXPECT_EQ(SampledProjectedSolidAngle(buffer, 0), 0.0) << "a flat patch never sees itself";
    }
  }
}

TEST(RBuffer, NearerPatchWinsTheDepthTest)
{
  // A small square at height 0.5 in front of a large one at height 1.5, both facing down, and
  // between them a square at height 1 facing up: it turns its back to the receiver, so it is no
  // source, but being opaque it hides the large square behind it (unless back faces are made
  // transparent, paper §4.2.1's culling).
  std::vector<Patch> patches{ Floor() };
  AppendSplit(patches, Parallelogram({ -2, -2, 1.5 }, { 0, 4, 0 }, { 4, 0, 0 }), 1, 1, 1);
  AppendSplit(patches, Parallelogram({ -0.2, -0.3, 0.5 }, { 0, 0.5, 0 }, { 0.6, 0, 0 }), 2, 1, 1);
  AppendSplit(patches, Parallelogram({ 0.85, -0.4, 1.0 }, { 0.35, 0, 0 }, { 0, 0.8, 0 }), 3, 1, 1);
  const glm::dvec3 p = patches[0].Point;
  const glm::dvec3 n = patches[0].Normal;
  const double far =
    LambertProjectedSolidAngle(p, n, Polygon({ -2, -2, 1.5 }, { 0, 4, 0 }, { 4, 0, 0 }));
  const double near =
    LambertProjectedSolidAngle(p, n, Polygon({ -0.2, -0.3, 0.5 }, { 0, 0.5, 0 }, { 0.6, 0, 0 }));
  const double back =
    LambertProjectedSolidAngle(p, n, Polygon({ 0.85, -0.4, 1.0 }, { 0.35, 0, 0 }, { 0, 0.8, 0 }));
  const HemisphereGrid grid(32, 128, 3, 3);
  for (const bool backFacesOcclude : { true, false })
  {
    RBufferFillOptions options;
    options.BackFacesOcclude = backFacesOcclude;
    for (const RBufferFill fill : { RBufferFill::Projection, RBufferFill::RayCasting })
    {
      const auto filler = RBufferFiller::Create(fill, patches, grid, options);
      RBuffer buffer(grid);
      CullingStatistics culling;
      filler->Fill(0, buffer, &culling);
      const double hidden = near + (backFacesOcclude ? back : 0.0);
      EXPECT_NEAR(SampledProjectedSolidAngle(buffer, 2), near, 2e-3 * near)
        << RBufferFillName(fill);
      EXPECT_NEAR(SampledProjectedSolidAngle(buffer, 1), far - hidden, 2e-3 * far)
        << RBufferFillName(fill) << " back faces occlude " << backFacesOcclude;
      EXPECT_EQ(SampledProjectedSolidAngle(buffer, 3), 0.0) << RBufferFillName(fill);
      // Every cell's R is the distance to its plane along a direction of its row:
      // height / cos(theta) for theta within the row.
      for (int cell = 0; cell < grid.CellCount(); ++cell)
      {
        const int32_t source = buffer.CellSource(cell);
        if (source != 1 && source != 2)
        {
          continue;
        }
        const double height = source == 1 ? 1.5 : 0.5;
        const int row = grid.RowOfCell(cell);
        const double lo = height / std::cos(grid.RowTheta(row));
        const double hi = height / std::cos(grid.RowTheta(row + 1));
        ASSERT_GE(buffer.CellDepth(cell), lo * (1 - 1e-6)) << RBufferFillName(fill);
        ASSERT_LE(buffer.CellDepth(cell), hi * (1 + 1e-6)) << RBufferFillName(fill);
      }
      if (fill == RBufferFill::Projection)
      {
        // The receiver itself lies in its tangent plane, the up-facing square turns its back
        // (projected as an occluder only if back faces occlude); the two others are kept.
        EXPECT_EQ(culling.Candidates, 4u);
        EXPECT_EQ(culling.BelowTangentPlane, 1u);
        EXPECT_EQ(culling.BackFacing, 1u);
        EXPECT_EQ(culling.Kept, 2u);
        EXPECT_EQ(culling.Occluders > 0, backFacesOcclude);
        // Paper §4.3 Step 3 data: without occlusion the far square would take all of its
        // projection, the near one keeps all of its own; an occluder is no source.
        ASSERT_TRUE(buffer.HasUnoccluded());
        double unoccludedFar = 0.0;
        double unoccludedNear = 0.0;
        for (const auto& entry : buffer.UnoccludedProjectedSolidAngles())
        {
          unoccludedFar = entry.first == 1 ? entry.second : unoccludedFar;
          unoccludedNear = entry.first == 2 ? entry.second : unoccludedNear;
          EXPECT_NE(entry.first, 3) << "an occluder is no source";
        }
        EXPECT_NEAR(unoccludedFar, far, 2e-3 * far);
        EXPECT_NEAR(unoccludedNear, near, 2e-3 * near);
        EXPECT_NEAR(unoccludedFar - SampledProjectedSolidAngle(buffer, 1), hidden, 2e-3 * far);
      }
      else
      {
        EXPECT_FALSE(buffer.HasUnoccluded());
      }
    }
  }
}

TEST(RBuffer, CullingIsRigorousAndCounted)
{
  // Inside the closed furnace cube every face is front-facing from every point; the receiver's
  // coplanar neighbours lie in its tangent plane. Nothing visible may be culled (every
  // characteristic point is covered completely, checked in TestSphericalCover); here the counts
  // must add up and match the geometry exactly. Outside the cube every point sees the backs of
  // the faces opposite.
  const Scene scene = LoadSceneFile(ScenePath("furnace_box.scene"));
  const std::vector<Patch> patches = SplitScene(scene, 3);
  const HemisphereGrid grid(16, 64, 2, 2);
  const auto filler = RBufferFiller::Create(RBufferFill::Projection, patches, grid);
  RBuffer buffer(grid);
  for (size_t i = 0; i < patches.size(); i += 5)
  {
    CullingStatistics culling;
    filler->Fill(i, buffer, &culling);
    EXPECT_EQ(culling.Candidates, patches.size());
    EXPECT_EQ(culling.Candidates, culling.BelowTangentPlane + culling.BackFacing + culling.Kept);
    // The 9 patches of the receiver's own face (itself included) are in its plane.
    EXPECT_EQ(culling.BelowTangentPlane, 9u);
    EXPECT_EQ(culling.BackFacing, 0u);
    EXPECT_EQ(culling.Occluders, 0u);
  }
  // Flip every patch (orientation outward) and look from the outside: a receiver on a face now
  // faces out; the other five faces lie below its tangent plane or turn their backs.
  std::vector<Patch> flipped;
  for (const Patch& patch : patches)
  {
    std::vector<glm::dvec3> points = patch.Geometry.ControlPoints();
    std::swap(points[1], points[2]); // transpose a bilinear net: u <-> v reverses the normal
    flipped.emplace_back(patch.SurfaceIndex, patch.Domain, 0, BezierPatch(1, 1, points));
  }
  const auto outside = RBufferFiller::Create(RBufferFill::Projection, flipped, grid);
  CullingStatistics culling;
  outside->Fill(4, buffer, &culling);
  EXPECT_EQ(culling.Kept, 0u);
  EXPECT_EQ(culling.BelowTangentPlane + culling.BackFacing, flipped.size());
  EXPECT_EQ(buffer.CoveredProjectedSolidAngle(), 0.0);
}

namespace
{
struct Agreement
{
  long Compared = 0;
  long Agreeing = 0;
  long Ties = 0;
  long Grazing = 0;
  long Total = 0;
  long RawAgreeing = 0;
};

/**
 * Cell-by-cell comparison of the two fills over the receivers i = first, first + stride, ...
 * Excluded: tie cells (the winner was decided by the tie rule in either fill, so one sample
 * more or less flips it) and grazing cells (a sample ray of the cell meets its surface within
 * ~2.9 degrees of tangency, |cos| < 0.05, as found by the ray fill's exact normal; there the
 * tessellation and the silhouette approximations move boundaries most).
 */
Agreement CompareFills(const std::vector<Patch>& patches, const HemisphereGrid& grid, size_t stride)
{
  const auto projection = RBufferFiller::Create(RBufferFill::Projection, patches, grid);
  const auto rays = RBufferFiller::Create(RBufferFill::RayCasting, patches, grid);
  RBuffer a(grid);
  RBuffer b(grid);
  Agreement result;
  for (size_t i = stride / 2; i < patches.size(); i += stride)
  {
    projection->Fill(i, a, nullptr);
    rays->Fill(i, b, nullptr);
    for (int cell = 0; cell < grid.CellCount(); ++cell)
    {
      ++result.Total;
      const bool same = a.CellSource(cell) == b.CellSource(cell);
      result.RawAgreeing += same;
      if ((a.CellFlags(cell) | b.CellFlags(cell)) & RBuffer::CellTie)
      {
        ++result.Ties;
        continue;
      }
      if (b.CellFlags(cell) & RBuffer::CellGrazing)
      {
        ++result.Grazing;
        continue;
      }
      ++result.Compared;
      result.Agreeing += same;
    }
  }
  return result;
}

void ReportAgreement(const char* name, const Agreement& agreement)
{
  std::printf("[ RBuffer  ] %s: %ld cells, %ld ties, %ld grazing excluded; agree on %.3f %% of "
              "the compared (%.3f %% of all cells)\n",
    name,
    agreement.Total,
    agreement.Ties,
    agreement.Grazing,
    100.0 * agreement.Agreeing / agreement.Compared,
    100.0 * agreement.RawAgreeing / agreement.Total);
}
}

TEST(RBuffer, FillsAgreeOnCornellBox)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = SplitScene(scene, 3);
  const HemisphereGrid grid(32, 128, 3, 3);
  const Agreement agreement = CompareFills(patches, grid, Sanitized ? 24 : 6);
  ReportAgreement("Cornell box", agreement);
  EXPECT_GE(agreement.Agreeing, 0.995 * agreement.Compared);
  EXPECT_LT(agreement.Ties + agreement.Grazing, agreement.Total / 10);
}

TEST(RBuffer, FillsAgreeOnTeapotRoom)
{
  const Scene scene = LoadSceneFile(ScenePath("teapot_room.scene"));
  const std::vector<Patch> patches = SplitScene(scene, 2);
  const HemisphereGrid grid(32, 128, 3, 3);
  const Agreement agreement = CompareFills(patches, grid, Sanitized ? 40 : 8);
  ReportAgreement("teapot room", agreement);
  EXPECT_GE(agreement.Agreeing, 0.995 * agreement.Compared);
  EXPECT_LT(agreement.Ties + agreement.Grazing, agreement.Total / 10);
}

TEST(RBuffer, RayFillTessellatesWithinTolerance)
{
  // The Utah teapot's bicubic patches: every curved patch's tessellation is even (its centre is
  // a vertex) and finer for a tighter tolerance; the room's flat quads are one quad each.
  const Scene scene = LoadSceneFile(ScenePath("teapot_room.scene"));
  const std::vector<Patch> patches = SplitScene(scene, 1);
  const HemisphereGrid grid(8, 16, 1, 1);
  RBufferFillOptions coarse;
  coarse.TessellationTolerance = 3e-2;
  RBufferFillOptions fine;
  fine.TessellationTolerance = 1e-3;
  const RayCastFiller a(patches, grid, coarse);
  const RayCastFiller b(patches, grid, fine);
  EXPECT_LT(a.Caster().TriangleCount(), b.Caster().TriangleCount());
  for (size_t p = 0; p < patches.size(); ++p)
  {
    int nu;
    int nv;
    a.Caster().Resolution(p, nu, nv);
    if (patches[p].Geometry.DegreeU() == 1 && patches[p].Geometry.DegreeV() == 1)
    {
      // The room's flat rectangles: two triangles are exact.
      EXPECT_EQ(nu, 1);
      EXPECT_EQ(nv, 1);
    }
    else
    {
      EXPECT_EQ(nu % 2, 0);
      EXPECT_EQ(nv % 2, 0);
    }
  }
}
