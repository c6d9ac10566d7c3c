// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Constants.h
 * @brief The mathematical constants of the method, defined once.
 */
#ifndef SPHCOVER_CONSTANTS_H
#define SPHCOVER_CONSTANTS_H

namespace sphcover
{

constexpr double Pi = 3.14159265358979323846;
constexpr double TwoPi = 2.0 * Pi;
constexpr double HalfPi = 0.5 * Pi;
/// Radians per degree (the scene format's angles are in degrees).
constexpr double Degree = Pi / 180.0;

} // namespace sphcover

#endif
