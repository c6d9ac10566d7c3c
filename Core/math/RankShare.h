// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RankShare.h
 * @brief The hook through which Core's engines share independent items among the K processes
 * (MPI ranks) of one solve without depending on MPI or VTK: which items are this rank's
 * (MyItems, Owns) and a join of bytes (Join: every rank's, in rank order, on every rank), with
 * the few typed joins the engines call (ShareItems, JoinOwnedItems, CombineOverRanks,
 * JoinValues). The default RankShare is one process: every item is its own and a join gives
 * back what it is given, so a serial engine reads no further. An engine that merges the joined
 * results in item order gives the serial result bit for bit whatever K.
 * What is distributed beyond that (the cover's rows dealt to the ranks, their bytes, the shared
 * propagation, K ranks as threads for the tests) lives in distributed/, the last stage of Core.
 * The VTK filters give a RankShare over their vtkMultiProcessController (vtkCoverDistribution).
 *
 * Contract: Join is collective (every rank calls it at the same point, as often); a rank that
 * fails still calls it, with `ok` false, so that no rank waits forever, and every rank then
 * learns that one failed (Join returns false). An engine whose Join returns false stops and
 * reports it as RankShare::PeerFailure (the failing rank reports its own problem).
 */
#ifndef SPHCOVER_RANKSHARE_H
#define SPHCOVER_RANKSHARE_H

#include "math/ByteBuffer.h"

#include <algorithm>
#include <cstddef>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace sphcover
{

class RankShare
{
public:
  /// Every rank's bytes and `ok`, in rank order, on every rank (an all-gather); `sameSize`:
  /// every rank gives as many bytes (one collective suffices).
  using AllGather = std::function<void(const std::vector<char>& mine,
    bool ok,
    bool sameSize,
    std::vector<std::vector<char>>& all,
    std::vector<char>& oks)>;

  /// Thrown by an engine on a rank whose Join learnt that another rank failed.
  class PeerFailure : public std::runtime_error
  {
  public:
    PeerFailure()
      : std::runtime_error(Text)
    {
    }
    /// Its message: a caller that reduces the ranks' problems to one prefers any other.
    static constexpr const char* Text = "another rank failed";
  };

  /// One process: every item is this rank's, Join returns the rank's own bytes.
  RankShare() = default;
  /// Rank `rank` of `ranks`, joined through `allGather`. Throws std::invalid_argument for a rank
  /// out of range or no all-gather with more than one rank.
  RankShare(int rank, int ranks, AllGather allGather)
    : ThisRank(rank)
    , RankCount(ranks)
    , Gather(std::move(allGather))
  {
    if (ranks < 1 || rank < 0 || rank >= ranks || (ranks > 1 && !this->Gather))
    {
      throw std::invalid_argument("RankShare: rank " + std::to_string(rank) + " of " +
        std::to_string(ranks) + (this->Gather ? "" : " without an all-gather"));
    }
  }

  int Rank() const { return this->ThisRank; }
  int Ranks() const { return this->RankCount; }
  bool Distributed() const { return this->RankCount > 1; }

  /// The items of [0, count) this rank computes: k = Rank(), Rank() + K, ... Interleaved, so
  /// that neighbouring items, whose costs are alike (nodes of one patch, patches of one
  /// surface), are spread over the ranks and the ranks' loads are balanced without an estimate.
  std::vector<std::size_t> MyItems(std::size_t count) const
  {
    return ItemsOf(this->ThisRank, this->RankCount, count);
  }

  /// Rank `rank`'s items of [0, count) among `ranks` (MyItems of that rank).
  static std::vector<std::size_t> ItemsOf(int rank, int ranks, std::size_t count)
  {
    std::vector<std::size_t> items;
    const std::size_t k = static_cast<std::size_t>(ranks);
    for (std::size_t item = static_cast<std::size_t>(rank); item < count; item += k)
    {
      items.push_back(item);
    }
    return items;
  }

  /// Whether `item` is among this rank's items (MyItems): item mod K = Rank().
  bool Owns(std::size_t item) const
  {
    return item % static_cast<std::size_t>(this->RankCount) ==
      static_cast<std::size_t>(this->ThisRank);
  }

  /// Every rank's `mine`, in rank order, into `all`; false (and `all` empty) when some rank
  /// gave `ok` false. Collective (see the file comment).
  bool Join(const std::vector<char>& mine, bool ok, std::vector<std::vector<char>>& all) const
  {
    return this->JoinBytes(mine, ok, false, all);
  }

  /// Whether every rank gave `ok` true: a verdict only this rank can reach (its own check or
  /// failure), joined so that the ranks go on or stop together. Collective; one process: `ok`.
  bool EveryRankOk(bool ok) const
  {
    std::vector<std::vector<char>> all;
    return this->Join({}, ok, all);
  }

  /// Join when every rank gives as many bytes: one collective instead of two (the per-shot
  /// exchanges of a shared propagation).
  bool JoinSameSize(const std::vector<char>& mine,
    bool ok,
    std::vector<std::vector<char>>& all) const
  {
    return this->JoinBytes(mine, ok, true, all);
  }

private:
  bool JoinBytes(const std::vector<char>& mine,
    bool ok,
    bool sameSize,
    std::vector<std::vector<char>>& all) const
  {
    all.clear();
    if (!this->Distributed())
    {
      if (ok)
      {
        all.push_back(mine);
      }
      return ok;
    }
    std::vector<char> oks;
    this->Gather(mine, ok, sameSize, all, oks);
    for (char rankOk : oks)
    {
      if (!rankOk)
      {
        all.clear();
        return false;
      }
    }
    return true;
  }

  int ThisRank = 0;
  int RankCount = 1;
  AllGather Gather;
};

/**
 * The values in every rank's bytes (ByteWriter::Values of each), concatenated in rank order.
 * Throws std::runtime_error when a rank's bytes are not whole values.
 */
template<typename Value>
std::vector<Value> ValuesOfRanks(const std::vector<std::vector<char>>& all)
{
  std::vector<Value> joinedValues;
  for (const std::vector<char>& bytes : all)
  {
    if (bytes.size() % sizeof(Value) != 0)
    {
      throw std::runtime_error(
        "JoinValues: a rank sent " + std::to_string(bytes.size()) + " bytes, not whole values");
    }
    const std::size_t at = joinedValues.size();
    joinedValues.resize(at + bytes.size() / sizeof(Value));
    ByteReader(bytes).Values(joinedValues.data() + at, bytes.size() / sizeof(Value));
  }
  return joinedValues;
}

/**
 * Every rank's `count` values, concatenated in rank order, on every rank (`sameSize`: every
 * rank gives as many, one collective). Collective; throws RankShare::PeerFailure when a rank
 * failed, std::runtime_error when a rank's bytes are not whole values. One process: a copy.
 */
template<typename Value>
std::vector<Value> JoinValues(const RankShare& share,
  const Value* values,
  std::size_t count,
  bool sameSize = false)
{
  std::vector<char> mine;
  ByteWriter(mine).Values(values, count);
  std::vector<std::vector<char>> all;
  const bool joined = sameSize ? share.JoinSameSize(mine, true, all) : share.Join(mine, true, all);
  if (!joined)
  {
    throw RankShare::PeerFailure();
  }
  return ValuesOfRanks<Value>(all);
}

/**
 * The values of items [0, lengths.size()) in item order, item k's lengths[k] of them, from
 * every rank's bytes in rank order (as Join or a gather gives them): rank r's are the values of
 * its items r, r + K, ... (RankShare::MyItems), in that order, written by ByteWriter::Values.
 * Throws std::runtime_error when a rank's bytes are not exactly its items' values.
 */
template<typename Value>
std::vector<Value> ItemsFromRanks(const std::vector<std::vector<char>>& all,
  const std::vector<std::size_t>& lengths)
{
  const std::size_t count = lengths.size();
  std::vector<std::size_t> offsets(count + 1, 0);
  for (std::size_t item = 0; item < count; ++item)
  {
    offsets[item + 1] = offsets[item] + lengths[item];
  }
  std::vector<Value> values(offsets[count]);
  const std::size_t ranks = all.size();
  for (std::size_t r = 0; r < ranks; ++r)
  {
    ByteReader reader(all[r]);
    bool whole = true;
    for (std::size_t item = r; whole && item < count; item += ranks)
    {
      whole = reader.Values(values.data() + offsets[item], lengths[item]);
    }
    if (!whole || !reader.AtEnd())
    {
      throw std::runtime_error("ItemsFromRanks: rank " + std::to_string(r) + " sent " +
        std::to_string(all[r].size()) + " bytes, not its items' values");
    }
  }
  return values;
}

/**
 * Every item's `lengths[k]` values in item order, on every rank, from each rank's `mine`: the
 * values of its own items (RankShare::MyItems) in that order. Collective; throws
 * RankShare::PeerFailure when a rank failed, std::runtime_error when a rank's values do not
 * match `lengths`. One process: a copy.
 */
template<typename Value>
std::vector<Value> JoinItems(const RankShare& share,
  const std::vector<Value>& mine,
  const std::vector<std::size_t>& lengths)
{
  std::vector<char> bytes;
  ByteWriter(bytes).Values(mine.data(), mine.size());
  std::vector<std::vector<char>> all;
  if (!share.Join(bytes, true, all))
  {
    throw RankShare::PeerFailure();
  }
  return ItemsFromRanks<Value>(all, lengths);
}

/**
 * `values` has one value per item of [0, values.size()), valid on its owner (RankShare::Owns):
 * returns every item's value from its owner, on every rank. Collective; one process: a copy.
 */
template<typename Value>
std::vector<Value> JoinOwnedItems(const RankShare& share, const std::vector<Value>& values)
{
  std::vector<Value> mine;
  for (const std::size_t item : share.MyItems(values.size()))
  {
    mine.push_back(values[item]);
  }
  return JoinItems(share, mine, std::vector<std::size_t>(values.size(), 1));
}

/**
 * Every rank's `values` (as many on every rank) combined element by element, into `values` on
 * every rank: values[k] = combine(... combine(combine(Value(), rank 0's), rank 1's) ..., rank
 * K - 1's). Gives the same on every rank whatever K when `combine` is associative and
 * commutative on the values given (a maximum of non-negative values, an integer sum).
 * Collective; one process: nothing changes.
 */
template<typename Value, typename Combine>
void CombineOverRanks(const RankShare& share, std::vector<Value>& values, const Combine& combine)
{
  if (!share.Distributed())
  {
    return;
  }
  const std::size_t count = values.size();
  const std::vector<Value> all = JoinValues(share, values.data(), count, true);
  std::fill(values.begin(), values.end(), Value());
  for (std::size_t at = 0; at < all.size(); at += count)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      values[k] = combine(values[k], all[at + k]);
    }
  }
}

