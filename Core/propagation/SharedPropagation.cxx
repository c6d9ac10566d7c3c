// SPDX-License-Identifier: BSD-3-Clause
// LightPropagation under MPI (SetRankShare in LightPropagation.h; the class is declared
// there): the ranks' rows, the once-only exchange of the keys of their non-diffuse rows, the
// scan joined every shot, and the shot's data sent by the shooter's owner. Communication per
// shot: one all-gather of K x 89 bytes (the scan, with what a Lambertian shot sends), and for a
// non-diffuse shooter a second join of its row's radiances and its unshot in-strips or its
// grid (Documentation/notes/distributed-solve.md).
#include "propagation/LightPropagation.h"

#include "cover/SphericalCover.h"

#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <utility>

namespace sphcover
{

namespace
{

/// Reads values of a trivially copyable type from a byte block, checking its length.
class ByteReader
{
public:
  explicit ByteReader(const std::vector<char>& bytes)
    : Bytes(bytes)
  {
  }

  template <typename T>
  void Read(T* values, std::size_t count)
  {
    if ((this->Bytes.size() - this->At) / sizeof(T) < count)
    {
      throw std::runtime_error("LightPropagation: a rank's shot data are damaged");
    }
    if (count > 0)
    {
      std::memcpy(values, this->Bytes.data() + this->At, count * sizeof(T));
    }
    this->At += count * sizeof(T);
  }

  bool Done() const { return this->At == this->Bytes.size(); }

  template <typename T>
  T Read()
  {
    T value{};
    this->Read(&value, 1);
    return value;
  }

  template <typename T>
  void ReadVector(std::vector<T>& values)
  {
    values.resize(static_cast<std::size_t>(this->Read<uint64_t>()));
    this->Read(values.data(), values.size());
  }

private:
  const std::vector<char>& Bytes;
  std::size_t At = 0;
};

template <typename T>
void AppendVector(std::vector<char>& bytes, const std::vector<T>& values)
{
  const uint64_t count = values.size();
  AppendBytes(bytes, &count, 1);
  AppendBytes(bytes, values.data(), values.size());
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
    const uint64_t row = j;
    AppendBytes(mine, &row, 1);
    AppendVector(mine, keys);
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
    ByteReader reader(all[r]);
    while (!reader.Done())
    {
      const uint64_t row = reader.Read<uint64_t>();
      if (row >= n)
      {
        throw std::runtime_error("LightPropagation: a rank's row keys are damaged");
      }
      reader.ReadVector(remoteRows[static_cast<std::size_t>(row)]);
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
  std::vector<char> bytes;
  AppendBytes(bytes, mine, ScanValues);
  std::vector<std::vector<char>> all;
  if (!this->Share.JoinSameSize(bytes, true, all))
  {
    throw RankShare::PeerFailure();
  }
  // The largest power over the ranks, the lowest index on ties: the serial scan's choice.
  bool someRankStops = false;
  largest = -1.0;
  unshot = 0.0;
  double counts[3] = { 0.0, 0.0, 0.0 };
  for (const std::vector<char>& rankBytes : all)
  {
    double theirs[ScanValues];
    if (rankBytes.size() != sizeof(theirs))
    {
      throw std::runtime_error("LightPropagation: a rank's scan is damaged");
    }
    std::memcpy(theirs, rankBytes.data(), sizeof(theirs));
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
      const uint8_t grid = this->GridShot ? 1 : 0;
      const uint64_t evaluations = this->LastWeightEvaluations;
      AppendBytes(bytes, &mean, 1);
      AppendBytes(bytes, &grid, 1);
      AppendBytes(bytes, &evaluations, 1);
      AppendVector(bytes, this->DirectionalOut);
      if (this->GridShot)
      {
        AppendVector(bytes, this->GridOut);
      }
      else
      {
        for (std::size_t row = 0; row < this->DirectionalIn.size(); ++row)
        {
          AppendVector(bytes, this->DirectionalIn[row]);
          AppendVector(bytes, this->DirectionalCoupled[row]);
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
  ByteReader reader(*theirs);
  mean = reader.Read<glm::dvec3>();
  this->GridShot = reader.Read<uint8_t>() != 0;
  this->LastWeightEvaluations = static_cast<std::size_t>(reader.Read<uint64_t>());
  reader.ReadVector(this->DirectionalOut);
  if (this->GridShot)
  {
    reader.ReadVector(this->GridOut);
  }
  else
  {
    const std::size_t rows = static_cast<std::size_t>(this->Cover.Grid().ThetaBins());
    this->DirectionalIn.resize(rows);
    this->DirectionalCoupled.resize(rows);
    for (std::size_t row = 0; row < rows; ++row)
    {
      reader.ReadVector(this->DirectionalIn[row]);
      reader.ReadVector(this->DirectionalCoupled[row]);
    }
  }
  return mean;
}

} // namespace sphcover
