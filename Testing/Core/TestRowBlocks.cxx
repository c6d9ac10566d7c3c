// SPDX-License-Identifier: BSD-3-Clause
// The cover built in row blocks (SphericalCover::BuildRowBlock, the rows of a range of
// characteristic points, paper §4.3: one R-buffer per point), sent as bytes (RowBlockBytes.h)
// and joined (ImportRowBlocks) is the cover Build gives, bit for bit, however the receivers are
// split: what the distributed filter relies on.
#include "CoverTestUtilities.h"
#include "cover/RayCastFill.h"
#include "cover/RowBlockBytes.h"
#include "cover/SphericalCover.h"
#include "geometry/RayCaster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{
/// Raw bytes of two vectors are equal (floats compared bit for bit, not by value).
template<typename T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b)
{
  // memcmp must not get an empty vector's data(), which may be null.
  return a.size() == b.size() &&
    (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void ExpectSameCover(const SphericalCover& joined, const SphericalCover& serial)
{
  const SphericalCover::Arrays a = joined.ExportArrays();
  const SphericalCover::Arrays b = serial.ExportArrays();
  EXPECT_TRUE(SameBytes(a.RowOffsets, b.RowOffsets));
  EXPECT_TRUE(SameBytes(a.Entries, b.Entries));
  EXPECT_TRUE(SameBytes(a.Unoccluded, b.Unoccluded));
  EXPECT_EQ(a.UnoccludedKnown, b.UnoccludedKnown);
  EXPECT_TRUE(SameBytes(a.Strips, b.Strips));
  EXPECT_TRUE(SameBytes(a.StripDepths, b.StripDepths));
  EXPECT_TRUE(SameBytes(a.Areas, b.Areas));
  EXPECT_TRUE(SameBytes(a.Measures, b.Measures));
  EXPECT_TRUE(SameBytes(a.Layers, b.Layers));
  EXPECT_TRUE(SameBytes(a.Filters, b.Filters));
  EXPECT_TRUE(SameBytes(a.Transmittances, b.Transmittances));
  EXPECT_EQ(joined.Culling().Candidates, serial.Culling().Candidates);
  EXPECT_EQ(joined.Culling().Kept, serial.Culling().Kept);
  EXPECT_EQ(joined.Culling().Pieces, serial.Culling().Pieces);
  EXPECT_EQ(joined.Options().MeasuredSurfaces, serial.Options().MeasuredSurfaces);
}

/// The cover of `patches` built in `parts` blocks split by cost, each through its bytes.
SphericalCover BuildInBlocks(const std::vector<Patch>& patches,
  const SphericalCoverOptions& options,
  std::size_t parts,
  const std::shared_ptr<const RayCaster>& rays = nullptr)
{
  const std::vector<std::size_t> bounds =
    SphericalCover::PartitionRows(SphericalCover::EstimateRowCosts(patches, options), parts);
  std::vector<SphericalCover::Arrays> blocks(parts);
  CullingStatistics culling;
  for (std::size_t k = 0; k < parts; ++k)
  {
    SphericalCover::Arrays block;
    CullingStatistics counts;
    EXPECT_TRUE(SphericalCover::BuildRowBlock(
      patches, options, bounds[k], bounds[k + 1], block, counts, ThreadedFor(2), nullptr, rays));
    const std::vector<char> bytes = PackRowBlock(block, counts);
    EXPECT_EQ(UnpackRowBlock(bytes.data(), bytes.size(), blocks[k], counts), "");
    culling += counts;
  }
  SphericalCover cover;
  EXPECT_EQ(cover.ImportRowBlocks(std::move(blocks), options, culling), "");
  return cover;
}

/// The ray fill on an 8 x 32 grid, the Cornell box's lamp measured on the lamp.
SphericalCoverOptions MeasuredLampOptions(const Scene& scene)
{
  SphericalCoverOptions options;
  options.ThetaBins = 8;
  options.PhiBins = 32;
  options.Fill = RBufferFill::RayCasting;
  const int lamp = SurfaceNamed(scene, "light");
  EXPECT_GE(lamp, 0);
  options.MeasuredSurfaces.assign(scene.Surfaces.size(), false);
  options.MeasuredSurfaces.at(static_cast<size_t>(lamp)) = true;
  return options;
}

std::vector<Patch> CornellPatches(const Scene& scene)
{
  std::vector<Patch> patches;
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    const int n = s <= 4 ? 5 : 3;
    AppendSplit(patches, scene.Surfaces[s].Patch, static_cast<int>(s), n, n);
  }
  return patches;
}
}

// Both fills, 1 to 5 blocks (more blocks than some ranges hold receivers: empty blocks).
TEST(RowBlocks, JoinedEqualsSerial)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = CornellPatches(scene);
  for (const RBufferFill fill : { RBufferFill::Projection, RBufferFill::RayCasting })
  {
    SphericalCoverOptions options;
    options.ThetaBins = 8;
    options.PhiBins = 32;
    options.Fill = fill;
    SphericalCover serial;
    ASSERT_TRUE(serial.Build(patches, options, ThreadedFor(2)));
    for (const std::size_t parts : { 1, 2, 3, 5 })
    {
      SCOPED_TRACE(
        testing::Message() << "fill " << static_cast<int>(fill) << ", " << parts << " blocks");
      ExpectSameCover(BuildInBlocks(patches, options, parts), serial);
    }
  }
}

