// SPDX-License-Identifier: BSD-3-Clause
// The propagation shared among ranks (SharePropagation): each rank holds the rows
// of its own receivers, dealt round the ranks (RowShares::RowsOf), the ranks agree on every
// shooter and its owner sends what it shoots. Every owned patch's results must be the serial ones
// bit for bit, for Lambertian, mirror, phong and tabulated shooters (strip-pair and grid shots),
// whatever the number of ranks (run here as threads, InProcessRanks).
#include "CoverTestUtilities.h"
#include "MaterialTestUtilities.h"
#include "cover/BrightEmitters.h"
#include "cover/HemisphereGrid.h"
#include "distributed/InProcessRanks.h"
#include "distributed/RowShares.h"
#include "distributed/SharedPropagation.h"
#include "math/RankShare.h"
#include "propagation/LightPropagation.h"
#include "scene/SceneLoader.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{

bool SameBits(const glm::dvec3& a, const glm::dvec3& b)
{
  return std::memcmp(&a, &b, sizeof(a)) == 0;
}

std::vector<HemisphereFrame> FramesOf(const std::vector<Patch>& patches)
{
  std::vector<HemisphereFrame> frames;
  for (const Patch& patch : patches)
  {
    frames.push_back(HemisphereFrame::OfPatch(patch));
  }
  return frames;
}

/// What a rank's propagation gives for its own patches, to compare with serial.
struct RankResult
{
  bool Converged = false;
  std::string Failure;
  std::vector<std::size_t> Receivers;
  std::vector<ShotRecord> History;
  std::vector<glm::dvec3> Irradiance;
  std::vector<glm::dvec3> Brightness;
  std::vector<glm::dvec3> Toward;
  std::vector<glm::dvec3> Incident;
  std::vector<glm::dvec3> Lamp;
  EnergyBalance Energy;
};

