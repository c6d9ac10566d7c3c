// SPDX-License-Identifier: BSD-3-Clause
// The joins that put the ranks' own items back in item order (math/RankShare.h): rank r holds
// items r, r + K, ... (MyItems); ItemsFromRanks, JoinOwnedItems and CombineOverRanks must give
// every rank the serial values whatever K, and refuse a rank's bytes that are not its items'.
#include "distributed/InProcessRanks.h"
#include "math/ByteBuffer.h"
#include "math/RankShare.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

using namespace sphcover;

namespace
{
/// Item k's values: lengths[k] of them, k * 10 + 0, k * 10 + 1, ...
std::vector<int> ValuesOfItem(std::size_t k, std::size_t length)
{
  std::vector<int> values;
  for (std::size_t v = 0; v < length; ++v)
  {
    values.push_back(static_cast<int>(k * 10 + v));
  }
  return values;
}

/// What rank `rank` of `ranks` sends: its items' values in item order.
std::vector<char> BytesOfRank(int rank, int ranks, const std::vector<std::size_t>& lengths)
{
  std::vector<int> values;
  for (const std::size_t k : RankShare::ItemsOf(rank, ranks, lengths.size()))
  {
    const std::vector<int> item = ValuesOfItem(k, lengths[k]);
    values.insert(values.end(), item.begin(), item.end());
  }
  std::vector<char> bytes;
  ByteWriter(bytes).Values(values.data(), values.size());
  return bytes;
}
}

// Items of unequal lengths (none, one, several) come back in item order from 1 to 4 ranks; a
// rank that sends one value too few or too many is refused.
TEST(RankShare, ItemsFromRanksPutsTheRanksItemsBackInOrder)
{
  const std::vector<std::size_t> lengths = { 2, 0, 1, 3, 0, 4, 1 };
  std::vector<int> serial;
  for (std::size_t k = 0; k < lengths.size(); ++k)
  {
    const std::vector<int> item = ValuesOfItem(k, lengths[k]);
    serial.insert(serial.end(), item.begin(), item.end());
  }
  for (int ranks = 1; ranks <= 4; ++ranks)
  {
    std::vector<std::vector<char>> all;
    for (int r = 0; r < ranks; ++r)
    {
      all.push_back(BytesOfRank(r, ranks, lengths));
    }
    EXPECT_EQ(ItemsFromRanks<int>(all, lengths), serial) << ranks << " ranks";
    std::vector<std::vector<char>> fewer = all;
    fewer.back().resize(fewer.back().size() - sizeof(int));
    EXPECT_THROW(ItemsFromRanks<int>(fewer, lengths), std::runtime_error) << ranks << " ranks";
    std::vector<std::vector<char>> more = all;
    more.front().resize(more.front().size() + sizeof(int));
    EXPECT_THROW(ItemsFromRanks<int>(more, lengths), std::runtime_error) << ranks << " ranks";
  }
}

// JoinOwnedItems gives every rank each item's value from its owner (the other ranks' copies
// are wrong on purpose); CombineOverRanks takes the maximum and the sum over the ranks.
TEST(RankShare, OwnedItemsAndCombinationsAreTheSameOnEveryRank)
{
  constexpr int Ranks = 3;
  constexpr std::size_t Items = 8;
  InProcessRanks world(Ranks);
  std::vector<std::vector<double>> owned(Ranks);
  std::vector<std::vector<double>> largest(Ranks);
  std::vector<std::vector<uint64_t>> sums(Ranks);
  world.Run(
    [&](const RankShare& share, int rank)
    {
      std::vector<double> values(Items, -1.0);
      for (const std::size_t k : share.MyItems(Items))
      {
        values[k] = 1.5 * static_cast<double>(k);
      }
      owned[static_cast<std::size_t>(rank)] = JoinOwnedItems(share, values);
      std::vector<double> mine(Items);
      std::vector<uint64_t> counts(Items);
      for (std::size_t k = 0; k < Items; ++k)
      {
        mine[k] = static_cast<double>((k + static_cast<std::size_t>(rank)) % Ranks);
        counts[k] = k * 100 + static_cast<uint64_t>(rank);
      }
      CombineOverRanks(share, mine, [](double a, double b) { return std::max(a, b); });
      CombineOverRanks(share, counts, [](uint64_t a, uint64_t b) { return a + b; });
      largest[static_cast<std::size_t>(rank)] = mine;
      sums[static_cast<std::size_t>(rank)] = counts;
    });
  for (int rank = 0; rank < Ranks; ++rank)
  {
    SCOPED_TRACE(testing::Message() << "rank " << rank);
    for (std::size_t k = 0; k < Items; ++k)
    {
      EXPECT_EQ(owned[static_cast<std::size_t>(rank)][k], 1.5 * static_cast<double>(k));
      EXPECT_EQ(largest[static_cast<std::size_t>(rank)][k], Ranks - 1.0);
      EXPECT_EQ(sums[static_cast<std::size_t>(rank)][k], 3 * k * 100 + 0 + 1 + 2);
    }
  }
}
