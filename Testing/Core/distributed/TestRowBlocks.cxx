// SPDX-License-Identifier: BSD-3-Clause
// The cover built in shares of rows (RowShares::BuildRowsOf, the rows of some characteristic
// points, paper §4.3: one R-buffer per point), sent as bytes (RowBlockBytes.h) and joined
// (RowShares::JoinRows) is the cover Build gives, bit for bit, however the receivers are split
// (ranges of about equal cost, or dealt round the ranks): what the distributed filters rely on.
#include "CoverTestUtilities.h"
#include "cover/RayCastFill.h"
#include "cover/SphericalCover.h"
#include "distributed/RowBlockBytes.h"
#include "distributed/RowShares.h"
#include "geometry/RayCaster.h"
#include "math/RankShare.h"

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

/// The cover of `patches` built in `parts` shares, one per range of receivers split by cost,
/// each through its bytes.
SphericalCover BuildInBlocks(const std::vector<Patch>& patches,
  const SphericalCoverOptions& options,
  std::size_t parts,
  const std::shared_ptr<const RayCaster>& rays = nullptr)
{
  const std::vector<std::size_t> bounds =
    RowShares::PartitionRows(RowShares::EstimateRowCosts(patches, options), parts);
  std::vector<SphericalCover::Arrays> blocks(parts);
  CullingStatistics culling;
  for (std::size_t k = 0; k < parts; ++k)
  {
    SphericalCover block;
    EXPECT_TRUE(RowShares::BuildRowsOf(block,
      patches,
      options,
      RowShares::ReceiversOfRanges(bounds, { k }),
      ThreadedFor(2),
      nullptr,
      rays));
    const std::vector<char> bytes = PackRowBlock(block.ExportArrays(), block.Culling());
    CullingStatistics counts;
    EXPECT_EQ(UnpackRowBlock(bytes.data(), bytes.size(), blocks[k], counts), "");
    culling += counts;
  }
  SphericalCover cover;
  EXPECT_EQ(RowShares::JoinRows(cover, std::move(blocks), options, culling), "");
  return cover;
}

