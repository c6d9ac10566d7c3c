// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TestFailures.h
 * @brief The failure count of a VTK-style test driver: Check() reports a failed condition on
 * stderr and counts it, Add() counts failures found elsewhere (FailureExpectation::Check),
 * ExitCode() is what the driver returns.
 *
 * CTest runs SphericalCoverCxxTests once per test (one driver per process), so one count per
 * process is one count per test.
 */
#ifndef SPHCOVER_TESTFAILURES_H
#define SPHCOVER_TESTFAILURES_H

#include <cstdlib>
#include <iostream>
#include <string>

namespace TestFailures
{
inline int& Count()
{
  static int count = 0;
  return count;
}

inline void Check(bool condition, const std::string& what)
{
  if (!condition)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Count();
  }
}

inline void Add(int failures)
{
  Count() += failures;
}

inline int ExitCode()
{
  return Count() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
}

#endif
