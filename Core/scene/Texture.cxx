// SPDX-License-Identifier: BSD-3-Clause
#include "scene/Texture.h"

#include "scene/InputError.h"
#include "scene/InputFile.h"

#include <glm/common.hpp>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

namespace sphcover
{

const char* TextureEncodingName(TextureEncoding encoding)
{
  return encoding == TextureEncoding::Linear ? "linear" : "srgb";
}

namespace
{

/// The sRGB transfer curve's inverse (IEC 61966-2-1): encoded value in [0, 1] -> linear.
double SrgbToLinear(double c)
{
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// What libpng's callbacks share with the reader: the file's bytes, the read position and the
/// first error message. libpng reports errors by longjmp to the setjmp of the phase that called
/// it (ReadHeader, ReadRows); those functions hold no object with a destructor, so the jump
/// skips none (the buffers live in the caller, Texture::Load).
struct PngSource
{
  const std::string* Bytes = nullptr;
  std::size_t Offset = 0;
  char Message[256] = { 0 };
};

void OnPngError(png_structp png, png_const_charp message)
{
  auto* source = static_cast<PngSource*>(png_get_error_ptr(png));
  if (source->Message[0] == 0)
  {
    std::snprintf(source->Message, sizeof(source->Message), "%s", message);
  }
  png_longjmp(png, 1);
}

void OnPngWarning(png_structp, png_const_charp)
{
  // Warnings (an ancillary chunk with a bad CRC, an unknown chunk) do not affect the pixels.
}

void ReadPngBytes(png_structp png, png_bytep data, std::size_t length)
{
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (length > source->Bytes->size() - source->Offset)
  {
    png_error(png, "unexpected end of file");
  }
  std::memcpy(data, source->Bytes->data() + source->Offset, length);
  source->Offset += length;
}

struct PngHeader
{
  png_uint_32 Width = 0;
  png_uint_32 Height = 0;
  int BitDepth = 0;
  int ColorType = 0;
  int Interlace = 0;
};

/// Reads the header up to the first image data. False on a libpng error (message in source).
bool ReadHeader(png_structp png, png_infop info, PngHeader& header)
{
  if (setjmp(png_jmpbuf(png)))
  {
    return false;
  }
  png_read_info(png, info);
  png_get_IHDR(png,
    info,
    &header.Width,
    &header.Height,
    &header.BitDepth,
    &header.ColorType,
    &header.Interlace,
    nullptr,
    nullptr);
  return true;
}

/// Reads every row (all passes of an interlaced image) and the file's end. False on a libpng
/// error (message in source).
bool ReadRows(png_structp png, png_infop info, png_bytepp rows)
{
  if (setjmp(png_jmpbuf(png)))
  {
    return false;
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

struct PngReadDeleter
{
  png_structp Png = nullptr;
  png_infop Info = nullptr;
  ~PngReadDeleter() { png_destroy_read_struct(&this->Png, &this->Info, nullptr); }
};

std::string ColourTypeName(int colorType)
{
  switch (colorType)
  {
    case PNG_COLOR_TYPE_PALETTE:
      return "a palette image";
    case PNG_COLOR_TYPE_GRAY_ALPHA:
      return "a grey image with alpha";
    case PNG_COLOR_TYPE_RGB_ALPHA:
      return "an RGB image with alpha";
    default:
      return "colour type " + std::to_string(colorType);
  }
}

} // namespace

Texture Texture::Load(const std::string& path, TextureEncoding encoding)
{
  const std::string bytes = ReadInputFile(path);
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0)
  {
    throw InputError(path, "", "not a PNG file");
  }
  PngSource source;
  source.Bytes = &bytes;
  PngReadDeleter handles;
  handles.Png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &source, OnPngError, OnPngWarning);
  if (handles.Png)
  {
    handles.Info = png_create_info_struct(handles.Png);
  }
  if (!handles.Png || !handles.Info)
  {
    throw std::bad_alloc();
  }
  png_set_read_fn(handles.Png, &source, ReadPngBytes);
  auto corrupt = [&]()
  { return InputError(path, "", std::string("corrupt PNG file: ") + source.Message); };

  PngHeader header;
  if (!ReadHeader(handles.Png, handles.Info, header))
  {
    throw corrupt();
  }
  if (header.ColorType != PNG_COLOR_TYPE_GRAY && header.ColorType != PNG_COLOR_TYPE_RGB)
  {
    throw InputError(path,
      "",
      "expected an 8- or 16-bit grey or RGB PNG, got " + ColourTypeName(header.ColorType));
  }
  if (header.BitDepth != 8 && header.BitDepth != 16)
  {
    throw InputError(path,
      "",
      "expected an 8- or 16-bit grey or RGB PNG, got " + std::to_string(header.BitDepth) +
        " bits per sample");
  }
  if (header.Width > static_cast<png_uint_32>(MaxSide) ||
    header.Height > static_cast<png_uint_32>(MaxSide) ||
    std::size_t(header.Width) * header.Height > MaxTexels)
  {
    throw InputError(path,
      "",
      "image too large: " + std::to_string(header.Width) + " x " + std::to_string(header.Height) +
        " (at most " + std::to_string(MaxSide) + " on a side and " + std::to_string(MaxTexels) +
        " pixels)");
  }
  const int width = static_cast<int>(header.Width);
  const int height = static_cast<int>(header.Height);
  const int channels = header.ColorType == PNG_COLOR_TYPE_RGB ? 3 : 1;
  const std::size_t bytesPerSample = header.BitDepth / 8;
  const std::size_t rowBytes = std::size_t(width) * channels * bytesPerSample;
  std::vector<png_byte> pixels(rowBytes * height);
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (int r = 0; r < height; ++r)
  {
    rows[static_cast<std::size_t>(r)] = pixels.data() + rowBytes * r;
  }
  if (!ReadRows(handles.Png, handles.Info, rows.data()))
  {
    throw corrupt();
  }

  // Decoding table: every possible sample value to its linear reflectance factor.
  const std::size_t levels = std::size_t(1) << header.BitDepth;
  std::vector<float> decode(levels);
  for (std::size_t k = 0; k < levels; ++k)
  {
    const double c = static_cast<double>(k) / static_cast<double>(levels - 1);
    decode[k] = static_cast<float>(encoding == TextureEncoding::Srgb ? SrgbToLinear(c) : c);
  }
  std::vector<glm::vec3> texels(std::size_t(width) * height);
  for (int r = 0; r < height; ++r)
  {
    const png_byte* row = rows[static_cast<std::size_t>(r)];
    const int j = height - 1 - r; // the PNG's first row is the top: v = 1
    for (int i = 0; i < width; ++i)
    {
      float value[3];
      for (int c = 0; c < channels; ++c)
      {
        const png_byte* sample = row + (std::size_t(i) * channels + c) * bytesPerSample;
        const std::size_t code =
          bytesPerSample == 2 ? (std::size_t(sample[0]) << 8) | sample[1] : sample[0];
        value[c] = decode[code];
      }
      texels[std::size_t(j) * width + i] =
        channels == 3 ? glm::vec3(value[0], value[1], value[2]) : glm::vec3(value[0]);
    }
  }
  return Texture(width, height, std::move(texels));
}

Texture::Texture(int width, int height, std::vector<glm::vec3> texels)
  : W(width)
  , H(height)
  , Texels(std::move(texels))
{
  if (width < 1 || height < 1 || width > MaxSide || height > MaxSide ||
    std::size_t(width) * height > MaxTexels)
  {
    throw std::invalid_argument("Texture: size " + std::to_string(width) + " x " +
      std::to_string(height) + " outside [1, MaxSide] or beyond MaxTexels");
  }
  if (this->Texels.size() != std::size_t(width) * height)
  {
    throw std::invalid_argument("Texture: " + std::to_string(this->Texels.size()) + " texels for " +
      std::to_string(width) + " x " + std::to_string(height));
  }
  for (const glm::vec3& t : this->Texels)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (!(t[c] >= 0.0f && t[c] <= 1.0f))
      {
        throw std::invalid_argument("Texture: a texel value outside [0, 1]");
      }
    }
  }
  const std::size_t stride = std::size_t(width) + 1;
  this->Sums.assign(stride * (std::size_t(height) + 1), glm::dvec3(0.0));
  for (int j = 0; j < height; ++j)
  {
    glm::dvec3 row(0.0);
    for (int i = 0; i < width; ++i)
    {
      row += glm::dvec3(this->Texels[std::size_t(j) * width + i]);
      this->Sums[(std::size_t(j) + 1) * stride + i + 1] =
        this->Sums[std::size_t(j) * stride + i + 1] + row;
    }
  }
}