/// Runs the propagation of `cover` with `materials` serially and on `ranks` ranks, and checks
/// the ranks' results against the serial ones.
void ExpectSharedEqualsSerial(const SphericalCover& cover,
  const std::vector<Patch>& patches,
  const std::vector<Material>& materials,
  int ranks,
  std::size_t batch,
  DirectionalMethod method = DirectionalMethod::Automatic)
{
  SCOPED_TRACE(testing::Message() << ranks << " ranks, batches of " << batch);
  const std::vector<HemisphereFrame> frames = FramesOf(patches);
  std::vector<glm::dvec3> emission;
  for (const Material& material : materials)
  {
    emission.push_back(material.Emission);
  }
  const std::vector<bool> lampSurfaces = BrightEmitters(patches, emission);
  std::vector<bool> lamps;
  for (const Patch& patch : patches)
  {
    const std::size_t surface = static_cast<std::size_t>(patch.SurfaceIndex);
    lamps.push_back(surface < lampSurfaces.size() && lampSurfaces[surface]);
  }
  const glm::dvec3 oblique = HemisphereGrid::LocalDirection(1.0, 2.0);
  PropagationSettings settings;
  settings.ConvergenceTolerance = 1e-6;
  settings.ShotBatch = batch;

  LightPropagation serial(cover, materials);
  serial.SetFrames(frames);
  serial.SetDirectionalMethod(method);
  ASSERT_TRUE(serial.Run(settings));
  const std::vector<glm::dvec3> serialLamp = serial.LampIrradiance(lamps, true);

  InProcessRanks world(ranks);
  std::vector<RankResult> results(static_cast<std::size_t>(ranks));
  world.Run(
    [&](const RankShare& share, int rank)
    {
      RankResult& result = results[static_cast<std::size_t>(rank)];
      try
      {
        result.Receivers = share.MyItems(cover.PatchCount());
        const SphericalCover rows = RowShares::RowsOf(cover, result.Receivers);
        LightPropagation shared(rows, materials);
        shared.SetFrames(frames);
        shared.SetDirectionalMethod(method);
        SharePropagation(shared, share);
        result.Converged = shared.Run(settings);
        result.History = shared.History();
        for (const std::size_t i : result.Receivers)
        {
          result.Irradiance.push_back(shared.Irradiance(i));
          result.Brightness.push_back(shared.Brightness(i));
          result.Toward.push_back(shared.ExitantRadianceToward(i, oblique));
        }
        result.Incident = shared.IncidentRadiances();
        result.Lamp = shared.LampIrradiance(lamps, true);
        result.Energy = shared.Energy();
      }
      catch (const std::exception& e)
      {
        result.Failure = e.what();
      }
    });

  const EnergyBalance serialEnergy = serial.Energy();
  for (int rank = 0; rank < ranks; ++rank)
  {
    SCOPED_TRACE(testing::Message() << "rank " << rank);
    const RankResult& result = results[static_cast<std::size_t>(rank)];
    ASSERT_EQ(result.Failure, "");
    EXPECT_TRUE(result.Converged);
    ASSERT_EQ(result.History.size(), serial.History().size());
    for (std::size_t s = 0; s < result.History.size(); ++s)
    {
      const ShotRecord& a = result.History[s];
      const ShotRecord& b = serial.History()[s];
      ASSERT_EQ(a.Shooter, b.Shooter) << "shot " << s;
      ASSERT_EQ(a.ShotPower, b.ShotPower) << "shot " << s;
      ASSERT_EQ(a.ReceiverUpdates, b.ReceiverUpdates) << "shot " << s;
      ASSERT_EQ(a.Fallbacks, b.Fallbacks) << "shot " << s;
      ASSERT_EQ(a.MeanFallbacks, b.MeanFallbacks) << "shot " << s;
      ASSERT_EQ(a.GridShot, b.GridShot) << "shot " << s;
      ASSERT_NEAR(a.UnshotEnergy, b.UnshotEnergy, 1e-12 * b.UnshotEnergy + 1e-300);
    }
    for (std::size_t k = 0; k < result.Receivers.size(); ++k)
    {
      const std::size_t i = result.Receivers[k];
      ASSERT_TRUE(SameBits(result.Irradiance[k], serial.Irradiance(i))) << "patch " << i;
      ASSERT_TRUE(SameBits(result.Brightness[k], serial.Brightness(i))) << "patch " << i;
      ASSERT_TRUE(SameBits(result.Toward[k], serial.ExitantRadianceToward(i, oblique)))
        << "patch " << i;
      ASSERT_TRUE(SameBits(result.Lamp[i], serialLamp[i])) << "patch " << i;
    }
    // The rows' incident radiances are the serial ones, entry e of the rank's rows being entry
    // KeptEntries(Receivers)[e] of the cover.
    const std::vector<std::size_t> kept = RowShares::KeptEntries(cover, result.Receivers);
    ASSERT_EQ(result.Incident.size(), kept.size());
    const std::vector<glm::dvec3>& serialIncident = serial.IncidentRadiances();
    for (std::size_t e = 0; e < result.Incident.size(); ++e)
    {
      ASSERT_TRUE(SameBits(result.Incident[e], serialIncident[kept[e]])) << "entry " << e;
    }
    for (int b = 0; b < 3; ++b)
    {
      EXPECT_NEAR(
        result.Energy.Emitted[b], serialEnergy.Emitted[b], 1e-12 * serialEnergy.Emitted[b]);
      EXPECT_NEAR(
        result.Energy.Absorbed[b], serialEnergy.Absorbed[b], 1e-12 * serialEnergy.Emitted[b]);
      EXPECT_NEAR(result.Energy.Unshot[b], serialEnergy.Unshot[b], 1e-12 * serialEnergy.Emitted[b]);
    }
  }
}

/// How one rank's Run ended.
struct RankEnd
{
  bool Converged = false;
  std::string Failure;
  std::size_t Shots = 0;
};

/// Runs the propagation of `cover` (batches of 16, the strip-pair method, to 1e-3 of the
/// emitted power unshot) on `ranks` ranks, rank r joining through share(world, r) and reporting
/// progress to progress(r); the receivers dealt round the ranks.
std::vector<RankEnd> RunOnRanks(const SphericalCover& cover,
  const std::vector<Patch>& patches,
  const std::vector<Material>& materials,
  int ranks,
  const std::function<RankShare(InProcessRanks&, int)>& share,
  const std::function<ProgressCallback(int)>& progress)
{
  const std::vector<HemisphereFrame> frames = FramesOf(patches);
  PropagationSettings settings;
  settings.ConvergenceTolerance = 1e-3;
  settings.ShotBatch = 16;
  InProcessRanks world(ranks);
  std::vector<RankEnd> ends(static_cast<std::size_t>(ranks));
  world.Run(
    [&](const RankShare&, int rank)
    {
      RankEnd& end = ends[static_cast<std::size_t>(rank)];
      try
      {
        const RankShare rankShare = share(world, rank);
        const SphericalCover rows = RowShares::RowsOf(cover, rankShare.MyItems(cover.PatchCount()));
        LightPropagation shared(rows, materials);
        shared.SetFrames(frames);
        shared.SetDirectionalMethod(DirectionalMethod::StripPairs);
        SharePropagation(shared, rankShare);
        end.Converged = shared.Run(settings, progress(rank));
        end.Shots = shared.History().size();
      }
      catch (const std::exception& e)
      {
        end.Failure = e.what();
      }
    });
  return ends;
}