/// `fill` on an 8 x 32 grid.
SphericalCoverOptions EightByThirtyTwo(RBufferFill fill)
{
  SphericalCoverOptions options;
  options.ThetaBins = 8;
  options.PhiBins = 32;
  options.Fill = fill;
  return options;
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

/// The furnace with a pane (furnace_pane.scene) in 3 x 3 patches per surface, and the ray fill
/// on an 8 x 32 grid that sees through its panes.
struct PaneSetup
{
  std::vector<Patch> Patches;
  SphericalCoverOptions Options;
};

PaneSetup PanedFurnace()
{
  const Scene scene = LoadSceneFile(ScenePath("furnace_pane.scene"));
  PaneSetup setup;
  setup.Patches = SplitScene(scene, 3);
  setup.Options.ThetaBins = 8;
  setup.Options.PhiBins = 32;
  setup.Options.Fill = RBufferFill::RayCasting;
  for (const Surface& surface : scene.Surfaces)
  {
    setup.Options.SurfaceTransmittance.push_back(
      glm::vec3(scene.Materials[static_cast<size_t>(surface.MaterialIndex)].Transmittance));
  }
  return setup;
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
    const SphericalCoverOptions options = EightByThirtyTwo(fill);
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

// The cover filter's ranks each build every K-th of K x 32 chunks of rows (ranges of about
// equal cost) into one share (RowShares::ReceiversOfRanges); the ranks' shares, read back from
// their bytes, join to the serial cover. Damaged bytes are refused.
TEST(RowBlocks, ChunksDealtRoundTheRanksJoinToSerial)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = CornellPatches(scene);
  SphericalCoverOptions options;
  options.ThetaBins = 8;
  options.PhiBins = 32;
  SphericalCover serial;
  ASSERT_TRUE(serial.Build(patches, options, ThreadedFor(2)));
  const int ranks = 3;
  const std::size_t chunks = 32 * ranks;
  const std::vector<std::size_t> bounds =
    RowShares::PartitionRows(RowShares::EstimateRowCosts(patches, options), chunks);
  std::vector<std::vector<char>> buffers(ranks);
  std::size_t receivers = 0;
  for (int r = 0; r < ranks; ++r)
  {
    const std::vector<std::size_t> mine =
      RowShares::ReceiversOfRanges(bounds, RankShare::ItemsOf(r, ranks, chunks));
    receivers += mine.size();
    SphericalCover share;
    ASSERT_TRUE(RowShares::BuildRowsOf(share, patches, options, mine));
    buffers[static_cast<std::size_t>(r)] = PackRowBlock(share.ExportArrays(), share.Culling());
  }
  EXPECT_EQ(receivers, patches.size());
  std::vector<SphericalCover::Arrays> shares(ranks);
  CullingStatistics culling;
  for (std::size_t r = 0; r < buffers.size(); ++r)
  {
    CullingStatistics counts;
    ASSERT_EQ(UnpackRowBlock(buffers[r].data(), buffers[r].size(), shares[r], counts), "");
    culling += counts;
  }
  SphericalCover joined;
  ASSERT_EQ(RowShares::JoinRows(joined, std::move(shares), options, culling), "");
  ExpectSameCover(joined, serial);

  SphericalCover::Arrays read;
  CullingStatistics counts;
  std::vector<char> bytes = buffers[0];
  EXPECT_NE(UnpackRowBlock(bytes.data(), 0, read, counts), "");
  EXPECT_NE(UnpackRowBlock(bytes.data(), bytes.size() - 1, read, counts), "");
  EXPECT_TRUE(read.Entries.empty());
  EXPECT_NE(UnpackRowBlock(bytes.data(), 4, read, counts), "");
  bytes[0] ^= 1; // the tag
  EXPECT_NE(UnpackRowBlock(bytes.data(), bytes.size(), read, counts), "");
  EXPECT_TRUE(read.Entries.empty());
}

// The lamp measured on the lamp (ray fill): shares without a measured row get their cells'
// measures as Build's rows do, whichever share holds the first measured row.
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
  const PaneSetup paned = PanedFurnace();
  SphericalCover serial;
  ASSERT_TRUE(serial.Build(paned.Patches, paned.Options, ThreadedFor(2)));
  ASSERT_TRUE(serial.HasPanes());
  for (const std::size_t parts : { 2, 3 })
  {
    SCOPED_TRACE(testing::Message() << parts << " blocks");
    ExpectSameCover(BuildInBlocks(paned.Patches, paned.Options, parts), serial);
  }
}

