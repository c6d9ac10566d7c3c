// SPDX-License-Identifier: BSD-3-Clause
// Writes the small OpenEXR seed files of Testing/Fuzz/seeds/exr (not built by CMake; run once):
//   g++ -std=c++17 MakeOpenEXRSeeds.cxx $(pkg-config --cflags --libs OpenEXR) -o make_seeds
//   ./make_seeds seeds/exr
// 8 x 6 images: every compression of OpenEXR 3.1 for float R, G, B + Depth (with the writer's
// vtkOrigin / vtkSpacing attributes), half and uint channels, a luminance-only file, a tiled
// file (with mipmaps), a two-part file and a sub-sampled channel (which the reader refuses).
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfTiledOutputFile.h>
#include <ImfVecAttribute.h>

#include <cstdint>
#include <string>
#include <vector>

namespace
{
constexpr int W = 8;
constexpr int H = 6;

struct Planes
{
  std::vector<float> F[4];
  std::vector<half> Half;
  std::vector<uint32_t> Uint;
  Planes()
  {
    for (auto& p : F)
    {
      p.resize(W * H);
    }
    Half.resize(W * H);
    Uint.resize(W * H);
    for (int k = 0; k < W * H; ++k)
    {
      F[0][k] = 0.01f * k;
      F[1][k] = 1.0f / (k + 1);
      F[2][k] = (k % 3) * 0.5f;
      F[3][k] = 2.0f + k % 7;
      Half[k] = half(0.1f * (k % 5));
      Uint[k] = k * 7u;
    }
  }
};

Imf::FrameBuffer Frame(Planes& p, const char* const* names, Imf::PixelType type, int count)
{
  Imf::FrameBuffer fb;
  for (int c = 0; c < count; ++c)
  {
    char* base = type == Imf::FLOAT ? reinterpret_cast<char*>(p.F[c].data())
      : type == Imf::HALF           ? reinterpret_cast<char*>(p.Half.data())
                                    : reinterpret_cast<char*>(p.Uint.data());
    const size_t size = type == Imf::FLOAT ? 4 : type == Imf::HALF ? 2 : 4;
    fb.insert(names[c], Imf::Slice(type, base, size, size * W));
  }
  return fb;
}

void Scanline(const std::string& file,
  Imf::Compression compression,
  Imf::PixelType type,
  const char* const* names,
  int count,
  bool attributes)
{
  Planes p;
  Imf::Header header(W, H);
  header.compression() = compression;
  for (int c = 0; c < count; ++c)
  {
    header.channels().insert(names[c], Imf::Channel(type));
  }
  if (attributes)
  {
    header.insert("vtkOrigin", Imf::V3dAttribute(Imath::V3d(-1, 2, 0)));
    header.insert("vtkSpacing", Imf::V3dAttribute(Imath::V3d(0.5, 0.5, 1)));
  }
  Imf::OutputFile out(file.c_str(), header);
  out.setFrameBuffer(Frame(p, names, type, count));
  out.writePixels(H);
}
}

int main(int argc, char** argv)
{
  const std::string dir = argc > 1 ? argv[1] : ".";
  const char* rgbd[] = { "R", "G", "B", "Depth" };
  const std::pair<Imf::Compression, const char*> compressions[] = { { Imf::NO_COMPRESSION, "none" },
    { Imf::RLE_COMPRESSION, "rle" },
    { Imf::ZIPS_COMPRESSION, "zips" },
    { Imf::ZIP_COMPRESSION, "zip" },
    { Imf::PIZ_COMPRESSION, "piz" },
    { Imf::PXR24_COMPRESSION, "pxr24" },
    { Imf::B44_COMPRESSION, "b44" },
    { Imf::B44A_COMPRESSION, "b44a" },
    { Imf::DWAA_COMPRESSION, "dwaa" },
    { Imf::DWAB_COMPRESSION, "dwab" } };
  for (const auto& [compression, name] : compressions)
  {
    Scanline(dir + "/float_rgb_depth_" + name + ".exr", compression, Imf::FLOAT, rgbd, 4, true);
  }
  Scanline(dir + "/half_rgb_zip.exr", Imf::ZIP_COMPRESSION, Imf::HALF, rgbd, 3, false);
  Scanline(dir + "/half_rgb_b44.exr", Imf::B44_COMPRESSION, Imf::HALF, rgbd, 3, false);
  Scanline(dir + "/half_rgb_dwaa.exr", Imf::DWAA_COMPRESSION, Imf::HALF, rgbd, 3, false);
  const char* id[] = { "SurfaceId" };
  Scanline(dir + "/uint_id_rle.exr", Imf::RLE_COMPRESSION, Imf::UINT, id, 1, false);
  const char* y[] = { "Y" };
  Scanline(dir + "/half_y_piz.exr", Imf::PIZ_COMPRESSION, Imf::HALF, y, 1, false);
  const char* rg[] = { "R", "G" };
  Scanline(dir + "/float_rg_none.exr", Imf::NO_COMPRESSION, Imf::FLOAT, rg, 2, false);

  { // tiled, with mipmaps
    Planes p;
    Imf::Header header(W, H);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (int c = 0; c < 3; ++c)
    {
      header.channels().insert(rgbd[c], Imf::Channel(Imf::FLOAT));
    }
    header.setTileDescription(Imf::TileDescription(4, 4, Imf::MIPMAP_LEVELS));
    Imf::TiledOutputFile out((dir + "/float_rgb_tiled_mipmap.exr").c_str(), header);
    for (int level = 0; level < out.numLevels(); ++level)
    {
      out.setFrameBuffer(Frame(p, rgbd, Imf::FLOAT, 3));
      out.writeTiles(0, out.numXTiles(level) - 1, 0, out.numYTiles(level) - 1, level);
    }
  }
  { // two parts
    Planes p;
    std::vector<Imf::Header> headers(2, Imf::Header(W, H));
    for (int part = 0; part < 2; ++part)
    {
      headers[part].setName(part == 0 ? "beauty" : "depth");
      headers[part].setType(Imf::SCANLINEIMAGE);
      headers[part].compression() = Imf::ZIPS_COMPRESSION;
      for (int c = part == 0 ? 0 : 3; c < (part == 0 ? 3 : 4); ++c)
      {
        headers[part].channels().insert(rgbd[c], Imf::Channel(Imf::FLOAT));
      }
    }
    Imf::MultiPartOutputFile out((dir + "/float_two_parts.exr").c_str(), headers.data(), 2);
    for (int part = 0; part < 2; ++part)
    {
      Imf::OutputPart o(out, part);
      Imf::FrameBuffer fb;
      for (int c = part == 0 ? 0 : 3; c < (part == 0 ? 3 : 4); ++c)
      {
        fb.insert(
          rgbd[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(p.F[c].data()), 4, 4 * W));
      }
      o.setFrameBuffer(fb);
      o.writePixels(H);
    }
  }
  { // a sub-sampled channel
    Planes p;
    Imf::Header header(W, H);
    header.channels().insert("Y", Imf::Channel(Imf::HALF));
    header.channels().insert("C", Imf::Channel(Imf::HALF, 2, 2));
    Imf::OutputFile out((dir + "/half_subsampled.exr").c_str(), header);
    Imf::FrameBuffer fb;
    fb.insert("Y", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(p.Half.data()), 2, 2 * W));
    fb.insert("C", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(p.Half.data()), 2, 2 * W, 2, 2));
    out.setFrameBuffer(fb);
    out.writePixels(H);
  }
  return 0;
}