/// Rank `rank` of `world`'s share, with `joined` called on every join that succeeded with the
/// joined blocks (in rank order), before the rank reads them.
RankShare WatchedShare(InProcessRanks& world,
  int rank,
  int ranks,
  std::function<void(std::vector<std::vector<char>>&)> joined)
{
  const RankShare inner = world.Share(rank);
  return RankShare(rank,
    ranks,
    [inner, ranks, joined](const std::vector<char>& mine,
      bool ok,
      bool sameSize,
      std::vector<std::vector<char>>& all,
      std::vector<char>& oks)
    {
      const bool good = sameSize ? inner.JoinSameSize(mine, ok, all) : inner.Join(mine, ok, all);
      oks.assign(static_cast<std::size_t>(ranks), good ? 1 : 0);
      if (good)
      {
        joined(all);
      }
    });
}

/// The furnace box with mirror, phong and tabulated surfaces (MixedMaterialsEqualSerial).
std::vector<Material> MixedMaterialsOf(const std::vector<Patch>& patches)
{
  const std::vector<Material> ofSurface = { Diffuse(glm::dvec3(0.5), glm::dvec3(1.0, 2.0, 3.0)),
    Mirror(glm::dvec3(0.9, 0.8, 0.7)),
    Phong(glm::dvec3(0.3, 0.2, 0.1), glm::dvec3(0.5, 0.4, 0.6), 30.0),
    Clay(),
    Diffuse(glm::dvec3(0.7, 0.6, 0.5)),
    Phong(glm::dvec3(0.1), glm::dvec3(0.8), 5.0) };
  std::vector<Material> materials;
  for (const Patch& patch : patches)
  {
    materials.push_back(ofSurface.at(static_cast<size_t>(patch.SurfaceIndex) % ofSurface.size()));
  }
  return materials;
}

} // namespace

TEST(SharedPropagation, CornellBoxEqualsSerial)
{
  const CoveredScene setup("cornell_box.scene", 3);
  for (const std::size_t batch : { 1, 16 })
  {
    for (const int ranks : { 2, 3 })
    {
      ExpectSharedEqualsSerial(setup.Cover, setup.Patches, setup.Materials, ranks, batch);
    }
  }
}

// Mirror, phong and tabulated shooters send their row's radiances and in-strips (strip-pair
// shots) or their grid (grid shots) to the other ranks; in batches, several ranks' shots at once.
TEST(SharedPropagation, MixedMaterialsEqualSerial)
{
  const CoveredScene setup("furnace_box.scene", 2);
  const std::vector<Material> materials = MixedMaterialsOf(setup.Patches);
  for (const DirectionalMethod method : { DirectionalMethod::StripPairs, DirectionalMethod::Grid })
  {
    SCOPED_TRACE(testing::Message() << "method " << static_cast<int>(method));
    for (const std::size_t batch : { 1, 16 })
    {
      for (const int ranks : { 2, 3 })
      {
        ExpectSharedEqualsSerial(setup.Cover, setup.Patches, materials, ranks, batch, method);
      }
    }
  }
}

// Panes (paper §5.4): the transposed entries another rank's receivers match are those seen
// through the same panes (the keys exchanged by SharePropagation carry layer and filter). Here, of
// the scenes above, other ranks' receivers also read fallback cells of a shot (receivers
// without h_ji): by both methods, the owner's radiance toward those cells.
TEST(SharedPropagation, PanesEqualSerial)
{
  std::ifstream file(ScenePath("mixed_box.scene"));
  nlohmann::json scene = nlohmann::json::parse(file);
  AddPaneAcrossMixedBox(scene);
  const PaneScene setup(ParseScene(scene.dump(), ScenePath("mixed_box.scene")), 3, 8, 32);
  ASSERT_TRUE(setup.Cover.HasPanes());
  for (const DirectionalMethod method : { DirectionalMethod::StripPairs, DirectionalMethod::Grid })
  {
    SCOPED_TRACE(testing::Message() << "method " << static_cast<int>(method));
    ExpectSharedEqualsSerial(setup.Cover, setup.Patches, setup.Materials, 3, 16, method);
  }
}

