// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ParallelFor.h
 * @brief The hook through which Core's engines run loops in parallel without depending on
 * VTK: the VTK filters pass a function that runs the chunks with vtkSMPTools::For.
 *
 * A ParallelFor calls `body(begin, end)` on disjoint chunks covering [0, count), possibly
 * concurrently. Engines must give results that do not depend on how the range is chunked.
 */
#ifndef SPHCOVER_PARALLELFOR_H
#define SPHCOVER_PARALLELFOR_H

#include <atomic>
#include <cstddef>
#include <functional>
#include <thread>
#include <vector>

namespace sphcover
{

using ParallelFor = std::function<void(std::size_t count,
  const std::function<void(std::size_t begin, std::size_t end)>& body)>;

/// Runs the whole range in the calling thread.
inline void SequentialFor(std::size_t count,
  const std::function<void(std::size_t begin, std::size_t end)>& body)
{
  if (count > 0)
  {
    body(0, count);
  }
}

/// Runs the range on `threads` std::threads, one item at a time: for Core-only programs
/// (benchmarks, tests) that have no vtkSMPTools.
inline ParallelFor ThreadedFor(int threads)
{
  return [threads](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  {
    std::atomic<std::size_t> next{ 0 };
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
    {
      pool.emplace_back(
        [&]
        {
          for (std::size_t k = next++; k < count; k = next++)
          {
            body(k, k + 1);
          }
        });
    }
    for (std::thread& thread : pool)
    {
      thread.join();
    }
  };
}

/// Reports the fraction done in [0,1]; returns false to abort the work.
using ProgressCallback = std::function<bool(double fraction)>;

} // namespace sphcover

#endif
