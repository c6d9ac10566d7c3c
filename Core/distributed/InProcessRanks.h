// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file InProcessRanks.h
 * @brief K ranks as threads of one process (a RankShare per thread, math/RankShare.h), for
 * Core's tests and benchmarks: they run a distributed solve's engines without MPI and compare
 * it with the serial one bit for bit.
 */
#ifndef SPHCOVER_INPROCESSRANKS_H
#define SPHCOVER_INPROCESSRANKS_H

#include "math/RankShare.h"

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace sphcover
{

/**
 * K ranks as threads of one process, for Core's tests and benchmarks: Share(r) is rank r's
 * RankShare; each rank's thread calls its engine, and Join waits for all K (a barrier).
 * The object must outlive the shares' use.
 */
class InProcessRanks
{
public:
  explicit InProcessRanks(int ranks)
    : Slots(static_cast<std::size_t>(ranks))
    , Oks(static_cast<std::size_t>(ranks), 1)
  {
  }

  RankShare Share(int rank)
  {
    return RankShare(rank,
      static_cast<int>(this->Slots.size()),
      [this, rank](const std::vector<char>& mine,
        bool ok,
        bool,
        std::vector<std::vector<char>>& all,
        std::vector<char>& oks) { this->Exchange(rank, mine, ok, all, oks); });
  }

  /// Runs body(Share(r), r) on one thread per rank and waits for all of them; `body` must not
  /// throw.
  void Run(const std::function<void(const RankShare&, int)>& body)
  {
    std::vector<std::thread> threads;
    for (int r = 0; r < static_cast<int>(this->Slots.size()); ++r)
    {
      threads.emplace_back([this, r, &body] { body(this->Share(r), r); });
    }
    for (std::thread& thread : threads)
    {
      thread.join();
    }
  }

private:
  void Exchange(int rank,
    const std::vector<char>& mine,
    bool ok,
    std::vector<std::vector<char>>& all,
    std::vector<char>& oks)
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    // Wait until the previous exchange has been read by every rank.
    this->Changed.wait(lock, [this] { return this->Reading == 0; });
    const std::size_t generation = this->Generation;
    this->Slots[static_cast<std::size_t>(rank)] = mine;
    this->Oks[static_cast<std::size_t>(rank)] = ok ? 1 : 0;
    if (++this->Arrived == this->Slots.size())
    {
      this->Arrived = 0;
      this->Reading = this->Slots.size();
      ++this->Generation;
      this->Changed.notify_all();
    }
    else
    {
      this->Changed.wait(lock, [this, generation] { return this->Generation != generation; });
    }
    all = this->Slots;
    oks = this->Oks;
    if (--this->Reading == 0)
    {
      this->Changed.notify_all();
    }
  }

  std::mutex Mutex;
  std::condition_variable Changed;
  std::vector<std::vector<char>> Slots;
  std::vector<char> Oks;
  std::size_t Arrived = 0;
  std::size_t Reading = 0;
  std::size_t Generation = 0;
};

} // namespace sphcover

#endif
