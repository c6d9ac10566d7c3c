// SPDX-License-Identifier: BSD-3-Clause
// LightPropagation under MPI (SetRankShare in LightPropagation.h; the class is declared
// there): the ranks' rows, the once-only exchange of the keys of their non-diffuse rows, the
// scan joined every shot, and the shot's data sent by the shooter's owner. Communication per
// shot: one all-gather of K x 89 bytes (the scan, with what a Lambertian shot sends), and for a
// non-diffuse shooter a second join of its row's radiances and its unshot in-strips or its
// grid (Documentation/notes/distributed-solve.md).
#include "propagation/LightPropagation.h"

#include "cover/SphericalCover.h"
#include "math/ByteBuffer.h"

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

bool LightPropagation::JoinScan(std::size_t& brightest,
  double& largest,
  double& unshot,
  bool stop,
  ShotRecord* record)
{
  // This rank's brightest patch comes with what a shot of it sends when it is Lambertian (its
  // unshot radiance), so that such a shot needs no exchange of its own.
  const bool owns = brightest < this->OwnedLast;
  const glm::dvec3 increment = owns ? this->Unshot[brightest] : glm::dvec3(0.0);
  const bool directional =
    owns && this->ModelOfPatch[brightest] >= 0 && this->DirectionalUnshot[brightest] > 0.0;
  const double mine[ScanValues] = { largest,
    static_cast<double>(brightest),
    unshot,
    stop ? 1.0 : 0.0,
    record ? static_cast<double>(record->ReceiverUpdates) : 0.0,
    record ? static_cast<double>(record->Fallbacks) : 0.0,
    record ? static_cast<double>(record->MeanFallbacks) : 0.0,
    increment.x,
    increment.y,
    increment.z,
    directional ? 1.0 : 0.0 };
  const std::vector<double> scans = JoinValues(this->Share, mine, ScanValues, true);
  // The largest power over the ranks, the lowest index on ties: the serial scan's choice.
  bool someRankStops = false;
  largest = -1.0;
  unshot = 0.0;
  double counts[3] = { 0.0, 0.0, 0.0 };
  for (std::size_t at = 0; at + ScanValues <= scans.size(); at += ScanValues)
  {
    const double* theirs = scans.data() + at;
    const std::size_t index = static_cast<std::size_t>(theirs[1]);
    if (theirs[0] > largest || (theirs[0] == largest && index < brightest))
    {
      largest = theirs[0];
      brightest = index;
      this->ScannedIncrement = glm::dvec3(theirs[7], theirs[8], theirs[9]);
      this->ScannedDirectional = theirs[10] != 0.0;
    }
    unshot += theirs[2];
    someRankStops = someRankStops || theirs[3] != 0.0;
    for (int c = 0; c < 3; ++c)
    {
      counts[c] += theirs[4 + c];
    }
  }
  if (record)
  {
    record->ReceiverUpdates = static_cast<std::size_t>(counts[0]);
    record->Fallbacks = static_cast<std::size_t>(counts[1]);
    record->MeanFallbacks = static_cast<std::size_t>(counts[2]);
  }
  return !someRankStops;
}

glm::dvec3 LightPropagation::ShareDirectionalShot(std::size_t shooter, bool owner)
{
  // The owner computes the shot (DirectionalShot, as serial) and packs it; the others send
  // nothing and find the owner's data as the one non-empty block.
  glm::dvec3 mean(0.0);
  std::vector<char> bytes;
  bool ok = true;
  std::exception_ptr failure;
  if (owner)
  {
    try
    {
      mean = this->DirectionalShot(shooter);
      ByteWriter out(bytes);
      out.Value(mean);
      out.Value(static_cast<uint8_t>(this->GridShot ? 1 : 0));
      out.Value(static_cast<uint64_t>(this->LastWeightEvaluations));
      out.Array(this->DirectionalOut);
      if (this->GridShot)
      {
        out.Array(this->GridOut);
      }
      else
      {
        for (std::size_t row = 0; row < this->DirectionalIn.size(); ++row)
        {
          out.Array(this->DirectionalIn[row]);
          out.Array(this->DirectionalCoupled[row]);
        }
      }
    }
    catch (...)
    {
      failure = std::current_exception();
      ok = false;
    }
  }
  std::vector<std::vector<char>> all;
  const bool everyRankOk = this->Share.Join(bytes, ok, all);
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  if (!everyRankOk)
  {
    throw RankShare::PeerFailure();
  }
  if (owner)
  {
    return mean;
  }
  const std::vector<char>* theirs = nullptr;
  for (const std::vector<char>& rankBytes : all)
  {
    if (!rankBytes.empty())
    {
      theirs = &rankBytes;
    }
  }
  if (!theirs)
  {
    throw std::runtime_error("LightPropagation: no rank owns the shooter");
  }
  ByteReader in(*theirs);
  uint8_t grid = 0;
  uint64_t evaluations = 0;
  bool read = in.Value(mean) && in.Value(grid) && in.Value(evaluations) &&
    in.Array(this->DirectionalOut);
  this->GridShot = grid != 0;
  this->LastWeightEvaluations = static_cast<std::size_t>(evaluations);
  if (this->GridShot)
  {
    read = read && in.Array(this->GridOut);
  }
  else
  {
    const std::size_t rows = static_cast<std::size_t>(this->Cover.Grid().ThetaBins());
    this->DirectionalIn.resize(rows);
    this->DirectionalCoupled.resize(rows);
    for (std::size_t row = 0; row < rows; ++row)
    {
      read = read && in.Array(this->DirectionalIn[row]) && in.Array(this->DirectionalCoupled[row]);
    }
  }
  Expect(read, "shot data");
  return mean;
}

} // namespace sphcover
