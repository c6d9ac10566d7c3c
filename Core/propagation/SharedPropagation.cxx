// SPDX-License-Identifier: BSD-3-Clause
// LightPropagation under MPI (SetRankShare in LightPropagation.h; the class is declared
// there): the ranks' rows, the once-only exchange of their non-diffuse rows (keys and regions),
// the scan joined every shot, and a non-diffuse shot divided among the ranks. Communication per
// shot: one all-gather of K x 89 bytes (the scan, with what a Lambertian shot sends); for a
// non-diffuse shooter two joins more, the owner's unshot in-strips and then each rank's
// reflected out rows (DirectionalShot.cxx; Documentation/notes/distributed-solve.md).
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
  // Every rank reflects a share of a non-diffuse shot's out rows and forms the shooter's
  // radiance toward each region of its row (ReflectInStrips): every rank gets every
  // non-diffuse row's regions (strips and Omega_e) once, here. The receivers of the other
  // ranks find theirs by the position of (j, i) in row j, matched from the rows' keys.
  std::vector<char> mine;
  ByteWriter out(mine);
  for (std::size_t j = firstOwned; j < lastOwned; ++j)
  {
    if (this->ModelOfPatch[j] < 0)
    {
      continue;
    }
    const RowRegions row = this->RegionsOf(j);
    const std::size_t firstStrip = row.Count > 0 ? row.StripBegin(0) : 0;
    std::vector<EntryKey> keys;
    std::vector<SphericalCover::Entry> entries;
    for (std::size_t e = this->Cover.EntryBegin(j); e < this->Cover.EntryEnd(j); ++e)
    {
      const SphericalCover::Entry& entry = this->Cover.EntryAt(e);
      keys.push_back({ entry.Source, this->Cover.Layer(e), glm::vec3(this->Cover.Filter(e)) });
      entries.push_back({ entry.Source, static_cast<uint32_t>(entry.FirstStrip - firstStrip) });
    }
    out.Value(static_cast<uint64_t>(j));
    out.Array(keys);
    out.Array(entries);
    out.Array(std::vector<SphericalCover::Strip>(
      row.Strips + firstStrip, row.Strips + (row.Count > 0 ? row.StripsEnd : firstStrip)));
    out.Array(std::vector<double>(row.Omega, row.Omega + row.Count));
  }
  std::vector<std::vector<char>> all;
  if (!this->Share.Join(mine, true, all))
  {
    throw RankShare::PeerFailure();
  }
  std::vector<std::vector<EntryKey>> remoteKeys(n);
  this->RemoteRows.assign(n, RemoteRow());
  for (std::size_t r = 0; r < all.size(); ++r)
  {
    if (static_cast<int>(r) == this->Share.Rank())
    {
      continue;
    }
    ByteReader in(all[r]);
    while (!in.AtEnd())
    {
      uint64_t j = 0;
      Expect(in.Value(j) && j < n, "rows");
      RemoteRow& row = this->RemoteRows[static_cast<std::size_t>(j)];
      Expect(in.Array(remoteKeys[static_cast<std::size_t>(j)]) && in.Array(row.Entries) &&
          in.Array(row.Strips) && in.Array(row.Omega),
        "rows");
      bool consistent = row.Entries.size() == remoteKeys[static_cast<std::size_t>(j)].size() &&
        row.Omega.size() == row.Entries.size();
      for (std::size_t e = 0; consistent && e < row.Entries.size(); ++e)
      {
        const std::size_t end =
          e + 1 < row.Entries.size() ? row.Entries[e + 1].FirstStrip : row.Strips.size();
        consistent = row.Entries[e].FirstStrip <= end && end <= row.Strips.size();
      }
      Expect(consistent, "rows");
    }
  }
  this->MatchTransposedEntries(remoteKeys);
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
  // The owner takes its unshot in-strips (its row's state) and sends them; the others find
  // them as the one non-empty block. Every rank then reflects its out rows (ReflectInStrips).
  std::vector<char> bytes;
  std::exception_ptr failure;
  if (owner)
  {
    try
    {
      this->TakeUnshotInStrips(shooter);
      ByteWriter out(bytes);
      out.Value(static_cast<uint8_t>(1));
      for (const std::vector<InStrip>& strips : this->DirectionalIn)
      {
        out.Array(strips);
      }
    }
    catch (...)
    {
      failure = std::current_exception();
    }
  }
  const std::vector<std::vector<char>> all = this->JoinOutRows(bytes, failure);
  if (!owner)
  {
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
    uint8_t marker = 0;
    bool read = in.Value(marker);
    this->DirectionalIn.resize(static_cast<std::size_t>(this->Cover.Grid().ThetaBins()));
    for (std::vector<InStrip>& strips : this->DirectionalIn)
    {
      read = read && in.Array(strips);
    }
    Expect(read && in.AtEnd(), "in-strips");
  }
  return this->ReflectInStrips(shooter);
}

std::vector<std::vector<char>> LightPropagation::JoinOutRows(const std::vector<char>& mine,
  std::exception_ptr failure) const
{
  std::vector<std::vector<char>> all;
  const bool everyRankOk = this->Share.Join(mine, !failure, all);
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  if (!everyRankOk)
  {
    throw RankShare::PeerFailure();
  }
  return all;
}

} // namespace sphcover