// A rank holding another rank's rows is refused (the whole cover on rank 0 of 2; rank 1's rows
// on rank 0); its own rows alone, and an empty cover's, are taken.
TEST(SharedPropagation, RefusesAnotherRanksRows)
{
  const CoveredScene setup("cornell_box.scene", 1);
  const std::size_t n = setup.Cover.PatchCount();
  InProcessRanks world(2);
  LightPropagation whole(setup.Cover, setup.Materials);
  EXPECT_THROW(SharePropagation(whole, world.Share(0)), std::invalid_argument);
  // The propagation keeps a reference to its cover: the rows outlive it.
  const SphericalCover rank1Rows = RowShares::RowsOf(setup.Cover, RankShare::ItemsOf(1, 2, n));
  LightPropagation others(rank1Rows, setup.Materials);
  EXPECT_THROW(SharePropagation(others, world.Share(0)), std::invalid_argument);
  const SphericalCover noRows = RowShares::RowsOf(setup.Cover, {});
  LightPropagation empty(noRows, setup.Materials);
  EXPECT_NO_THROW(SharePropagation(empty, RankShare()));
}

// RowsOf keeps the given rows whole and in order (strips, measures, the entries' strips
// re-based) and empties the others; receivers out of range or order are refused.
TEST(SharedPropagation, RowsOfKeepsTheGivenRows)
{
  const CoveredScene setup("cornell_box.scene", 2);
  const SphericalCover& cover = setup.Cover;
  const std::vector<std::size_t> receivers = RankShare::ItemsOf(1, 3, cover.PatchCount());
  const SphericalCover rows = RowShares::RowsOf(cover, receivers);
  const std::vector<std::size_t> kept = RowShares::KeptEntries(cover, receivers);
  ASSERT_EQ(rows.PatchCount(), cover.PatchCount());
  ASSERT_EQ(rows.EntryCount(), kept.size());
  std::size_t next = 0;
  for (std::size_t i = 0; i < cover.PatchCount(); ++i)
  {
    const bool own = next < receivers.size() && receivers[next] == i;
    next += own ? 1 : 0;
    EXPECT_EQ(rows.PatchArea(i), cover.PatchArea(i));
    ASSERT_EQ(
      rows.EntryEnd(i) - rows.EntryBegin(i), own ? cover.EntryEnd(i) - cover.EntryBegin(i) : 0u)
      << "row " << i;
    for (std::size_t e = rows.EntryBegin(i); e < rows.EntryEnd(i); ++e)
    {
      const std::size_t original = kept[e];
      EXPECT_EQ(rows.EntryAt(e).Source, cover.EntryAt(original).Source);
      EXPECT_EQ(rows.ProjectedSolidAngle(e), cover.ProjectedSolidAngle(original));
      if (cover.HasUnoccluded())
      {
        EXPECT_EQ(
          rows.UnoccludedProjectedSolidAngle(e), cover.UnoccludedProjectedSolidAngle(original));
      }
      ASSERT_EQ(rows.StripEnd(e) - rows.StripBegin(e),
        cover.StripEnd(original) - cover.StripBegin(original));
      for (std::size_t k = 0; k < rows.StripEnd(e) - rows.StripBegin(e); ++k)
      {
        const SphericalCover::Strip& a = rows.StripAt(rows.StripBegin(e) + k);
        const SphericalCover::Strip& b = cover.StripAt(cover.StripBegin(original) + k);
        EXPECT_EQ(a.Row, b.Row);
        EXPECT_EQ(a.PhiBegin, b.PhiBegin);
        EXPECT_EQ(a.PhiEnd, b.PhiEnd);
        EXPECT_EQ(rows.StripDepth(rows.StripBegin(e) + k),
          cover.StripDepth(cover.StripBegin(original) + k));
      }
    }
  }
  EXPECT_THROW(RowShares::RowsOf(cover, { 2, 1 }), std::invalid_argument);
  EXPECT_THROW(RowShares::RowsOf(cover, { cover.PatchCount() }), std::invalid_argument);
}

