// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file UVRect.h
 * @brief A rectangle [U0,U1] x [V0,V1] of a patch's parameter domain [0,1]^2.
 *
 * The subdivision of paper §4.3 works on parametric rectangles of the surfaces ("the total
 * parametric range rectangle as the associated area"); the range bounds of paper §4.2 are
 * taken over one such rectangle.
 */
#ifndef SPHCOVER_UVRECT_H
#define SPHCOVER_UVRECT_H

namespace sphcover
{

struct UVRect
{
  double U0 = 0.0;
  double U1 = 1.0;
  double V0 = 0.0;
  double V1 = 1.0;

  /// The whole parameter domain [0,1] x [0,1].
  static constexpr UVRect Unit() { return { 0.0, 1.0, 0.0, 1.0 }; }

  /// True when 0 <= U0 <= U1 <= 1 and 0 <= V0 <= V1 <= 1 (false for NaN bounds). A rectangle
  /// of zero width (a curve or a point of the patch) is valid.
  constexpr bool IsValid() const
  {
    return 0.0 <= this->U0 && this->U0 <= this->U1 && this->U1 <= 1.0 && 0.0 <= this->V0 &&
      this->V0 <= this->V1 && this->V1 <= 1.0;
  }

  constexpr bool IsUnit() const
  {
    return this->U0 == 0.0 && this->U1 == 1.0 && this->V0 == 0.0 && this->V1 == 1.0;
  }

  constexpr double CenterU() const { return 0.5 * (this->U0 + this->U1); }
  constexpr double CenterV() const { return 0.5 * (this->V0 + this->V1); }
};

} // namespace sphcover

#endif
