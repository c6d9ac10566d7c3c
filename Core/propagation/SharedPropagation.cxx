// SPDX-License-Identifier: BSD-3-Clause
// LightPropagation under MPI (SetRankShare in LightPropagation.h; the class is declared
// there): the ranks' rows, the once-only exchange of the keys of their non-diffuse rows, the
// scan joined every batch, and the batch's non-diffuse shots sent by their owners.
// Communication per batch of B shots: one all-gather of K x (32 + 48 B + 24 B) bytes (the scan,
// with what a Lambertian shot sends and the last batch's counts), and when the batch has
// non-diffuse shooters a second join of their rows' radiances and their unshot in-strips or
// their grids (Documentation/notes/distributed-solve.md).
#include "propagation/LightPropagation.h"

#include "cover/SphericalCover.h"
#include "math/ByteBuffer.h"

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <string>
#include <utility>

namespace sphcover
{

namespace
{

/// A read of another rank's bytes that must succeed (ByteReader's false: they are damaged).
void Expect(bool read, const char* what)
{
  if (!read)
  {
    throw std::runtime_error(std::string("LightPropagation: a rank's ") + what + " are damaged");
  }
}

} // namespace

void LightPropagation::SetRankShare(RankShare share, std::size_t firstOwned, std::size_t lastOwned)
{
  const std::size_t n = this->PatchCount();
  if (firstOwned > lastOwned || lastOwned > n)
  {
    throw std::invalid_argument("LightPropagation: receivers [" + std::to_string(firstOwned) +
      ", " + std::to_string(lastOwned) + ") of " + std::to_string(n));
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    if ((i < firstOwned || i >= lastOwned) && this->Cover.EntryEnd(i) > this->Cover.EntryBegin(i))
    {
      throw std::invalid_argument("LightPropagation: row " + std::to_string(i) +
        " is outside this rank's receivers [" + std::to_string(firstOwned) + ", " +
        std::to_string(lastOwned) + ") but not empty (SphericalCover::RowsOf)");
    }
  }
  this->Share = std::move(share);
  this->OwnedFirst = firstOwned;
  this->OwnedLast = lastOwned;
  if (this->Reflectances.Empty() || !this->Shared())
  {
    return;
  }
  // A non-diffuse shooter's owner sends its radiance toward each region of its row; the
  // receivers of the other ranks find theirs by the position of (j, i) in row j, matched once
  // here from the keys of every rank's non-diffuse rows.
  std::vector<char> mine;
  ByteWriter out(mine);
  for (std::size_t j = firstOwned; j < lastOwned; ++j)
  {
    if (this->ModelOfPatch[j] < 0)
    {
      continue;
    }
    std::vector<EntryKey> keys;
    for (std::size_t e = this->Cover.EntryBegin(j); e < this->Cover.EntryEnd(j); ++e)
    {
      keys.push_back({ this->Cover.EntryAt(e).Source,
        this->Cover.Layer(e),
        glm::vec3(this->Cover.Filter(e)) });
    }
    out.Value(static_cast<uint64_t>(j));
    out.Array(keys);
  }
  std::vector<std::vector<char>> all;
  if (!this->Share.Join(mine, true, all))
  {
    throw RankShare::PeerFailure();
  }
  std::vector<std::vector<EntryKey>> remoteRows(n);
  for (std::size_t r = 0; r < all.size(); ++r)
  {
    if (static_cast<int>(r) == this->Share.Rank())
    {
      continue;
    }
    ByteReader in(all[r]);
    while (!in.AtEnd())
    {
      uint64_t row = 0;
      Expect(in.Value(row) && row < n && in.Array(remoteRows[static_cast<std::size_t>(row)]),
        "row keys");
    }
  }
  this->MatchTransposedEntries(remoteRows);
  this->EncodeFallbacks();
}

bool LightPropagation::JoinScan(std::vector<Candidate>& batch,
  double& largest,
  double& unshot,
  std::size_t size,
  bool stop,
  std::vector<ShotRecord>* records)
{
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
    const Candidate none;
    const Candidate& candidate = c < batch.size() ? batch[c] : none;
    mine.push_back(static_cast<double>(candidate.Shooter));
    mine.push_back(candidate.Power);
    mine.push_back(candidate.Increment.x);
    mine.push_back(candidate.Increment.y);
    mine.push_back(candidate.Increment.z);
    mine.push_back(candidate.Directional ? 1.0 : 0.0);
  }
  const std::size_t stride = mine.size();
  const std::vector<double> scans = JoinValues(this->Share, mine.data(), stride, true);
  if (scans.size() != stride * static_cast<std::size_t>(this->Share.Ranks()))
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
      Candidate candidate;
      candidate.Shooter = static_cast<std::size_t>(values[0]);
      Expect(candidate.Shooter < this->PatchCount(), "scans");
      candidate.Power = values[1];
      candidate.Increment = glm::dvec3(values[2], values[3], values[4]);
      candidate.Directional = values[5] != 0.0;
      batch.push_back(candidate);
    }
  }
  SelectBatch(batch, largest, size);
  for (std::size_t m = 0; m < members; ++m)
  {
    ShotRecord& record = (*records)[m];
    record.ReceiverUpdates = static_cast<std::size_t>(counts[3 * m]);
    record.Fallbacks = static_cast<std::size_t>(counts[3 * m + 1]);
    record.MeanFallbacks = static_cast<std::size_t>(counts[3 * m + 2]);
  }
  return !someRankStops;
}