namespace
{
/// The arrays of two covers are the same, bit for bit (culling counts aside).
void ExpectSameRows(const SphericalCover& a, const SphericalCover& b)
{
  const SphericalCover::Arrays x = a.ExportArrays();
  const SphericalCover::Arrays y = b.ExportArrays();
  EXPECT_TRUE(SameBytes(x.RowOffsets, y.RowOffsets));
  EXPECT_TRUE(SameBytes(x.Entries, y.Entries));
  EXPECT_TRUE(SameBytes(x.Unoccluded, y.Unoccluded));
  EXPECT_TRUE(SameBytes(x.Strips, y.Strips));
  EXPECT_TRUE(SameBytes(x.StripDepths, y.StripDepths));
  EXPECT_TRUE(SameBytes(x.Areas, y.Areas));
  EXPECT_TRUE(SameBytes(x.Measures, y.Measures));
  EXPECT_TRUE(SameBytes(x.Layers, y.Layers));
  EXPECT_TRUE(SameBytes(x.Filters, y.Filters));
  EXPECT_TRUE(SameBytes(x.Transmittances, y.Transmittances));
}

/// The shares of `receiverSets` built apart (BuildRowsOf, measures kept where a share's rows
/// are not measured but another's are), each checked against the serial cover's RowsOf, then
/// joined through their bytes: the serial cover.
void ExpectSharesJoinToSerial(const std::vector<Patch>& patches,
  const SphericalCoverOptions& options,
  const std::vector<std::vector<std::size_t>>& receiverSets,
  const SphericalCover& serial)
{
  std::vector<SphericalCover> shares(receiverSets.size());
  bool measured = false;
  for (std::size_t s = 0; s < shares.size(); ++s)
  {
    ASSERT_TRUE(
      RowShares::BuildRowsOf(shares[s], patches, options, receiverSets[s], ThreadedFor(2)));
    measured = measured || shares[s].HasMeasures();
  }
  std::vector<SphericalCover::Arrays> sent;
  CullingStatistics culling;
  for (std::size_t s = 0; s < shares.size(); ++s)
  {
    SCOPED_TRACE(testing::Message() << "share " << s);
    if (measured)
    {
      RowShares::KeepCellMeasures(shares[s]);
    }
    ExpectSameRows(shares[s], RowShares::RowsOf(serial, receiverSets[s]));
    const std::vector<char> bytes = PackRowBlock(shares[s].ExportArrays(), shares[s].Culling());
    SphericalCover::Arrays read;
    CullingStatistics counts;
    ASSERT_EQ(UnpackRowBlock(bytes.data(), bytes.size(), read, counts), "");
    sent.push_back(std::move(read));
    culling += counts;
  }
  SphericalCover joined;
  ASSERT_EQ(RowShares::JoinRows(joined, std::move(sent), options, culling), "");
  ExpectSameCover(joined, serial);

  // The form factors summed from the shares' rows (each receiver's sums from the share that
  // holds its row, as the ranks of a solution kept in pieces join them) are the serial ones bit
  // for bit; and they are not all zero, nor the same from every surface.
  std::vector<int> groups;
  int groupCount = 0;
  for (const Patch& patch : patches)
  {
    groups.push_back(patch.SurfaceIndex);
    groupCount = std::max(groupCount, patch.SurfaceIndex + 1);
  }
  std::vector<std::vector<SphericalCover::GroupSum>> sums(patches.size());
  for (std::size_t s = 0; s < shares.size(); ++s)
  {
    std::vector<std::vector<SphericalCover::GroupSum>> own =
      shares[s].FormFactorSums(groups, groupCount);
    for (const std::size_t i : receiverSets[s])
    {
      sums[i] = std::move(own[i]);
    }
  }
  std::vector<double> areas;
  for (std::size_t i = 0; i < patches.size(); ++i)
  {
    areas.push_back(serial.PatchArea(i));
  }
  const std::vector<double> factors = serial.FormFactors(groups, groupCount);
  EXPECT_EQ(SphericalCover::FormFactorsOf(sums, groups, groupCount, areas), factors);
  EXPECT_GT(*std::max_element(factors.begin(), factors.end()), 0.05);
  EXPECT_THROW(SphericalCover::FormFactorsOf(sums, groups, groupCount, {}), std::invalid_argument);
}
}