// One ray caster of the patches, built by the caller and shared with the direct light (as the
// cover filter does), gives the rows each fill's own caster gives, measured lamp included, and
// the same memory estimate; a caster of other patches is refused, not cast against.
TEST(RowBlocks, ASharedCasterGivesTheSameRows)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = CornellPatches(scene);
  const SphericalCoverOptions options = MeasuredLampOptions(scene);
  SphericalCover own;
  ASSERT_TRUE(own.Build(patches, options, ThreadedFor(2)));
  ASSERT_EQ(own.ExportArrays().Measures.size(), own.EntryCount());
  const auto rays =
    std::make_shared<const RayCaster>(RayCastPatches(patches), RayCastOptions(options.FillOptions));
  SphericalCover shared;
  ASSERT_TRUE(shared.Build(patches, options, ThreadedFor(2), nullptr, rays));
  ExpectSameCover(shared, own);
  ExpectSameCover(BuildInBlocks(patches, options, 3, rays), own);
  EXPECT_EQ(SphericalCover::EstimateBytes(patches, options, 8, rays),
    SphericalCover::EstimateBytes(patches, options, 8));

  const std::vector<Patch> fewer(patches.begin(), patches.end() - 1);
  const auto other =
    std::make_shared<const RayCaster>(RayCastPatches(fewer), RayCastOptions(options.FillOptions));
  SphericalCover refused;
  EXPECT_THROW(
    refused.Build(patches, options, SequentialFor, nullptr, other), std::invalid_argument);
  EXPECT_TRUE(refused.Empty());
}

// A process's several blocks in one buffer (AppendRowBlock, UnpackRowBlocks): the filter's
// ranks each build every K-th of K x 32 chunks of rows; the chunks, read back from the ranks'
// buffers and put in receiver order, join to the serial cover. Damaged buffers are refused.
TEST(RowBlocks, ChunksDealtRoundTheRanksJoinToSerial)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = CornellPatches(scene);
  SphericalCoverOptions options;
  options.ThetaBins = 8;
  options.PhiBins = 32;
  SphericalCover serial;
  ASSERT_TRUE(serial.Build(patches, options, ThreadedFor(2)));
  const std::size_t ranks = 3;
  const std::size_t chunks = 32 * ranks;
  const std::vector<std::size_t> bounds =
    SphericalCover::PartitionRows(SphericalCover::EstimateRowCosts(patches, options), chunks);
  std::vector<std::vector<char>> buffers(ranks);
  for (std::size_t c = 0; c < chunks; ++c)
  {
    SphericalCover::Arrays block;
    CullingStatistics counts;
    ASSERT_TRUE(
      SphericalCover::BuildRowBlock(patches, options, bounds[c], bounds[c + 1], block, counts));
    AppendRowBlock(buffers[c % ranks], block, counts);
  }
  std::vector<SphericalCover::Arrays> blocks(chunks);
  CullingStatistics culling;
  for (std::size_t r = 0; r < ranks; ++r)
  {
    std::vector<SphericalCover::Arrays> read;
    CullingStatistics counts;
    ASSERT_EQ(UnpackRowBlocks(buffers[r].data(), buffers[r].size(), read, counts), "");
    ASSERT_EQ(read.size(), chunks / ranks);
    for (std::size_t k = 0; k < read.size(); ++k)
    {
      blocks[k * ranks + r] = std::move(read[k]);
    }
    culling += counts;
  }
  SphericalCover joined;
  ASSERT_EQ(joined.ImportRowBlocks(std::move(blocks), options, culling), "");
  ExpectSameCover(joined, serial);

  std::vector<SphericalCover::Arrays> read;
  CullingStatistics counts;
  std::vector<char> bytes = buffers[0];
  EXPECT_EQ(UnpackRowBlocks(bytes.data(), 0, read, counts), "");
  EXPECT_TRUE(read.empty());
  EXPECT_NE(UnpackRowBlocks(bytes.data(), bytes.size() - 1, read, counts), "");
  EXPECT_TRUE(read.empty());
  EXPECT_NE(UnpackRowBlocks(bytes.data(), 4, read, counts), "");
  bytes[8] ^= 1; // the first block's tag
  EXPECT_NE(UnpackRowBlocks(bytes.data(), bytes.size(), read, counts), "");
  EXPECT_TRUE(read.empty());
  EXPECT_EQ(counts.Candidates, 0u);
}

