// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Texture.h
 * @brief A material's texture (paper §5.4, "textured surfaces"): an RGB image over a surface's
 * parameter square that multiplies its diffuse reflectance, read from a PNG file.
 *
 * The image covers (u, v) in [0, 1]^2: u runs across its columns from the left, v up its rows
 * from the bottom (the PNG's last row is v near 0). Texel (i, j), i the column and j the row
 * counted from the bottom, is the square [i / W, (i + 1) / W] x [j / H, (j + 1) / H].
 *
 * Two readings, one for each use:
 *  - At(u, v): the bilinear reconstruction between the texel centres, clamped to the edge
 *    texels; what the render multiplies a visible point's diffuse reflectance by (paper §5.3).
 *  - Mean(rect): the exact mean of the texels (as constant squares) over a (u, v) rectangle,
 *    from a summed-area table in O(1); what the propagation gives a characteristic point whose
 *    patch is that rectangle (the texture "convolved with the surface reflectance map", §5.4:
 *    the light a patch reflects is its mean reflectance times its irradiance when the
 *    irradiance is about constant over it, which is what the subdivision's characterisability,
 *    §4.2.4, makes it).
 *
 * Values are linear reflectance factors in [0, 1]. The PNG's values are sRGB-encoded unless the
 * material says "linear" (Data/scenes/FORMAT.md, "texture_encoding").
 *
 * Files: 8- or 16-bit grey or RGB PNG (interlaced or not). Palette images, alpha channels and
 * bit depths below 8 are refused, as are images beyond MaxSide or MaxTexels (refused from the
 * header, before the pixels are allocated) and files that InputFile's policy refuses.
 */
#ifndef SPHCOVER_TEXTURE_H
#define SPHCOVER_TEXTURE_H

#include "math/UVRect.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace sphcover
{

/// How a texture file's values map to reflectance factors.
enum class TextureEncoding
{
  /// The sRGB transfer curve (IEC 61966-2-1), the usual encoding of images.
  Srgb = 0,
  /// Values proportional to the reflectance factor.
  Linear = 1
};

/// "srgb" or "linear".
const char* TextureEncodingName(TextureEncoding encoding);

class Texture
{
public:
  /// Largest width or height accepted.
  static constexpr int MaxSide = 16384;
  /// Largest width x height accepted: 2^22 texels (2048 x 2048) take 4 M x (12 + 24) bytes =
  /// 150 MB with the summed-area table; a larger image is refused from its header.
  static constexpr std::size_t MaxTexels = std::size_t(1) << 22;

  /**
   * Reads a PNG file. Throws InputError(path, "", problem) for a file InputFile refuses, one
   * that is not a PNG, is corrupt or truncated, of a kind not supported (see the file comment)
   * or too large.
   */
  static Texture Load(const std::string& path, TextureEncoding encoding);

  /**
   * A texture of width x height linear RGB texels, row 0 at the bottom (texel (i, j) at index
   * j * width + i). Throws std::invalid_argument for a size below 1 or beyond the limits, a
   * count that does not match, or a value outside [0, 1] (or NaN).
   */
  Texture(int width, int height, std::vector<glm::vec3> texels);

  int Width() const { return this->W; }
  int Height() const { return this->H; }
  /// Texel (i, j), row j from the bottom.
  glm::dvec3 Texel(int i, int j) const;
  /// The bilinear reconstruction at (u, v) (clamped to [0, 1]^2 and to the edge texels).
  glm::dvec3 At(double u, double v) const;
  /// The mean of the texels over the rectangle, each texel a constant square, exactly (up to
  /// rounding); the rectangle is clamped to [0, 1]^2, and a rectangle thinner than a thousandth
  /// of a texel gives the mean over a band of that width about its middle (the line's mean,
  /// but near a texel's edge).
  glm::dvec3 Mean(const UVRect& rect) const;
  /// The mean over the whole image.
  glm::dvec3 Mean() const { return this->Mean(UVRect{ 0.0, 1.0, 0.0, 1.0 }); }

private:
  /// The integral of the texels over [0, x] x [0, y] in texel units (x in [0, W], y in [0, H]).
  glm::dvec3 Integral(double x, double y) const;

  int W = 0;
  int H = 0;
  std::vector<glm::vec3> Texels;
  /// Summed-area table, (W + 1) x (H + 1): entry (i, j) the sum of texels [0, i) x [0, j).
  std::vector<glm::dvec3> Sums;
};

} // namespace sphcover

#endif