/**
 * `values[k]` for every k of [0, count) on every rank: `computeMine(items)` computes those of
 * this rank's items (RankShare::MyItems; returns false when aborted), and the ranks' values are
 * joined. `Value` is trivially copyable. Returns false when this rank aborted; throws what
 * computeMine threw (after joining, so no rank waits), RankShare::PeerFailure when another
 * rank failed, and std::runtime_error when a rank's bytes are not its items' values
 * (ItemsFromRanks). One process: computeMine gets every item, nothing is copied.
 */
template<typename Value, typename ComputeMine>
bool ShareItems(const RankShare& share,
  std::size_t count,
  std::vector<Value>& values,
  const ComputeMine& computeMine)
{
  static_assert(std::is_trivially_copyable<Value>::value, "ShareItems copies values as bytes");
  const std::vector<std::size_t> items = share.MyItems(count);
  if (!share.Distributed())
  {
    return computeMine(items);
  }
  bool ok = false;
  std::exception_ptr failure;
  try
  {
    ok = computeMine(items);
  }
  catch (...)
  {
    failure = std::current_exception();
  }
  std::vector<char> mine;
  ByteWriter writer(mine);
  for (std::size_t k = 0; ok && k < items.size(); ++k)
  {
    writer.Value(values[items[k]]);
  }
  std::vector<std::vector<char>> all;
  const bool everyRankOk = share.Join(mine, ok, all);
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  if (!ok)
  {
    return false;
  }
  if (!everyRankOk)
  {
    throw RankShare::PeerFailure();
  }
  const std::vector<Value> joined = ItemsFromRanks<Value>(all, std::vector<std::size_t>(count, 1));
  std::copy(joined.begin(), joined.end(), values.begin());
  return true;
}

} // namespace sphcover

#endif