void LightPropagation::ShareDirectionalShots(const std::vector<Candidate>& batch,
  const std::vector<bool>& directional,
  std::vector<DirectionalShotData>& data,
  bool ok)
{
  // Each rank packs the shots of its own members (computed by ShootBatch, as serial), in the
  // batch's order; one join gives every rank every shot, each found by its member index.
  std::vector<char> bytes;
  if (ok)
  {
    ByteWriter out(bytes);
    for (std::size_t m = 0; m < batch.size(); ++m)
    {
      const std::size_t shooter = batch[m].Shooter;
      if (!directional[m] || shooter < this->OwnedFirst || shooter >= this->OwnedLast)
      {
        continue;
      }
      const DirectionalShotData& shot = data[m];
      out.Value(static_cast<uint64_t>(m));
      out.Value(shot.Mean);
      out.Value(static_cast<uint8_t>(shot.Grid ? 1 : 0));
      out.Value(static_cast<uint64_t>(shot.WeightEvaluations));
      out.Array(shot.Out);
      if (shot.Grid)
      {
        out.Array(shot.GridOut);
      }
      else
      {
        for (std::size_t row = 0; row < shot.In.size(); ++row)
        {
          out.Array(shot.In[row]);
          out.Array(shot.Coupled[row]);
        }
      }
    }
  }
  std::vector<std::vector<char>> all;
  if (!this->Share.Join(bytes, ok, all))
  {
    if (!ok)
    {
      return; // this rank's own failure is rethrown by the caller
    }
    throw RankShare::PeerFailure();
  }
  const std::size_t rows = static_cast<std::size_t>(this->Cover.Grid().ThetaBins());
  std::vector<bool> received(batch.size(), false);
  for (std::size_t r = 0; r < all.size(); ++r)
  {
    if (static_cast<int>(r) == this->Share.Rank())
    {
      continue;
    }
    ByteReader in(all[r]);
    while (!in.AtEnd())
    {
      uint64_t m = 0;
      Expect(in.Value(m) && m < batch.size() && directional[m] && !received[m], "shot data");
      DirectionalShotData& shot = data[m];
      uint8_t grid = 0;
      uint64_t evaluations = 0;
      bool read = in.Value(shot.Mean) && in.Value(grid) && in.Value(evaluations) &&
        in.Array(shot.Out);
      shot.Grid = grid != 0;
      shot.WeightEvaluations = static_cast<std::size_t>(evaluations);
      if (shot.Grid)
      {
        read = read && in.Array(shot.GridOut);
      }
      else
      {
        shot.In.resize(rows);
        shot.Coupled.resize(rows);
        for (std::size_t row = 0; row < rows; ++row)
        {
          read = read && in.Array(shot.In[row]) && in.Array(shot.Coupled[row]);
        }
      }
      Expect(read, "shot data");
      received[m] = true;
    }
  }
  for (std::size_t m = 0; m < batch.size(); ++m)
  {
    const std::size_t shooter = batch[m].Shooter;
    const bool own = shooter >= this->OwnedFirst && shooter < this->OwnedLast;
    Expect(!directional[m] || own || received[m], "shot data (a shot is missing)");
  }
}

} // namespace sphcover
