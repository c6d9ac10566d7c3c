// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PatternShift.h
 * @brief A Cranley-Patterson rotation of a stratified sample pattern, from a key alone: the
 * shift in [0, 1)^2 that decorrelates the patterns of neighbouring pixels (the renderer) or
 * nodes (the first bounce of DirectIrradiance.h), so that their sampling errors average out
 * over an area instead of adding up. Deterministic: the same key always gives the same shift,
 * whichever thread asks.
 */
#ifndef SPHCOVER_PATTERNSHIFT_H
#define SPHCOVER_PATTERNSHIFT_H

#include <cstdint>

namespace sphcover
{

/// SplitMix64's finaliser: a bijection of 64-bit integers whose outputs for neighbouring keys
/// are unrelated.
inline uint64_t MixBits(uint64_t x)
{
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// The shift (x, y) in [0, 1)^2 of the pattern with this key.
inline void PatternShift(uint64_t key, double& x, double& y)
{
  const uint64_t a = MixBits(key);
  const uint64_t b = MixBits(a);
  x = static_cast<double>(a >> 11) * 0x1.0p-53;
  y = static_cast<double>(b >> 11) * 0x1.0p-53;
}

} // namespace sphcover

#endif
