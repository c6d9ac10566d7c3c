// SPDX-License-Identifier: BSD-3-Clause
#include "distributed/RowBlockBytes.h"

#include "math/ByteBuffer.h"

#include <cstdint>

namespace sphcover
{
namespace
{
constexpr uint32_t Tag = 0x53524231; // "SRB1"
constexpr uint32_t Version = 2;
}

std::vector<char> PackRowBlock(const SphericalCover::Arrays& block,
  const CullingStatistics& culling)
{
  std::vector<char> bytes;
  bytes.reserve(128 + block.RowOffsets.size() * sizeof(uint64_t) +
    block.Entries.size() * (sizeof(SphericalCover::Entry) + 2 * sizeof(float)) +
    block.Strips.size() * SphericalCover::BytesPerStrip + block.Areas.size() * sizeof(double));
  ByteWriter out(bytes);
  out.Value(Tag);
  out.Value(Version);
  for (const int value :
    { block.ThetaBins, block.PhiBins, block.SamplesTheta, block.SamplesPhi, block.Fill })
  {
    out.Value(static_cast<int32_t>(value));
  }
  out.Value(static_cast<uint8_t>(block.UnoccludedKnown ? 1 : 0));
  for (const uint64_t count : { culling.Candidates,
         culling.BelowTangentPlane,
         culling.BackFacing,
         culling.Kept,
         culling.Pieces,
         culling.Occluders })
  {
    out.Value(count);
  }
  out.Array(block.RowOffsets);
  out.Array(block.Entries);
  out.Array(block.Unoccluded);
  out.Array(block.Strips);
  out.Array(block.StripDepths);
  out.Array(block.Areas);
  out.Array(block.Measures);
  out.Array(block.Layers);
  out.Array(block.Filters);
  out.Array(block.Transmittances);
  return bytes;
}

std::string UnpackRowBlock(const char* bytes,
  std::size_t size,
  SphericalCover::Arrays& block,
  CullingStatistics& culling)
{
  block = SphericalCover::Arrays();
  culling = CullingStatistics();
  ByteReader in(bytes, size);
  uint32_t tag = 0;
  uint32_t version = 0;
  if (!in.Value(tag) || !in.Value(version) || tag != Tag || version != Version)
  {
    return "the bytes are not a row block of this version";
  }
  int32_t grid[5] = { 0, 0, 0, 0, 0 };
  uint8_t unoccludedKnown = 0;
  bool read = true;
  for (int32_t& value : grid)
  {
    read = read && in.Value(value);
  }
  read = read && in.Value(unoccludedKnown);
  for (uint64_t* count : { &culling.Candidates,
         &culling.BelowTangentPlane,
         &culling.BackFacing,
         &culling.Kept,
         &culling.Pieces,
         &culling.Occluders })
  {
    read = read && in.Value(*count);
  }
  read = read && in.Array(block.RowOffsets) && in.Array(block.Entries) &&
    in.Array(block.Unoccluded) && in.Array(block.Strips) && in.Array(block.StripDepths) &&
    in.Array(block.Areas) && in.Array(block.Measures) && in.Array(block.Layers) &&
    in.Array(block.Filters) && in.Array(block.Transmittances);
  if (!read || !in.AtEnd())
  {
    block = SphericalCover::Arrays();
    culling = CullingStatistics();
    return read ? "the row block has bytes left over" : "the row block is truncated";
  }
  block.ThetaBins = grid[0];
  block.PhiBins = grid[1];
  block.SamplesTheta = grid[2];
  block.SamplesPhi = grid[3];
  block.Fill = grid[4];
  block.UnoccludedKnown = unoccludedKnown != 0;
  return std::string();
}
}
