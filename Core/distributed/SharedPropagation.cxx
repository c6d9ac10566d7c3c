// SPDX-License-Identifier: BSD-3-Clause
// LightPropagation under MPI (SharePropagation in SharedPropagation.h), through its batch hook
// (LightPropagation::BatchHook): the ranks' rows, the once-only exchange of the keys of their
// non-diffuse rows, the scan joined every batch, and the batch's non-diffuse shots sent by their
// owners. Communication per batch of B shots: one all-gather of K x (32 + 48 B + 24 B) bytes (the
// scan, with what a Lambertian shot sends and the last batch's counts), and when the batch has
// non-diffuse shooters a second join of their radiance toward what the other ranks' receivers
// read (the regions of their rows, the cells of their fallbacks and of their views of the
// shooter: ExchangeShotNeeds)
// (Documentation/notes/distributed-solve.md).
#include "distributed/SharedPropagation.h"

#include "cover/SphericalCover.h"
#include "distributed/RowShares.h"
#include "math/ByteBuffer.h"

#include <algorithm>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

namespace sphcover
{

namespace
{

/// A read of a rank's joined bytes that must succeed (ByteReader's false: they are damaged).
/// Every rank reads every rank's block, its own too, and so reaches the same verdict from the
/// same joined bytes: damaged bytes stop all the ranks at once, and none goes on alone to a
/// join the others never reach.
void Expect(bool read, const char* what)
{
  if (!read)
  {
    throw std::runtime_error(std::string("LightPropagation: a rank's ") + what + " are damaged");
  }
}

/// `values` sorted, each once.
void SortUnique(std::vector<uint32_t>& values)
{
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
}

} // namespace

/// The batch hook of a propagation shared among ranks (LightPropagation::BatchHook): what it
/// adds to each batch, and the shot needs it keeps for them.
class SharedPropagation final : public LightPropagation::BatchHook
{
public:
  explicit SharedPropagation(LightPropagation& propagation)
    : Propagation(propagation)
  {
  }
  /// SharePropagation's body (SharedPropagation.h).
  static void Install(LightPropagation& propagation, RankShare share);

  bool JoinScan(std::vector<LightPropagation::Candidate>& batch,
    double& largest,
    double& unshot,
    std::size_t size,
    bool stop,
    std::vector<ShotRecord>* records) override;
  void ShareDirectionalShots(const std::vector<LightPropagation::Candidate>& batch,
    const std::vector<bool>& directional,
    std::vector<LightPropagation::DirectionalShotData>& data,
    bool ok) override;
  void FallbacksChanged() override { this->ShotNeedsKnown = false; }

private:
  /**
   * Which of a non-diffuse shot's values the other ranks read, per non-diffuse row j: the
   * positions in row j of the entries (j, i) of their receivers i (SentPositions[j]) and the
   * cells of the directions toward their receivers without h_ji or of their receivers' views
   * of Q_j (LightPropagation.h; SentCells[j]), each the sorted union over the ranks, the same
   * on every rank. A view is built from the receiver's own row, which its rank holds. Collective;
   * from the first JoinScan of a Run, once after SharePropagation or SetFrames.
   */
  void ExchangeShotNeeds();