glm::dvec3 Texture::Texel(int i, int j) const
{
  return glm::dvec3(this->Texels[std::size_t(j) * this->W + i]);
}

glm::dvec3 Texture::At(double u, double v) const
{
  // Texel centres at ((i + 1/2) / W, (j + 1/2) / H); outside the outer centres the edge texel.
  const double x = std::clamp(std::isfinite(u) ? u : 0.0, 0.0, 1.0) * this->W - 0.5;
  const double y = std::clamp(std::isfinite(v) ? v : 0.0, 0.0, 1.0) * this->H - 0.5;
  const double xc = std::clamp(x, 0.0, static_cast<double>(this->W - 1));
  const double yc = std::clamp(y, 0.0, static_cast<double>(this->H - 1));
  const int i0 = std::min(static_cast<int>(xc), this->W - 1);
  const int j0 = std::min(static_cast<int>(yc), this->H - 1);
  const int i1 = std::min(i0 + 1, this->W - 1);
  const int j1 = std::min(j0 + 1, this->H - 1);
  const double fx = xc - i0;
  const double fy = yc - j0;
  return (1.0 - fy) * ((1.0 - fx) * this->Texel(i0, j0) + fx * this->Texel(i1, j0)) +
    fy * ((1.0 - fx) * this->Texel(i0, j1) + fx * this->Texel(i1, j1));
}