// A rank whose progress asks to stop (ParaView's abort on one rank) stops every rank after the
// same batch: each Run returns false, none hangs, all made the same shots.
TEST(SharedPropagation, ARankThatAbortsStopsEveryRank)
{
  const CoveredScene setup("furnace_box.scene", 2);
  const std::vector<Material> materials = MixedMaterialsOf(setup.Patches);
  for (const int aborting : { 0, 2 })
  {
    SCOPED_TRACE(testing::Message() << "rank " << aborting << " aborts");
    const std::vector<RankEnd> ends = RunOnRanks(
      setup.Cover,
      setup.Patches,
      materials,
      3,
      [](InProcessRanks& world, int rank) { return world.Share(rank); },
      [aborting](int rank) -> ProgressCallback
      {
        auto reports = std::make_shared<int>(0);
        return [rank, aborting, reports](double) { return rank != aborting || ++*reports < 3; };
      });
    for (const RankEnd& end : ends)
    {
      EXPECT_EQ(end.Failure, "");
      EXPECT_FALSE(end.Converged);
      EXPECT_GT(end.Shots, 0u);
      EXPECT_EQ(end.Shots, ends.front().Shots);
    }
  }
}

// Bytes damaged on their way between ranks (one rank's block of one join, seen alike by every
// rank, as an all-gather delivers it), at every join of the setup and the first batches and
// at later ones: every rank stops (the damage named on some rank, the others told that another
// failed), or, where the damaged block is not read, every rank converges; none goes on alone
// to a join the others never reach (it would hang here).
TEST(SharedPropagation, DamagedBytesStopEveryRank)
{
  const CoveredScene setup("furnace_box.scene", 2);
  const std::vector<Material> materials = MixedMaterialsOf(setup.Patches);
  const auto noProgress = [](int) { return ProgressCallback(); };
  // The number of joins of a whole run (every rank joins as often).
  std::size_t joins = 0;
  const std::vector<RankEnd> clean = RunOnRanks(
    setup.Cover,
    setup.Patches,
    materials,
    2,
    [&joins](InProcessRanks& world, int rank)
    {
      return WatchedShare(world,
        rank,
        2,
        [rank, &joins](std::vector<std::vector<char>>&) { joins += rank == 0 ? 1 : 0; });
    },
    noProgress);
  ASSERT_TRUE(clean[0].Converged && clean[1].Converged);
  ASSERT_GT(joins, 40u);

  std::vector<std::size_t> targets = { 0, 1, 2, 3, 4, 5 };
  for (std::size_t target = 6; target < joins; target += joins / 4)
  {
    targets.push_back(target);
  }
  std::size_t stopped = 0;
  for (const std::size_t target : targets)
  {
    for (const int victim : { 0, 1 })
    {
      SCOPED_TRACE(testing::Message()
        << "join " << target << " of " << joins << ", rank " << victim << "'s bytes damaged");
      const std::vector<RankEnd> ends = RunOnRanks(
        setup.Cover,
        setup.Patches,
        materials,
        2,
        [target, victim](InProcessRanks& world, int rank)
        {
          auto count = std::make_shared<std::size_t>(0);
          return WatchedShare(world,
            rank,
            2,
            [count, target, victim](std::vector<std::vector<char>>& all)
            {
              if ((*count)++ != target)
              {
                return;
              }
              std::vector<char>& bytes = all[static_cast<std::size_t>(victim)];
              if (bytes.empty())
              {
                bytes.push_back(1);
              }
              else
              {
                bytes.pop_back();
              }
            });
        },
        noProgress);
      const bool failed = !ends[0].Failure.empty();
      EXPECT_EQ(!ends[1].Failure.empty(), failed);
      if (!failed)
      {
        EXPECT_TRUE(ends[0].Converged && ends[1].Converged);
        EXPECT_EQ(ends[0].Shots, clean[0].Shots);
        continue;
      }
      ++stopped;
      bool named = false;
      for (const RankEnd& end : ends)
      {
        const bool damage = end.Failure.find("damaged") != std::string::npos ||
          end.Failure.find("not whole values") != std::string::npos;
        named = named || damage;
        EXPECT_TRUE(damage || end.Failure == RankShare::PeerFailure::Text) << end.Failure;
      }
      EXPECT_TRUE(named);
    }
  }
  // Almost every join's blocks are read: most damages stop the ranks.
  EXPECT_GT(stopped, targets.size());
}
