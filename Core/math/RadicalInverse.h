// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RadicalInverse.h
 * @brief The base-2 radical inverse of k (van der Corput): k's binary digits mirrored about the
 * binary point, in [0, 1). With (k + 1/2) / N it makes the N points of Hammersley's set, the
 * deterministic stratified samples of the render's pixels and of the buried-point test.
 */
#ifndef SPHCOVER_RADICALINVERSE_H
#define SPHCOVER_RADICALINVERSE_H

namespace sphcover
{

inline double RadicalInverse(unsigned k)
{
  double result = 0.0;
  double digit = 0.5;
  for (; k != 0; k >>= 1, digit *= 0.5)
  {
    if (k & 1u)
    {
      result += digit;
    }
  }
  return result;
}

} // namespace sphcover

#endif