// The lamp measured on the lamp (ray fill): blocks without a measured row get their cells'
// measures as Build's rows do, whichever block holds the first measured row.
TEST(RowBlocks, MeasuredLampJoinedEqualsSerial)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = CornellPatches(scene);
  const SphericalCoverOptions options = MeasuredLampOptions(scene);
  SphericalCover serial;
  ASSERT_TRUE(serial.Build(patches, options, ThreadedFor(2)));
  ASSERT_EQ(serial.ExportArrays().Measures.size(), serial.EntryCount());
  for (const std::size_t parts : { 2, 4, 7 })
  {
    SCOPED_TRACE(testing::Message() << parts << " blocks");
    ExpectSameCover(BuildInBlocks(patches, options, parts), serial);
  }
}

// Panes (SphericalCover.h "Panes"): the layers behind them and their filters join as the rest.
TEST(RowBlocks, PanesJoinedEqualSerial)
{
  const Scene scene = LoadSceneFile(ScenePath("furnace_pane.scene"));
  const std::vector<Patch> patches = SplitScene(scene, 3);
  SphericalCoverOptions options;
  options.ThetaBins = 8;
  options.PhiBins = 32;
  options.Fill = RBufferFill::RayCasting;
  for (const Surface& surface : scene.Surfaces)
  {
    options.SurfaceTransmittance.push_back(
      glm::vec3(scene.Materials[static_cast<size_t>(surface.MaterialIndex)].Transmittance));
  }
  SphericalCover serial;
  ASSERT_TRUE(serial.Build(patches, options, ThreadedFor(2)));
  ASSERT_TRUE(serial.HasPanes());
  for (const std::size_t parts : { 2, 3 })
  {
    SCOPED_TRACE(testing::Message() << parts << " blocks");
    ExpectSameCover(BuildInBlocks(patches, options, parts), serial);
  }
}

// The split follows the cost, not the count; every receiver is in exactly one range.
TEST(RowBlocks, PartitionByCost)
{
  const std::vector<double> costs = { 10, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1 };
  const std::vector<std::size_t> two = SphericalCover::PartitionRows(costs, 2);
  EXPECT_EQ(two, (std::vector<std::size_t>{ 0, 1, 11 }));
  const std::vector<std::size_t> many = SphericalCover::PartitionRows({ 1, 1 }, 4);
  ASSERT_EQ(many.size(), 5u);
  EXPECT_EQ(many.front(), 0u);
  EXPECT_EQ(many.back(), 2u);
  for (std::size_t k = 0; k + 1 < many.size(); ++k)
  {
    EXPECT_LE(many[k], many[k + 1]);
  }
  EXPECT_THROW(SphericalCover::PartitionRows(costs, 0), std::invalid_argument);

  // A point in a corner sees less of the room than one in the middle of a wall.
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = CornellPatches(scene);
  SphericalCoverOptions projection;
  projection.Fill = RBufferFill::Projection;
  const std::vector<double> estimate = SphericalCover::EstimateRowCosts(patches, projection);
  ASSERT_EQ(estimate.size(), patches.size());
  const auto [low, high] = std::minmax_element(estimate.begin(), estimate.end());
  EXPECT_GE(*low, 1.0);
  EXPECT_LE(*high, static_cast<double>(patches.size()));
  EXPECT_LT(*low, *high);
  // The ray fill's rows cost their rays besides their candidates: a fixed part of 2N each.
  SphericalCoverOptions rays;
  rays.Fill = RBufferFill::RayCasting;
  const std::vector<double> rayEstimate = SphericalCover::EstimateRowCosts(patches, rays);
  EXPECT_EQ(rayEstimate[0] - estimate[0], 2.0 * static_cast<double>(patches.size()) - 1.0);
}

// Damaged bytes and inconsistent blocks are refused with a reason, the cover left empty.
TEST(RowBlocks, BadBlocksRefused)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = CornellPatches(scene);
  SphericalCoverOptions options;
  options.ThetaBins = 8;
  options.PhiBins = 32;
  options.Fill = RBufferFill::RayCasting;
  SphericalCover::Arrays block;
  CullingStatistics culling;
  ASSERT_TRUE(SphericalCover::BuildRowBlock(patches, options, 0, 4, block, culling));
  std::vector<char> bytes = PackRowBlock(block, culling);
  SphericalCover::Arrays read;
  EXPECT_NE(UnpackRowBlock(bytes.data(), bytes.size() - 1, read, culling), "");
  EXPECT_TRUE(read.Entries.empty());
  bytes.push_back(0);
  EXPECT_NE(UnpackRowBlock(bytes.data(), bytes.size(), read, culling), "");
  bytes[0] ^= 1;
  EXPECT_NE(UnpackRowBlock(bytes.data(), bytes.size() - 1, read, culling), "");

  // The rows of four receivers only: their sources name patches the joined cover lacks.
  SphericalCover cover;
  EXPECT_NE(cover.ImportRowBlocks({ block }, options, culling), "");
  EXPECT_TRUE(cover.Empty());
  SphericalCoverOptions other = options;
  other.PhiBins = 64;
  EXPECT_NE(cover.ImportRowBlocks({ block }, other, culling), "");
  EXPECT_NE(cover.ImportRowBlocks({}, options, culling), "");
  EXPECT_THROW(
    SphericalCover::BuildRowBlock(patches, options, 5, 4, block, culling), std::invalid_argument);
}
