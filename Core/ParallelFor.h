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

#include <cstddef>
#include <functional>

namespace sphcover
{

using ParallelFor =
  std::function<void(std::size_t count, const std::function<void(std::size_t begin, std::size_t end)>& body)>;

/// Runs the whole range in the calling thread.
inline void SequentialFor(
  std::size_t count, const std::function<void(std::size_t begin, std::size_t end)>& body)
{
  if (count > 0)
  {
    body(0, count);
  }
}

/// Reports the fraction done in [0,1]; returns false to abort the work.
using ProgressCallback = std::function<bool(double fraction)>;

} // namespace sphcover

#endif