glm::dvec3 Texture::Integral(double x, double y) const
{
  // The summed-area table at the whole texels below (x, y), plus the partial column and row
  // and the partial corner texel, each a constant square.
  const int i = std::min(static_cast<int>(x), this->W);
  const int j = std::min(static_cast<int>(y), this->H);
  const double fx = x - i;
  const double fy = y - j;
  const std::size_t stride = std::size_t(this->W) + 1;
  glm::dvec3 sum = this->Sums[std::size_t(j) * stride + i];
  if (fx > 0.0 && i < this->W)
  {
    // Column i, rows [0, j): the table's difference of columns i + 1 and i.
    sum +=
      fx * (this->Sums[std::size_t(j) * stride + i + 1] - this->Sums[std::size_t(j) * stride + i]);
  }
  if (fy > 0.0 && j < this->H)
  {
    sum += fy *
      (this->Sums[(std::size_t(j) + 1) * stride + i] - this->Sums[std::size_t(j) * stride + i]);
  }
  if (fx > 0.0 && fy > 0.0 && i < this->W && j < this->H)
  {
    sum += fx * fy * this->Texel(i, j);
  }
  return sum;
}

glm::dvec3 Texture::Mean(const UVRect& rect) const
{
  const auto clamp01 = [](double t) { return std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0); };
  double u0 = clamp01(rect.U0) * this->W;
  double u1 = clamp01(rect.U1) * this->W;
  double v0 = clamp01(rect.V0) * this->H;
  double v1 = clamp01(rect.V1) * this->H;
  if (u1 < u0)
  {
    std::swap(u0, u1);
  }
  if (v1 < v0)
  {
    std::swap(v0, v1);
  }
  // A rectangle thinner than a thousandth of a texel: the mean along its line (the limit) taken
  // over a band of that width inside the image, so that the differences of the summed-area
  // table (sums up to W H) divided by the area keep about 9 digits.
  constexpr double thinnest = 1e-3;
  const auto widen = [](double& a, double& b, double size)
  {
    if (b - a < thinnest)
    {
      const double mid = 0.5 * (a + b);
      a = std::clamp(mid - 0.5 * thinnest, 0.0, size - thinnest);
      b = a + thinnest;
    }
  };
  widen(u0, u1, this->W);
  widen(v0, v1, this->H);
  const glm::dvec3 sum = this->Integral(u1, v1) - this->Integral(u0, v1) - this->Integral(u1, v0) +
    this->Integral(u0, v0);
  return glm::clamp(sum / ((u1 - u0) * (v1 - v0)), 0.0, 1.0);
}

} // namespace sphcover