// Each rank builds the rows of its receivers (r, r + K, ...: BuildRowsOf) and keeps them; the
// shares are the serial cover's RowsOf and join (JoinRows) to the serial cover, bit for bit:
// both fills, the lamp measured on the lamp (a share of the lamp's own rows, which see no
// measured region, keeps its cells' measures), panes.
TEST(RowBlocks, SharesBuiltApartJoinToSerial)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = CornellPatches(scene);
  auto dealt = [&](std::size_t ranks)
  {
    std::vector<std::vector<std::size_t>> sets;
    for (std::size_t r = 0; r < ranks; ++r)
    {
      sets.push_back(
        RankShare::ItemsOf(static_cast<int>(r), static_cast<int>(ranks), patches.size()));
    }
    return sets;
  };
  for (const RBufferFill fill : { RBufferFill::Projection, RBufferFill::RayCasting })
  {
    const SphericalCoverOptions options = EightByThirtyTwo(fill);
    SphericalCover serial;
    ASSERT_TRUE(serial.Build(patches, options, ThreadedFor(2)));
    for (const std::size_t ranks : { 1, 2, 3 })
    {
      SCOPED_TRACE(
        testing::Message() << "fill " << static_cast<int>(fill) << ", " << ranks << " ranks");
      ExpectSharesJoinToSerial(patches, options, dealt(ranks), serial);
    }
  }

  const SphericalCoverOptions measuredLamp = MeasuredLampOptions(scene);
  SphericalCover serial;
  ASSERT_TRUE(serial.Build(patches, measuredLamp, ThreadedFor(2)));
  ASSERT_TRUE(serial.HasMeasures());
  ExpectSharesJoinToSerial(patches, measuredLamp, dealt(2), serial);
  const int lamp = SurfaceNamed(scene, "light");
  std::vector<std::vector<std::size_t>> lampAndRest(2);
  for (std::size_t i = 0; i < patches.size(); ++i)
  {
    lampAndRest[patches[i].SurfaceIndex == lamp ? 0 : 1].push_back(i);
  }
  SphericalCover lampRows;
  ASSERT_TRUE(RowShares::BuildRowsOf(lampRows, patches, measuredLamp, lampAndRest[0]));
  EXPECT_FALSE(lampRows.HasMeasures()); // the path KeepCellMeasures is for
  ExpectSharesJoinToSerial(patches, measuredLamp, lampAndRest, serial);

  const PaneSetup paned = PanedFurnace();
  SphericalCover paneSerial;
  ASSERT_TRUE(paneSerial.Build(paned.Patches, paned.Options, ThreadedFor(2)));
  ASSERT_TRUE(paneSerial.HasPanes());
  std::vector<std::vector<std::size_t>> paneSets;
  for (int r = 0; r < 2; ++r)
  {
    paneSets.push_back(RankShare::ItemsOf(r, 2, paned.Patches.size()));
  }
  ExpectSharesJoinToSerial(paned.Patches, paned.Options, paneSets, paneSerial);
}

// Shares that do not make one cover are refused with a reason, the cover left empty.
TEST(RowBlocks, BadSharesRefused)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = CornellPatches(scene);
  SphericalCoverOptions options;
  options.ThetaBins = 8;
  options.PhiBins = 32;
  SphericalCover first;
  SphericalCover second;
  ASSERT_TRUE(RowShares::BuildRowsOf(first, patches, options, { 0, 1, 2 }));
  ASSERT_TRUE(RowShares::BuildRowsOf(second, patches, options, { 2, 3 }));
  SphericalCover joined;
  const std::string twice =
    RowShares::JoinRows(joined, { first.ExportArrays(), second.ExportArrays() }, options, {});
  EXPECT_NE(twice.find("receiver 2's row is in share 0 and in share 1"), std::string::npos)
    << twice;
  EXPECT_TRUE(joined.Empty());
  SphericalCoverOptions other = options;
  other.PhiBins = 64;
  EXPECT_NE(RowShares::JoinRows(joined, { first.ExportArrays() }, other, {}), "");
  std::vector<Patch> fewer(patches.begin(), patches.end() - 1);
  SphericalCover short_;
  ASSERT_TRUE(RowShares::BuildRowsOf(short_, fewer, options, { 3 }));
  EXPECT_NE(
    RowShares::JoinRows(joined, { first.ExportArrays(), short_.ExportArrays() }, options, {}), "");
  SphericalCover::Arrays damaged = first.ExportArrays();
  damaged.RowOffsets.back() += 1; // past the entries
  EXPECT_NE(RowShares::JoinRows(joined, { damaged }, options, {}), "");
  EXPECT_NE(RowShares::JoinRows(joined, {}, options, {}), "");
  EXPECT_TRUE(joined.Empty());
  SphericalCover unordered;
  EXPECT_THROW(
    RowShares::BuildRowsOf(unordered, patches, options, { 2, 1 }), std::invalid_argument);
  EXPECT_THROW(
    RowShares::BuildRowsOf(unordered, patches, options, { patches.size() }), std::invalid_argument);
}

