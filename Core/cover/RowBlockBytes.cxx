// SPDX-License-Identifier: BSD-3-Clause
#include "cover/RowBlockBytes.h"

#include <cstdint>
#include <cstring>
#include <type_traits>

namespace sphcover
{
namespace
{
constexpr uint32_t Tag = 0x53524231; // "SRB1"
constexpr uint32_t Version = 2;

/// Appends raw values to the buffer.
class Writer
{
public:
  explicit Writer(std::vector<char>& bytes)
    : Bytes(bytes)
  {
  }
  template<typename T>
  void Value(const T& value)
  {
    static_assert(std::is_trivially_copyable<T>::value, "raw bytes only");
    const char* raw = reinterpret_cast<const char*>(&value);
    this->Bytes.insert(this->Bytes.end(), raw, raw + sizeof(T));
  }
  template<typename T>
  void Array(const std::vector<T>& values)
  {
    static_assert(std::is_trivially_copyable<T>::value, "raw bytes only");
    this->Value(static_cast<uint64_t>(values.size()));
    const char* raw = reinterpret_cast<const char*>(values.data());
    this->Bytes.insert(this->Bytes.end(), raw, raw + values.size() * sizeof(T));
  }

private:
  std::vector<char>& Bytes;
};

/// Reads raw values from the buffer; false once a value would run past its end.
class Reader
{
public:
  Reader(const char* bytes, std::size_t size)
    : Next(bytes)
    , Left(size)
  {
  }
  template<typename T>
  bool Value(T& value)
  {
    if (this->Left < sizeof(T))
    {
      return false;
    }
    std::memcpy(&value, this->Next, sizeof(T));
    this->Next += sizeof(T);
    this->Left -= sizeof(T);
    return true;
  }
  template<typename T>
  bool Array(std::vector<T>& values)
  {
    uint64_t count = 0;
    if (!this->Value(count) || count > this->Left / sizeof(T))
    {
      return false;
    }
    values.resize(static_cast<std::size_t>(count));
    if (count == 0)
    {
      return true; // an empty vector's data() may be null, which memcpy must not get
    }
    std::memcpy(values.data(), this->Next, values.size() * sizeof(T));
    this->Next += values.size() * sizeof(T);
    this->Left -= values.size() * sizeof(T);
    return true;
  }
  bool AtEnd() const { return this->Left == 0; }

private:
  const char* Next;
  std::size_t Left;
};
}

std::vector<char> PackRowBlock(const SphericalCover::Arrays& block,
  const CullingStatistics& culling)
{
  std::vector<char> bytes;
  bytes.reserve(128 + block.RowOffsets.size() * sizeof(uint64_t) +
    block.Entries.size() * (sizeof(SphericalCover::Entry) + 2 * sizeof(float)) +
    block.Strips.size() * SphericalCover::BytesPerStrip + block.Areas.size() * sizeof(double));
  Writer out(bytes);
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
  Reader in(bytes, size);
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
