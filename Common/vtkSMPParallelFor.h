// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkSMPParallelFor.h
 * @brief Runs Core's parallel loops (sphcover::ParallelFor) with vtkSMPTools, so the filters
 * use whatever SMP backend and thread count the application selected.
 */
#ifndef vtkSMPParallelFor_h
#define vtkSMPParallelFor_h

#include "math/ParallelFor.h"

#include <vtkSMPTools.h>

namespace vtkSMPParallelFor
{
inline sphcover::ParallelFor Make()
{
  return [](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  {
    // Small grains: the work per item (a receiver's pairs, a hemisphere) varies a lot.
    vtkSMPTools::For(vtkIdType(0),
      static_cast<vtkIdType>(count),
      vtkIdType(1),
      [&body](vtkIdType begin, vtkIdType end)
      { body(static_cast<std::size_t>(begin), static_cast<std::size_t>(end)); });
  };
}
}

#endif