// The split follows the cost, not the count; every receiver is in exactly one range.
TEST(RowBlocks, PartitionByCost)
{
  const std::vector<double> costs = { 10, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1 };
  const std::vector<std::size_t> two = RowShares::PartitionRows(costs, 2);
  EXPECT_EQ(two, (std::vector<std::size_t>{ 0, 1, 11 }));
  const std::vector<std::size_t> many = RowShares::PartitionRows({ 1, 1 }, 4);
  ASSERT_EQ(many.size(), 5u);
  EXPECT_EQ(many.front(), 0u);
  EXPECT_EQ(many.back(), 2u);
  for (std::size_t k = 0; k + 1 < many.size(); ++k)
  {
    EXPECT_LE(many[k], many[k + 1]);
  }
  EXPECT_THROW(RowShares::PartitionRows(costs, 0), std::invalid_argument);

  // A point in a corner sees less of the room than one in the middle of a wall.
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = CornellPatches(scene);
  SphericalCoverOptions projection;
  projection.Fill = RBufferFill::Projection;
  const std::vector<double> estimate = RowShares::EstimateRowCosts(patches, projection);
  ASSERT_EQ(estimate.size(), patches.size());
  const auto [low, high] = std::minmax_element(estimate.begin(), estimate.end());
  EXPECT_GE(*low, 1.0);
  EXPECT_LE(*high, static_cast<double>(patches.size()));
  EXPECT_LT(*low, *high);
  // The ray fill's rows cost their rays besides their candidates: a fixed part of 2N each.
  SphericalCoverOptions rays;
  rays.Fill = RBufferFill::RayCasting;
  const std::vector<double> rayEstimate = RowShares::EstimateRowCosts(patches, rays);
  EXPECT_EQ(rayEstimate[0] - estimate[0], 2.0 * static_cast<double>(patches.size()) - 1.0);
}

// Damaged bytes and a share of another grid are refused with a reason, the cover left empty.
TEST(RowBlocks, BadBlocksRefused)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = CornellPatches(scene);
  SphericalCoverOptions options;
  options.ThetaBins = 8;
  options.PhiBins = 32;
  options.Fill = RBufferFill::RayCasting;
  SphericalCover rows;
  ASSERT_TRUE(RowShares::BuildRowsOf(rows, patches, options, { 0, 1, 2, 3 }));
  CullingStatistics culling = rows.Culling();
  const SphericalCover::Arrays block = rows.ExportArrays();
  std::vector<char> bytes = PackRowBlock(block, culling);
  SphericalCover::Arrays read;
  EXPECT_NE(UnpackRowBlock(bytes.data(), bytes.size() - 1, read, culling), "");
  EXPECT_TRUE(read.Entries.empty());
  bytes.push_back(0);
  EXPECT_NE(UnpackRowBlock(bytes.data(), bytes.size(), read, culling), "");
  bytes[0] ^= 1;
  EXPECT_NE(UnpackRowBlock(bytes.data(), bytes.size() - 1, read, culling), "");

  SphericalCover cover;
  SphericalCoverOptions other = options;
  other.PhiBins = 64;
  EXPECT_NE(RowShares::JoinRows(cover, { block }, other, culling), "");
  EXPECT_TRUE(cover.Empty());
  EXPECT_NE(RowShares::JoinRows(cover, {}, options, culling), "");
  // The rows of four receivers alone are a cover whose other rows are empty.
  EXPECT_EQ(RowShares::JoinRows(cover, { block }, options, culling), "");
  EXPECT_EQ(cover.PatchCount(), patches.size());
  EXPECT_EQ(cover.EntryBegin(4), cover.EntryCount());

  // Ranges of receivers: those of the ranges given, in order.
  const std::vector<std::size_t> bounds = { 0, 2, 2, 5 };
  EXPECT_EQ(
    RowShares::ReceiversOfRanges(bounds, { 0, 2 }), (std::vector<std::size_t>{ 0, 1, 2, 3, 4 }));
  EXPECT_TRUE(RowShares::ReceiversOfRanges(bounds, { 1 }).empty());
  EXPECT_THROW(RowShares::ReceiversOfRanges(bounds, { 3 }), std::out_of_range);
}