  LightPropagation& Propagation;
  /// ExchangeShotNeeds' unions, by row, and whether they are up to date.
  std::vector<std::vector<uint32_t>> SentPositions;
  std::vector<std::vector<uint32_t>> SentCells;
  bool ShotNeedsKnown = false;
};

void SharePropagation(LightPropagation& propagation, RankShare share)
{
  SharedPropagation::Install(propagation, std::move(share));
}

void SharedPropagation::Install(LightPropagation& propagation, RankShare share)
{
  const std::size_t n = propagation.PatchCount();
  const std::size_t i = RowShares::FirstForeignRow(propagation.Cover, share);
  if (i < n)
  {
    throw std::invalid_argument("LightPropagation: row " + std::to_string(i) + " is rank " +
      std::to_string(i % static_cast<std::size_t>(share.Ranks())) + "'s receiver's, not rank " +
      std::to_string(share.Rank()) + "'s, but not empty (RowShares::RowsOf)");
  }
  propagation.Share = std::move(share);
  propagation.Hook.reset();
  if (!propagation.Share.Distributed())
  {
    return;
  }
  propagation.Hook = std::make_unique<SharedPropagation>(propagation);
  if (propagation.Reflectances.Empty())
  {
    return;
  }
  // A non-diffuse shooter's owner sends its radiance toward each region of its row; the
  // receivers of the other ranks find theirs by the position of (j, i) in row j, matched once
  // here from the keys of every rank's non-diffuse rows.
  std::vector<char> mine;
  ByteWriter out(mine);
  for (const std::size_t j : propagation.Share.MyItems(n))
  {
    if (propagation.ModelOfPatch[j] < 0)
    {
      continue;
    }
    std::vector<LightPropagation::EntryKey> keys;
    for (std::size_t e = propagation.Cover.EntryBegin(j); e < propagation.Cover.EntryEnd(j); ++e)
    {
      keys.push_back({ propagation.Cover.EntryAt(e).Source,
        propagation.Cover.Layer(e),
        glm::vec3(propagation.Cover.Filter(e)) });
    }
    out.Value(static_cast<uint64_t>(j));
    out.Array(keys);
  }
  std::vector<std::vector<char>> all;
  if (!propagation.Share.Join(mine, true, all))
  {
    throw RankShare::PeerFailure();
  }
  std::vector<std::vector<LightPropagation::EntryKey>> remoteRows(n);
  std::vector<LightPropagation::EntryKey> ownKeys;
  for (std::size_t r = 0; r < all.size(); ++r)
  {
    const bool own = static_cast<int>(r) == propagation.Share.Rank();
    ByteReader in(all[r]);
    while (!in.AtEnd())
    {
      uint64_t row = 0;
      Expect(in.Value(row) && row < n &&
          in.Array(own ? ownKeys : remoteRows[static_cast<std::size_t>(row)]),
        "row keys");
    }
  }
  propagation.MatchTransposedEntries(remoteRows);
  propagation.EncodeFallbacks();
}

void SharedPropagation::ExchangeShotNeeds()
{
  // Each rank lists, for every non-diffuse row another rank owns, what its receivers in that
  // row's column read of a shot: the positions ColumnBack points at and the cells of its
  // fallbacks (the mean goes with every shot). Every rank gets every list and forms the same
  // unions: the owner packs those values, the others find them in that order.
  const std::size_t n = this->Propagation.PatchCount();
  std::vector<char> mine;
  ByteWriter out(mine);
  std::vector<uint32_t> positions;
  std::vector<uint32_t> cells;
  for (std::size_t j = 0; j < n; ++j)
  {
    if (this->Propagation.ModelOfPatch[j] < 0 || this->Propagation.Owns(j))
    {
      continue;
    }
    positions.clear();
    cells.clear();
    for (std::size_t k = this->Propagation.Cover.ColumnBegin(j);
         k < this->Propagation.Cover.ColumnEnd(j);
         ++k)
    {
      const uint32_t back = this->Propagation.ColumnBack[k];
      if (this->Propagation.HasView(j, k))
      {
        // A receiver's view of a non-diffuse shooter reads the cells of its view alone.
        for (std::size_t v = this->Propagation.ViewStart(j, k);
             v < this->Propagation.ViewStart(j, k + 1);
             ++v)
        {
          cells.push_back(this->Propagation.Views[v].Cell);
        }
      }
      else if (back < LightPropagation::FallbackFlag)
      {
        positions.push_back(back);
      }
      else if (back != LightPropagation::NoEntry)
      {
        cells.push_back(back & ~LightPropagation::FallbackFlag);
      }
    }
    if (positions.empty() && cells.empty())
    {
      continue;
    }
    SortUnique(positions);
    SortUnique(cells);
    out.Value(static_cast<uint64_t>(j));
    out.Array(positions);
    out.Array(cells);
  }
  std::vector<std::vector<char>> all;
  if (!this->Propagation.Share.Join(mine, true, all))
  {
    throw RankShare::PeerFailure();
  }
  this->SentPositions.assign(n, {});
  this->SentCells.assign(n, {});
  const uint32_t cellCount = static_cast<uint32_t>(this->Propagation.Cover.Grid().CellCount());
  for (const std::vector<char>& rankBytes : all)
  {
    ByteReader in(rankBytes);
    while (!in.AtEnd())
    {
      uint64_t j = 0;
      Expect(in.Value(j) && j < n && this->Propagation.ModelOfPatch[j] >= 0 &&
          in.Array(positions) && in.Array(cells),
        "shot needs");
      for (const uint32_t cell : cells)
      {
        Expect(cell < cellCount, "shot needs");
      }
      std::vector<uint32_t>& sent = this->SentPositions[j];
      sent.insert(sent.end(), positions.begin(), positions.end());
      std::vector<uint32_t>& sentCells = this->SentCells[j];
      sentCells.insert(sentCells.end(), cells.begin(), cells.end());
    }
  }
  bool fits = true;
  for (std::size_t j = 0; j < n; ++j)
  {
    SortUnique(this->SentPositions[j]);
    SortUnique(this->SentCells[j]);
    // An owner's row must hold every position its receivers elsewhere read. Only the owner
    // can tell, so the ranks join its verdict: none goes on alone.
    if (this->Propagation.Owns(j) && !this->SentPositions[j].empty())
    {
      fits = fits &&
        this->SentPositions[j].back() <
          this->Propagation.Cover.EntryEnd(j) - this->Propagation.Cover.EntryBegin(j);
    }
  }
  if (!this->Propagation.Share.EveryRankOk(fits))
  {
    Expect(fits, "shot needs");
    throw RankShare::PeerFailure();
  }
  this->ShotNeedsKnown = true;
}

bool SharedPropagation::JoinScan(std::vector<LightPropagation::Candidate>& batch,
  double& largest,
  double& unshot,
  std::size_t size,
  bool stop,
  std::vector<ShotRecord>* records)
{
  // What the other ranks read of a non-diffuse shot, found once (again after SetFrames), before
  // the first scan of a Run: every rank is here at the same point.
  if (!this->Propagation.Reflectances.Empty() && !this->ShotNeedsKnown)
  {
    this->ExchangeShotNeeds();
  }
  // One block of doubles per rank, as many on every rank: its largest power, unshot energy,
  // whether it stops, the last batch's counts per member (every rank had the same batch), and
  // its candidates padded to `size`, each with what a Lambertian shot of it sends (its unshot
  // radiance), so that such a shot needs no exchange of its own.
  const std::size_t members = records ? records->size() : 0;
  constexpr std::size_t PerCandidate = 6;
  std::vector<double> mine;
  mine.reserve(4 + 3 * members + PerCandidate * size);
  mine.push_back(largest);
  mine.push_back(unshot);
  mine.push_back(stop ? 1.0 : 0.0);
  for (std::size_t m = 0; m < members; ++m)
  {
    const ShotRecord& record = (*records)[m];
    mine.push_back(static_cast<double>(record.ReceiverUpdates));
    mine.push_back(static_cast<double>(record.Fallbacks));
    mine.push_back(static_cast<double>(record.MeanFallbacks));
  }
  mine.push_back(static_cast<double>(batch.size()));
  for (std::size_t c = 0; c < size; ++c)
  {
    const LightPropagation::Candidate none;
    const LightPropagation::Candidate& candidate = c < batch.size() ? batch[c] : none;
    mine.push_back(static_cast<double>(candidate.Shooter));
    mine.push_back(candidate.Power);
    mine.push_back(candidate.Increment.x);
    mine.push_back(candidate.Increment.y);
    mine.push_back(candidate.Increment.z);
    mine.push_back(candidate.Directional ? 1.0 : 0.0);
  }
  const std::size_t stride = mine.size();
  const std::vector<double> scans = JoinValues(this->Propagation.Share, mine.data(), stride, true);
  if (scans.size() != stride * static_cast<std::size_t>(this->Propagation.Share.Ranks()))
  {
    throw std::runtime_error("LightPropagation: a rank's scan is damaged");
  }
  // The ranks' candidates, chosen among as the serial scan chooses among all patches.
  bool someRankStops = false;
  largest = 0.0;
  unshot = 0.0;
  batch.clear();
  std::vector<double> counts(3 * members, 0.0);
  for (std::size_t at = 0; at < scans.size(); at += stride)
  {
    const double* theirs = scans.data() + at;
    largest = std::max(largest, theirs[0]);
    unshot += theirs[1];
    someRankStops = someRankStops || theirs[2] != 0.0;
    for (std::size_t c = 0; c < 3 * members; ++c)
    {
      counts[c] += theirs[3 + c];
    }
    const double* candidates = theirs + 3 + 3 * members;
    const std::size_t count = static_cast<std::size_t>(candidates[0]);
    Expect(count <= size, "scans");
    for (std::size_t c = 0; c < count; ++c)
    {
      const double* values = candidates + 1 + PerCandidate * c;
      LightPropagation::Candidate candidate;
      candidate.Shooter = static_cast<std::size_t>(values[0]);
      Expect(candidate.Shooter < this->Propagation.PatchCount(), "scans");
      candidate.Power = values[1];
      candidate.Increment = glm::dvec3(values[2], values[3], values[4]);
      candidate.Directional = values[5] != 0.0;
      batch.push_back(candidate);
    }
  }
  LightPropagation::SelectBatch(batch, largest, size);
  for (std::size_t m = 0; m < members; ++m)
  {
    ShotRecord& record = (*records)[m];
    record.ReceiverUpdates = static_cast<std::size_t>(counts[3 * m]);
    record.Fallbacks = static_cast<std::size_t>(counts[3 * m + 1]);
    record.MeanFallbacks = static_cast<std::size_t>(counts[3 * m + 2]);
  }
  return !someRankStops;
}

void SharedPropagation::ShareDirectionalShots(const std::vector<LightPropagation::Candidate>& batch,
  const std::vector<bool>& directional,
  std::vector<LightPropagation::DirectionalShotData>& data,
  bool ok)
{
  // Each rank packs the shots of its own members (computed by ShootBatch, as serial), in the
  // batch's order; one join gives every rank every shot, each found by its member index.
  std::vector<char> bytes;
  std::vector<glm::dvec3> values;
  if (ok)
  {
    ByteWriter out(bytes);
    for (std::size_t m = 0; m < batch.size(); ++m)
    {
      const std::size_t shooter = batch[m].Shooter;
      if (!directional[m] || !this->Propagation.Owns(shooter))
      {
        continue;
      }
      // Only what the other ranks read (ExchangeShotNeeds): the radiance toward their
      // receivers' entries of the row, then toward the cells of their fallbacks.
      const LightPropagation::DirectionalShotData& shot = data[m];
      values.clear();
      for (const uint32_t position : this->SentPositions[shooter])
      {
        values.push_back(shot.Out[position]);
      }
      std::size_t unused = 0;
      for (const uint32_t cell : this->SentCells[shooter])
      {
        values.push_back(this->Propagation.TowardReceiver(
          shooter, LightPropagation::FallbackFlag | cell, shot, unused));
      }
      out.Value(static_cast<uint64_t>(m));
      out.Value(shot.Mean);
      out.Value(static_cast<uint8_t>(shot.Grid ? 1 : 0));
      out.Value(static_cast<uint64_t>(shot.WeightEvaluations));
      out.Array(values);
    }
  }
  std::vector<std::vector<char>> all;
  if (!this->Propagation.Share.Join(bytes, ok, all))
  {
    if (!ok)
    {
      return; // this rank's own failure is rethrown by the caller
    }
    throw RankShare::PeerFailure();
  }
  const std::size_t cellCount =
    static_cast<std::size_t>(this->Propagation.Cover.Grid().CellCount());
  std::vector<bool> received(batch.size(), false);
  for (std::size_t r = 0; r < all.size(); ++r)
  {
    // Its own block too (Expect); a rank keeps its own shots as it computed them.
    const bool own = static_cast<int>(r) == this->Propagation.Share.Rank();
    ByteReader in(all[r]);
    while (!in.AtEnd())
    {
      uint64_t m = 0;
      Expect(in.Value(m) && m < batch.size() && directional[m] && !received[m], "shot data");
      const std::size_t shooter = batch[m].Shooter;
      const std::vector<uint32_t>& positions = this->SentPositions[shooter];
      const std::vector<uint32_t>& cells = this->SentCells[shooter];
      glm::dvec3 mean(0.0);
      uint8_t grid = 0;
      uint64_t evaluations = 0;
      Expect(in.Value(mean) && in.Value(grid) && in.Value(evaluations) && in.Array(values) &&
          values.size() == positions.size() + cells.size(),
        "shot data");
      received[m] = true;
      if (own)
      {
        continue;
      }
      LightPropagation::DirectionalShotData& shot = data[m];
      shot.Mean = mean;
      shot.Grid = grid != 0;
      shot.WeightEvaluations = static_cast<std::size_t>(evaluations);
      // Only the positions and cells this rank's receivers read are set (the others keep what
      // an earlier shot left there, never read).
      shot.ByCell = true;
      if (!positions.empty() && shot.Out.size() <= positions.back())
      {
        shot.Out.resize(positions.back() + 1);
      }
      shot.GridOut.resize(cellCount);
      for (std::size_t p = 0; p < positions.size(); ++p)
      {
        shot.Out[positions[p]] = values[p];
      }
      for (std::size_t c = 0; c < cells.size(); ++c)
      {
        shot.GridOut[cells[c]] = values[positions.size() + c];
      }
    }
  }
  for (std::size_t m = 0; m < batch.size(); ++m)
  {
    Expect(!directional[m] || received[m], "shot data (a shot is missing)");
  }
}

} // namespace sphcover
